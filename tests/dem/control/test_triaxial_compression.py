"""Yade's triaxial engines: TriaxialCompressionEngine (its state machine, files and checkpoint),
ThreeDTriaxialEngine and TriaxialStateRecorder, side by side with Yade 2023.02a on the same
packing (triax_side_by_side.py) and on their own."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from talus.dem import *  # noqa: F401,F403
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "control"  # the scripts Yade and Talus both run
yade_missing = pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")


def records(phase, steps):
    """The TriaxialStateRecorder rows (iteration s11 s22 s33 e11 e22 e33 unb porosity kineticE)
    of the same run in Talus and in Yade."""
    params = {"phase": phase, "steps": steps}
    ours, theirs = (twin.run(TWINS / "triax_side_by_side.py", params, p) for p in ("talus", "yade"))
    return np.array(ours["rows"]), np.array(theirs["rows"]), ours, theirs


def relative_gap(a, b, columns):
    return np.max(np.abs(a[:, columns] - b[:, columns])) / np.max(np.abs(b[:, columns]))


@yade_missing
def test_deviatoric_loading_matches_yade():
    # From Yade's packing at the end of the compaction, 400 steps of loading: top and bottom at
    # the strain rate, lateral walls at 50 kPa. Stresses and strains to ~1e-8 (the packing's
    # own chaos amplifies rounding beyond that).
    a, b, ours, theirs = records("loading", 400)
    assert a.shape == b.shape == (40, 10) and ours["state"] == theirs["state"] == 3
    assert np.array_equal(a[:, 0], b[:, 0])
    assert b[-1, 5] < -1e-3                            # the sample was shortened
    assert relative_gap(a, b, [1, 2, 3]) < 1e-7
    assert relative_gap(a, b, [4, 5, 6]) < 1e-8
    assert relative_gap(a, b, [8]) < 1e-10


@yade_missing
def test_isotropic_compaction_matches_yade():
    # triax-basic's compaction by the walls (max_vel 10) from makeCloud(seed=7): the first 100
    # steps, up to where the packing's chaos takes over (1e-4 by step 150). Row 0 is left out:
    # before the first step only rounding-size contacts touch the walls.
    a, b, _, _ = records("compaction", 100)
    assert a.shape == b.shape == (10, 10)
    assert b[-1, 4] < -0.1                             # the walls did compact the sample
    assert relative_gap(a[1:], b[1:], [1, 2, 3]) < 1e-6
    assert relative_gap(a[1:], b[1:], [4, 5, 6, 8]) < 1e-9


@yade_missing
def test_three_d_triaxial_engine_matches_yade():
    # x and z under stress control, y strained at a rate relaxing towards 1/s.
    a, b, _, _ = records("threeD", 300)
    assert b[-1, 5] < -0.05
    assert relative_gap(a, b, [1, 2, 3]) < 1e-7
    assert relative_gap(a, b, [4, 5, 6]) < 1e-9


def packed_scene(**engine):
    """The stored compacted packing between its walls, with a TriaxialCompressionEngine."""
    stored = json.loads((TWINS / "triax_packing.json").read_text())
    scene = Scene()
    scene.materials.append(FrictMat(young=15e6, poisson=.4, frictionAngle=math.radians(30), density=2600,
                                    label="spheres"))
    scene.materials.append(FrictMat(young=15e6, poisson=.4, frictionAngle=0, density=0, label="walls"))
    scene.bodies.append([sphere(c, r, material="spheres") for c, r in stored["spheres"]])
    ids = scene.bodies.append(aabbWalls(stored["walls"], material="walls"))
    triax = TriaxialCompressionEngine(**dict(dict(zip(
        ("wall_left_id", "wall_right_id", "wall_bottom_id", "wall_top_id", "wall_back_id", "wall_front_id"), ids)),
        internalCompaction=False, max_vel=10, **engine))
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                     [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     GlobalStiffnessTimeStepper(timeStepUpdateInterval=100), triax, NewtonIntegrator(damping=.4)]
    return scene, triax


def test_unloading_then_loading_with_the_autosaved_state(tmp_path, monkeypatch):
    # Compacted at 50 kPa, asked for 60 then 40 kPa: compaction, unloading, loading. Entering
    # each of the last two, Yade's files are written; O.reload() comes back to the last one.
    monkeypatch.chdir(tmp_path)
    scene, triax = packed_scene(sigmaIsoCompaction=-60e3, sigmaLateralConfinement=-40e3, strainRate=0.05,
                                StabilityCriterion=0.01, frictionAngleDegree=20, Key="t")
    seen = []
    while triax.currentState != 3:
        assert scene.iter < 20000, f"still in state {triax.currentState}"
        scene.run(20)
        if not seen or seen[-1] != triax.currentState:
            seen.append(triax.currentState)
    assert seen[-3:] == [1, 2, 3]
    assert triax.sigmaIsoCompaction == -40e3 and triax.sigma_iso == -40e3      # Yade's unloading sets both
    assert abs(triax.meanStress + 40e3) < 0.005 * 40e3
    assert not triax.wall_top_activated and not triax.wall_bottom_activated and not triax.internalCompaction
    # friction of the loading phase on the contacts between spheres
    assert np.isclose(scene.materials[0].frictionAngle, math.radians(20))
    stems = sorted(p.stem for p in tmp_path.glob("t_*.xml"))
    assert [s.split("_")[1] for s in stems] == ["Compacted", "Unloaded"] and stems[1].endswith("_3")
    spheres = np.loadtxt(tmp_path / (stems[1] + ".spheres"))
    assert spheres.shape == (300, 4)
    saved_iter = int(stems[1].split("_")[2])
    # loading: top and bottom approach each other, the strains restarted at the transition
    h0 = triax.height0
    scene.run(400 + (1 - scene.iter) % 10)     # the last step one where the strains are computed
    assert triax.strain[1] == pytest.approx(math.log(triax.height / h0))
    assert triax.strain[1] < -1e-4 and triax.currentStrainRate > 0
    scene.reload()
    again = scene.engines[4]
    assert scene.iter == saved_iter and again.currentState == 3 and again.height0 == pytest.approx(h0)
    assert not again.wall_top_activated and again.sigmaLateralConfinement == -40e3


def test_no_files_and_stop_in_limbo(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene, triax = packed_scene(sigmaIsoCompaction=-50e3, sigmaLateralConfinement=-50e3, noFiles=True,
                                autoCompressionActivation=False)
    scene.run(2000)
    assert triax.currentState == 1        # without autoCompressionActivation the compaction goes on
    assert list(tmp_path.iterdir()) == []


def test_recorder_writes_yades_columns(tmp_path):
    scene, triax = packed_scene(sigmaIsoCompaction=-50e3, sigmaLateralConfinement=-50e3, noFiles=True)
    path = tmp_path / "WallStresses"
    path.write_text("old line\n")
    engines = scene.engines
    scene.engines = engines[:5] + [TriaxialStateRecorder(iterPeriod=20, file=str(path))] + engines[5:]
    scene.run(41)
    lines = path.read_text().splitlines()
    assert lines[0] == "old line"        # appended to (truncate=False); no header in a non-empty file
    rows = np.array([[float(x) for x in l.split()] for l in lines[1:]])
    assert rows[:, 0].tolist() == [0, 20, 40]
    assert rows[-1, 2] == pytest.approx(triax.stress(3)[1])
    assert rows[-1, 8] == pytest.approx(triax.porosity, rel=1e-6)   # Yade's 1.3333333 for 4/3
    with pytest.raises(ValueError, match="file is empty"):
        scene.engines = [TriaxialStateRecorder(iterPeriod=1)] + engines
        scene.run(1)


def test_wall_ids_are_checked():
    scene, triax = packed_scene(sigmaIsoCompaction=-50e3, sigmaLateralConfinement=-50e3, noFiles=True)
    triax.wall_top_id = 0   # a sphere
    with pytest.raises(ValueError, match="wall_top_id = 0"):
        scene.run(1)


@yade_missing
def test_triaxial_test_preprocessor_matches_yade():
    # Yade's TriaxialTest on the stored packing (importFilename): the same scene (walls 0-5,
    # engines, first step, masses from `density`), then 200 steps of its compaction.
    ours, theirs = (twin.run(TWINS / "triaxial_test_side_by_side.py", {"steps": 200}, p) for p in ("talus", "yade"))
    for key in ("engines", "walls", "state", "mass"):
        assert ours[key] == theirs[key], key
    assert ours["dt0"] == pytest.approx(theirs["dt0"], rel=1e-14)
    assert ours["dt"] == pytest.approx(theirs["dt"], rel=1e-12)
    a, b = np.array(ours["stress"]), np.array(theirs["stress"])
    assert np.max(np.abs(a - b)) < 1e-9 * np.max(np.abs(b)) and np.max(np.abs(b)) > 5e4
    assert np.max(np.abs(np.array(ours["pos"]) - theirs["pos"])) < 1e-10
    assert np.max(np.abs(np.array(ours["strain"]) - theirs["strain"])) < 1e-12


def test_triaxial_test_generates_a_file_that_loads(tmp_path):
    path = tmp_path / "triax.xml"
    TriaxialTest(numberOfGrains=100, noFiles=True, radiusMean=0.05, seed=3).generate(str(path))
    scene = Scene()
    scene.load(str(path))
    assert len(scene.bodies) == 106 and type(scene.engines[4]).__name__ == "TriaxialCompressionEngine"
    assert scene.bodies[6].state.mass == pytest.approx(4 / 3 * math.pi * scene.bodies[6].shape.radius ** 3 * 2600)
    scene.run(50)
    assert scene.engines[4].currentState == 1
    with pytest.raises(TypeError, match="numberOfGrain"):
        TriaxialTest(numberOfGrain=10)
    with pytest.raises(ValueError, match="facetWalls"):
        TriaxialTest(facetWalls=True, numberOfGrains=10).load()
