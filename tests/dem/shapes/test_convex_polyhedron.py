"""pack.inConvexPolyhedron: inside every (point, inward normal) plane by at least the pad; its
box from the vertices. The unit cube's answers are what Yade 2023.02a prints for the same calls."""
import pytest

from talus.dem.packing.pack import inConvexPolyhedron

CUBE = [((0, 0, 0), (1, 0, 0)), ((1, 0, 0), (-1, 0, 0)), ((0, 0, 0), (0, 1, 0)), ((0, 1, 0), (0, -1, 0)),
        ((0, 0, 0), (0, 0, 1)), ((0, 0, 1), (0, 0, -1))]


def test_unit_cube_as_yade():
    p = inConvexPolyhedron(CUBE)
    lo, hi = p.aabb()
    assert tuple(lo) == (0, 0, 0) and tuple(hi) == (1, 1, 1) and tuple(p.center()) == (0.5, 0.5, 0.5)
    # Yade: True False False False
    assert [p((0.5, 0.5, 0.5), 0.1), p((0.5, 0.5, 0.5), 0.6), p((0.95, 0.5, 0.5), 0.1), p((1.5, 0.5, 0.5), 0)] == \
        [True, False, False, False]


def test_tetrahedron_box_and_bad_planes():
    tet = inConvexPolyhedron([((0, 0, 0), (1, 0, 0)), ((0, 0, 0), (0, 1, 0)), ((0, 0, 0), (0, 0, 1)),
                              ((1, 0, 0), (-1, -1, -1))])
    lo, hi = tet.aabb()
    assert tuple(lo) == pytest.approx((0, 0, 0)) and tuple(hi) == pytest.approx((1, 1, 1))
    assert tet((0.2, 0.2, 0.2)) and not tet((0.5, 0.5, 0.5))
    with pytest.raises(ValueError, match="non-zero normal"):
        inConvexPolyhedron([*CUBE[:5], ((0, 0, 1), (0, 0, 0))])
    with pytest.raises(ValueError, match="at least 4 planes"):
        inConvexPolyhedron(CUBE[:3])
