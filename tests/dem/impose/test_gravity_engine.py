"""GravityEngine moves bodies and books gravWork as Yade 2023.02a's does."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import GravityEngine, NewtonIntegrator, Scene, sphere, ForceResetter
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_gravity_engine_matches_yade():
    ours, theirs = (np.array(twin.run(TWINS / "gravity_engine_side_by_side.py", {}, who)) for who in ("talus", "yade"))
    assert ours.shape == theirs.shape
    assert abs(theirs[-1, -1]) > 1e-3                    # gravity did work
    assert np.abs(theirs[-1, 3:6] - theirs[0, 3:6]).max() == 0   # the fixed sphere stays
    assert np.abs(ours - theirs).max() < 1e-12 * max(1.0, np.abs(theirs).max())


def test_gravity_engine_equals_newton_gravity_without_energy():
    def fall(engines):
        scene = Scene()
        scene.bodies.append(sphere((0, 0, 0), 0.1))
        scene.engines = engines
        scene.dt = 1e-3
        scene.run(100)
        return np.array(scene.bodies[0].state.pos)
    g = (0.0, 1.0, -9.81)
    assert np.array_equal(fall([ForceResetter(), GravityEngine(gravity=g, warnOnce=False), NewtonIntegrator()]),
                          fall([ForceResetter(), NewtonIntegrator(gravity=g)]))
