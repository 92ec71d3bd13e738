"""The visco-elastic contact (ViscElMat, Ip2_ViscElMat_ViscElMat_ViscElPhys,
Law2_ScGeom_ViscElPhys_Basic) against Yade 2023.02a on the same scenes (viscoelastic_yade.py:
the young/en, tc and kn forms, walls, facets, boxes, fixed spheres, rolling resistance,
MatchMakers, lubrication), and its errors."""
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom_ViscElPhys_Basic, MatchMaker, NewtonIntegrator, Scene, ViscElMat, sphere)

TWINS = Path(__file__).parents[1] / "yade_twins" / "laws"  # the scripts Yade and Talus both run
YADE = shutil.which("yade")


def scenes(cmd, env=None):
    done = subprocess.run([*cmd, "viscoelastic_yade.py"], capture_output=True, text=True, timeout=600, cwd=TWINS, env=env)
    lines = [line for line in done.stdout.splitlines() if line.startswith("JSON ")]
    assert lines, f"{cmd[0]} exited {done.returncode}:\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}"
    return json.loads(lines[0][5:])


@pytest.fixture(scope="module")
def talus_scenes(build_dir):
    return scenes([str(build_dir / "bin" / "talus"), "run", "-j", "1"])


def test_dashpot_from_restitution_is_yades(talus_scenes):
    # Measured with Yade 2023.02a: two spheres E 1e7, r 1 cm, density 2500: kn = E r, ks = 0.3 kn,
    # cs = 0 and cn for en = .1, .3, .5, .7, .9, .99 (its Newton iteration stops at 1% in en).
    got = np.array(talus_scenes["dashpots"])
    assert np.allclose(got[:, 2], 1e5, rtol=1e-15) and np.allclose(got[:, 4], 3e4, rtol=1e-15)
    assert np.all(got[:, 5] == 0)
    assert np.allclose(got[:, 3], [56.754, 22.748, 11.666, 5.5313, 1.45673, 0.145673], rtol=5e-5)


@pytest.mark.skipif(YADE is None, reason="yade is not installed (apt-get install yade)")
def test_scenes_equal_yades(talus_scenes):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    theirs = scenes([YADE, "-n", "-j1", "-x"], env)
    assert set(theirs) == set(talus_scenes)
    for name, rows in theirs.items():
        ours, rows = np.array(talus_scenes[name], float), np.array(rows, float)
        assert ours.shape == rows.shape, name
        # Each column (position, velocity, angular velocity component, parameter) to round-off
        # relative to its largest value.
        scale = np.abs(rows).max(axis=0)
        scale[scale == 0] = 1
        assert np.all(np.abs(ours - rows) <= 1e-11 * scale), name


def pair(S, *materials, physics=None):
    """Two touching spheres of the given materials, the visco-elastic loop (``physics``: its Ip2)."""
    ids = [S.materials.append(m) for m in materials]
    S.bodies.append([sphere((0, 0, 0), 0.01, material=ids[0]), sphere((0, 0, 0.0199), 0.01, material=ids[-1])])
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [physics or Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]),
                 NewtonIntegrator(damping=0)]
    S.dt = 1e-6
    return ids


def test_materials_of_different_forms_cannot_meet():
    S = Scene()
    pair(S, ViscElMat(tc=1e-3, en=0.5, et=0.5, label="a"), ViscElMat(young=1e7, en=0.5, label="b"))
    with pytest.raises(RuntimeError, match=r"same set of tc, en.*bodies 0 and 1, materials 'a' and 'b'"):
        S.step()


def test_young_form_needs_a_restitution():
    S = Scene()
    pair(S, ViscElMat(young=1e7, label="a"))
    with pytest.raises(RuntimeError, match="needs en .or cn and cs. besides young"):
        S.step()


def test_matchmaker_without_the_pair_is_an_error():
    S = Scene()
    ids = pair(S, ViscElMat(tc=1e-3, en=0.5, et=0.5), ViscElMat(tc=1e-3, en=0.5, et=0.5),
               physics=Ip2_ViscElMat_ViscElMat_ViscElPhys(en=MatchMaker(matches=((5, 6, 0.3),))))
    with pytest.raises(RuntimeError, match="MatchMaker .* has no value for this pair"):
        S.step()
    assert ids == [0, 1]


def test_matchmaker_algorithms():
    m = MatchMaker(algo="harmAvg", matches=((1, 2, 0.5),))
    assert m(2, 1) == 0.5 and m(0, 1, 1.0, 3.0) == 1.5
    assert MatchMaker(algo="min")(0, 0, 2, 3) == 2 and MatchMaker(algo="max")(0, 0, 2, 3) == 3
    assert MatchMaker()(0, 0, 2, 3) == 2.5 and MatchMaker(algo="zero")(0, 0) == 0
    with pytest.raises(ValueError, match="values required"):
        MatchMaker(algo="avg")(0, 1)
    with pytest.raises(ValueError, match="not recognized"):
        MatchMaker(algo="median")
    assert float(MatchMaker(algo="val", val=0.3)) == 0.3
    with pytest.raises(TypeError, match="gives a value per pair"):
        float(MatchMaker(algo="val", val=0.3, matches=((0, 1, 0.2),)))
