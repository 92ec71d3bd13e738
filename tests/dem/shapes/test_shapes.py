"""Shapes and orientations read as in Yade scripts: b.shape.<attribute>, isinstance(b.shape, Sphere),
b.state.ori * v."""
import math

import numpy as np
import pytest

from talus.dem import Box, Clump, Facet, Quaternion, Scene, Sphere, Wall, box, facet, sphere, wall


def test_each_kind_exposes_its_geometry():
    S = Scene()
    s = S.bodies.append(sphere((0, 0, 0), 0.25))
    w = S.bodies.append(wall(-1, axis=1, sense=1))
    f = S.bodies.append(facet([(0, 0, 1), (1, 0, 1), (0, 1, 1)]))
    b = S.bodies.append(box((3, 0, 0), (0.1, 0.2, 0.3), orientation=Quaternion((0, 0, 1), math.pi / 2)))
    cid, members = S.bodies.appendClumped([sphere((5, 0, 0), 0.1), sphere((5.15, 0, 0), 0.1)])
    assert isinstance(S.bodies[s].shape, Sphere) and S.bodies[s].shape.radius == 0.25
    assert isinstance(S.bodies[w].shape, Wall) and (S.bodies[w].shape.axis, S.bodies[w].shape.sense) == (1, 1)
    shape = S.bodies[f].shape
    assert isinstance(shape, Facet) and str(shape) == "Facet"
    world = [S.bodies[f].state.pos + S.bodies[f].state.ori * v for v in shape.vertices]
    np.testing.assert_allclose(world, [(0, 0, 1), (1, 0, 1), (0, 1, 1)], atol=1e-15)
    np.testing.assert_allclose(shape.normal, (0, 0, 1))
    np.testing.assert_allclose(S.bodies[b].shape.extents, (0.1, 0.2, 0.3))
    clump = S.bodies[cid]
    assert isinstance(clump.shape, Clump) and list(clump.shape.members) == members
    assert not isinstance(S.bodies[b].shape, (Sphere, Wall, Facet)) and isinstance(S.bodies[b].shape, Box)
    with pytest.raises(AttributeError):
        S.bodies[s].shape.extents


def test_quaternion_rotates_and_composes_like_yade():
    q = Quaternion((0, 0, 1), math.pi / 2)
    np.testing.assert_allclose(q * (1, 0, 0), (0, 1, 0), atol=1e-15)
    np.testing.assert_allclose((q * q) * (1, 0, 0), (-1, 0, 0), atol=1e-15)
    np.testing.assert_allclose((q * q.conjugate()), Quaternion.Identity, atol=1e-15)
    axis, angle = q.toAxisAngle()
    np.testing.assert_allclose(axis, (0, 0, 1))
    assert angle == pytest.approx(math.pi / 2)
    assert list(q) == [q.x, q.y, q.z, q.w] and (q.z, q.w) == (q[2], q[3])   # minieigen's order: w last
    with pytest.raises(ValueError, match="axis must be non-zero"):
        Quaternion((0, 0, 0), 1.0)


def test_a_shape_still_equals_its_kind_name():
    S = Scene()
    s = S.bodies.append(sphere((0, 0, 0), 0.25))
    assert S.bodies[s].shape == "Sphere" and S.bodies[s].shape != "Wall"
    assert S.bodies[s].shape == S.bodies[s].shape and len({S.bodies[s].shape, S.bodies[s].shape}) == 1
