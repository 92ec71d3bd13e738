"""Yade's ResetRandomPosition: Yade's fixed-seed generators reproduced, the places and the
velocities of the first re-insertions equal to Yade 2023.02a's."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_first_reinsertion_is_yades():
    script = TWINS / "reset_random_position_side_by_side.py"
    ours, theirs = (twin.run(script, {}, who) for who in ("talus", "yade"))
    assert len(ours) >= 5 and len(theirs) >= 5                      # the spheres recirculate in both
    # step, id, position (on the facets at z = 0.5), velocity and angular velocity drawn
    assert ours[0][:2] == theirs[0][:2] == [706, 2]
    assert np.allclose(ours[0][2:], theirs[0][2:], rtol=0, atol=1e-12)
    # the velocities of the next re-insertions are Yade's draws too, whichever sphere gets them
    assert np.allclose([m[5:] for m in ours[:3]], [m[5:] for m in theirs[:3]], rtol=0, atol=1e-12)


def test_facets_without_bound_touch_nothing(tmp_path):
    from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                           Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, O, facet, sphere)
    O.reset()
    floor = O.bodies.append([facet([(-1, -1, 0), (1, -1, 0), (0, 1, 0)], noBound=True),
                             facet([(-1, -1, -1), (1, -1, -1), (0, 1, -1)])])
    ball = O.bodies.append(sphere((0, 0, 0.2), 0.1))
    O.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81))]
    O.dt = 1e-4
    assert not O.bodies[floor[0]].bounded and O.bodies[floor[1]].bounded
    O.save(str(tmp_path / "scene.h5"))
    O.load(str(tmp_path / "scene.h5"))
    assert not O.bodies[floor[0]].bounded
    O.run(5000, True)
    assert O.bodies[ball].state.pos[2] < -0.7                        # through the first
    O.run(1000, True)
    assert O.bodies[ball].state.vel[2] > 0                           # bounced on the second
