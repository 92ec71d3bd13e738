"""Yade's Peri3dController against Yade 2023.02a on a dense periodic packing
(peri3d_side_by_side.py), and its input checks."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import Peri3dController
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "periodic"  # the scripts Yade and Talus both run
needs_yade = pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
STRESS, STRAIN, PROGRESS, TRSF = slice(0, 6), slice(6, 12), 12, slice(13, 22)


def _both(case):
    return [twin.run(TWINS / "peri3d_side_by_side.py", {"case": case}, who, timeout=600) for who in ("talus", "yade")]


@needs_yade
def test_strain_paths_match_yade():
    ours, theirs = _both("strain")
    a, b = np.array(ours["rows"]), np.array(theirs["rows"])
    assert a.shape == b.shape and ours["iter"] == theirs["iter"] < 1500 and ours["dead"] and theirs["dead"]
    assert ours["xyPath"] == theirs["xyPath"]                           # paths normalised in place alike
    assert np.ptp(b[:, 11]) > 3e-3 and b[-1, PROGRESS] >= 1             # the shear went back and forth
    for part in (STRAIN, TRSF):
        assert np.abs(a[:, part] - b[:, part]).max() < 1e-12
    assert np.abs(a[:, PROGRESS] - b[:, PROGRESS]).max() < 1e-12
    # The stress depends on when the cell moves within a step: Yade deforms it at the start of
    # the step (before the contacts), Talus at the end of the NewtonIntegrator, so the forces
    # lag one step of cell deformation behind Yade's.
    assert np.abs(a[:, STRESS] - b[:, STRESS]).max() < 2e-3 * np.abs(b[:, STRESS]).max()


@needs_yade
@pytest.mark.xfail(strict=True, reason="Talus deforms the periodic cell at the end of the step, Yade at its start: "
                                       "the stresses differ by ~5e-4 and the stress predictor then takes other turns")
def test_stress_control_matches_yade():
    ours, theirs = _both("stress")
    assert ours["hooks"] == theirs["hooks"] and ours["iter"] == theirs["iter"]
    a, b = np.array(ours["rows"]), np.array(theirs["rows"])
    assert a.shape == b.shape
    scale = np.maximum(np.abs(b).max(axis=0), 1e-300)
    assert np.all(np.abs(a - b) <= 1e-9 * scale)


@pytest.mark.parametrize("kwargs, message", [
    ({"goal": (1, 2, 3)}, "goal must be 6 finite numbers"),
    ({"nSteps": 0}, "nSteps must be positive"),
    ({"xxPath": []}, "xxPath must be a non-empty list"),
    ({"xyPath": [(1, 2, 3)]}, "xyPath must be a non-empty list"),
])
def test_bad_parameters_are_errors(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Peri3dController(**kwargs)


def test_paths_must_advance_and_the_scene_be_periodic():
    from talus.dem import O, sphere
    O.reset()
    O.bodies.append(sphere((0, 0, 0), 1))
    O.dt = 1e-3
    O.engines = [Peri3dController(goal=(1e-3,) * 6)]
    with pytest.raises(RuntimeError, match="Peri3dController: the scene is not periodic"):
        O.step()
    O.reset()
    O.periodic = True
    O.dt = 1e-3
    O.engines = [Peri3dController(goal=(1e-3,) * 6, yyPath=[(2, 1), (1, 2)])]
    with pytest.raises(RuntimeError, match="yyPath must increase strictly"):
        O.step()


def test_without_done_hook_it_dies_and_pauses_and_keeps_its_state_in_checkpoints(tmp_path):
    from talus.dem import O
    O.reset()
    O.periodic = True
    O.cell.setBox(1, 1, 1)
    O.dt = 1e-3
    O.engines = [Peri3dController(goal=(1e-2, 0, 0, 0, 0, 2e-2), nSteps=8, label="p3d")]
    O.run(50, True)
    p3d = O.engines[0]
    assert O.iter == 8 and p3d.dead and p3d.progress == 1      # 8 steps of 1/8: exact
    assert np.allclose(p3d.strain, (1e-2, 0, 0, 0, 0, 2e-2))
    # no NewtonIntegrator moves the cell: the velocity gradient is the path's (xy: half the engineering rate)
    assert np.allclose(O.cell.velGrad, [[1.25, 1.25, 0], [1.25, 0, 0], [0, 0, 0]], rtol=1e-12)
    O.save(str(tmp_path / "p3d.pkl"))
    O.load(str(tmp_path / "p3d.pkl"))
    again = O.engines[0]
    assert again.dead and again.progress == p3d.progress and np.array_equal(again.strain, p3d.strain)
    assert again.xyPath == p3d.xyPath and list(again.pathsCounter) == list(p3d.pathsCounter)
