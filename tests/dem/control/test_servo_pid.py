"""Yade's ServoPIDController (combined with a rotation, as in Yade's PIDController.py) moves its
plate as Yade 2023.02a's."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import ServoPIDController
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "control"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_servo_pid_controller_matches_yade():
    ours, theirs = (np.array(twin.run(TWINS / "servo_pid_side_by_side.py", {}, who)) for who in ("talus", "yade"))
    assert ours.shape == theirs.shape
    assert np.ptp(theirs[:, 9]) > 0.5 and np.abs(theirs[:, 8]).max() > 2e4   # the speed and the force changed
    scale = np.maximum(np.abs(theirs).max(axis=0), 1e-300)
    assert np.all(np.abs(ours - theirs) <= 1e-9 * scale)


def test_zero_axis_is_an_error():
    from talus.dem import O, sphere
    O.reset()
    O.bodies.append(sphere((0, 0, 0), 1))
    O.engines = [ServoPIDController(ids=[0], target=1.0)]
    O.dt = 1
    with pytest.raises(ValueError, match="ServoPIDController: axis must be a non-zero"):
        O.step()
