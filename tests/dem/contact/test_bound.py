"""b.bound (Yade's Aabb): the shape's box at the position of the last re-detection grown by the
skin (Yade 2023.02a gives these numbers for this scene), not saved by checkpoints (NaN until the
collider runs again, as in Yade), None for a clump."""
import math

import pytest

from talus.dem import ForceResetter, InsertionSortCollider, NewtonIntegrator, Scene, box, facet, sphere, wall
from talus.dem.files import io


def scene():
    S = Scene()
    S.bodies.append([sphere((0, 0, 0), 1), wall(-2, axis=2), facet([(0, 0, -3), (1, 0, -3), (0, 1, -3)]),
                     box((5, 0, 0), (1, 2, 3))])
    S.engines = [ForceResetter(), InsertionSortCollider(), NewtonIntegrator(gravity=(0, 0, -10))]
    S.dt = 1e-3
    return S


def test_bounds_are_the_shapes_at_the_last_redetection_grown_by_the_skin():
    S = scene()
    assert math.isnan(S.bodies[0].bound.min[0])      # not bounded yet
    S.run(2, True)
    sphere_bound = S.bodies[0].bound
    assert tuple(sphere_bound.min) == (-1.5, -1.5, -1.5) and tuple(sphere_bound.max) == (1.5, 1.5, 1.5)
    assert sphere_bound.sweepLength == 0.5 and tuple(sphere_bound.refPos) == (0, 0, 0)
    assert S.bodies[0].state.pos[2] < 0              # it fell, its bound stays where it was taken
    wall_bound = S.bodies[1].bound
    assert tuple(wall_bound.min) == (-math.inf, -math.inf, -2.5) and tuple(wall_bound.max) == (math.inf, math.inf, -1.5)
    facet_bound = S.bodies[2].bound
    assert tuple(facet_bound.min) == pytest.approx((-0.5, -0.5, -3.5)) and tuple(facet_bound.max) == pytest.approx((1.5, 1.5, -2.5))
    box_bound = S.bodies[3].bound
    assert tuple(box_bound.min) == pytest.approx((3.5, -2.5, -3.5)) and tuple(box_bound.max) == pytest.approx((6.5, 2.5, 3.5))


@pytest.mark.skipif(not io.available(), reason="built without HDF5")
def test_bounds_are_not_saved_and_clumps_have_none(tmp_path):
    S = scene()
    S.run(1, True)
    io.save(S, tmp_path / "s.h5")
    R = Scene()
    io.load(R, tmp_path / "s.h5")
    assert math.isnan(R.bodies[0].bound.min[0])
    R.run(1, True)
    assert tuple(R.bodies[0].bound.max) == pytest.approx((1.5, 1.5, 1.5), abs=1e-4)   # bounded again
    clump, _ = R.bodies.appendClumped([sphere((9, 9, 9), 0.1), sphere((9, 9, 9.15), 0.1)])
    assert R.bodies[clump].bound is None
