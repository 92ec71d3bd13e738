"""O.dynDt (Yade's switch of the time stepper) and a negative O.dt as in Yade 2023.02a. Without
it a script's `O.dt = 1e-4; O.dynDt = False` kept the GlobalStiffnessTimeStepper in charge and
ran at its (16 times larger) step: FluidCouplingPFV/oedometer.py blew up."""
from pathlib import Path

import pytest

from talus.dem import ForceResetter, GlobalStiffnessTimeStepper, NewtonIntegrator, Scene
from talus import twin

HERE = Path(__file__).parent


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_dyndt_as_yade():
    ours, theirs = (twin.run(HERE / "side_by_side" / "dyndt_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert ours["trace"] == theirs["trace"]
    steps = {row[0]: row[1] for row in ours["trace"]}
    assert steps["overridden while active"] != 1e-6 and steps["kept"] == 1e-6


def test_dyndt_switches_the_stepper():
    scene = Scene()
    stepper = GlobalStiffnessTimeStepper()
    scene.engines = [ForceResetter(), stepper, NewtonIntegrator()]
    assert scene.dynDt
    scene.dynDt = False
    assert not stepper.active and not scene.dynDt
    scene.dt = -1
    assert stepper.active and scene.dynDt
    scene.engines = [ForceResetter(), GlobalStiffnessTimeStepper(), GlobalStiffnessTimeStepper(), NewtonIntegrator()]
    with pytest.raises(RuntimeError, match="Multiple"):
        scene.dynDt = False
