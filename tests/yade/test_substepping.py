"""O.subStepping, O.subStep, engines set during a step (O._nextEngines) and a step a PyRunner
error interrupted behave as in Yade 2023.02a."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import ForceResetter, NewtonIntegrator, PyRunner, Scene, sphere
from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_substepping_and_interrupted_steps_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "substepping_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert theirs["errors"] == ["PyRunner error."] * 3
    # After the error Yade's O.subStep is 0 (its next step runs the step's engines again from
    # the first); Talus's is the sub-step after the PyRunner that raised, where it goes on.
    interrupted = [row for row in ours["trace"] if row[0] == "after run"]
    assert interrupted and all(row[2] == 3 for row in interrupted)
    for row in interrupted + [row for row in theirs["trace"] if row[0] == "after run"]:
        row[2] = None
    assert [row[:6] for row in ours["trace"]] == [row[:6] for row in theirs["trace"]]
    assert np.allclose([row[6] for row in ours["trace"]], [row[6] for row in theirs["trace"]], rtol=0, atol=1e-14)


def test_an_error_in_another_engine_stops_the_scene():
    """Only a PyRunner's error leaves the scene whole: after a C++ engine's, further steps are
    refused until a checkpoint is loaded."""
    scene = Scene()
    scene.bodies.append(sphere((0, 0, 0), 1))
    scene.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -10))]
    scene.dt = 0.1
    scene.saveTmp("ok")
    scene.bodies[0].state.mass = 0.0    # a dynamic body without mass: NewtonIntegrator throws
    with pytest.raises(Exception):
        scene.step()
    with pytest.raises(RuntimeError, match="cannot continue"):
        scene.step()
    scene.loadTmp("ok")
    assert scene.subStep == -1
    scene.step()
    assert scene.iter == 1


def test_a_pyrunner_error_is_finished_by_the_next_step():
    scene = Scene()
    scene.bodies.append(sphere((0, 0, 0), 1))
    calls = []
    scene.engines = [ForceResetter(), PyRunner(command=lambda: 1 / 0, initRun=True),
                     PyRunner(command=lambda: calls.append(scene.iter), initRun=True),
                     NewtonIntegrator(gravity=(0, 0, -10), damping=0)]
    scene.dt = 0.1
    with pytest.raises(ZeroDivisionError):
        scene.step()
    assert (scene.iter, scene.subStep, calls) == (0, 2, [])
    scene.engines[1].dead = True
    scene.step()                       # the rest of step 0: the engines after the one that raised
    assert (scene.iter, scene.subStep, calls) == (1, -1, [0])
    assert scene.bodies[0].state.vel[2] == pytest.approx(-1.0)
