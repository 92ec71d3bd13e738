"""Nearly degenerate contacts of Potential Blocks and Potential Particles (parallel and nearly
parallel faces, crossed and parallel edges, a vertex or an edge into a face, vertex to vertex,
an oblique pair), each turned by 0, 1e-9, 1e-6 and 1e-3 rad away from the exact configuration
and swept through 12 distances from 1e-6 m apart to centres together: never a NaN, always a
unit normal from body 1 to body 2, contact exactly when the shapes overlap (to 1e-10 m), and in
the symmetric configurations the normal within a few tilts of the exact one and, untilted, the
overlap equal to the depth."""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (FrictMat, PotentialBlock, PotentialParticle, Quaternion, Scene, blockContact,
                       particleContact, potentialBlock, potentialParticle)

SHAPES = {
    "block": (lambda: PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.05), potentialBlock, blockContact),
    "particle": (lambda: PotentialParticle.cuboid((0.5, 0.5, 0.5), r=0.05, k=0.2), potentialParticle,
                 particleContact),
}
TILTS = [0.0, 1e-9, 1e-6, 1e-3]


def scene_of(kind):
    """The shape, body maker and contact probe of `kind`, a scene and its material."""
    if kind == "block" and not _dem.have_potential_blocks:
        pytest.skip("built without CLP")
    make_shape, make_body, probe = SHAPES[kind]
    S = Scene()
    m = S.materials.append(FrictMat(density=1000))
    return make_shape(), make_body, probe, S, m


def first_touch(S, a, b, probe, position):
    """The smallest s in [0.5, 2.5] at which body b, placed at position(s), touches body a
    (bisection on "touching")."""
    lo, hi = 0.5, 2.5
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        S.bodies[b].state.pos = position(mid)
        lo, hi = (mid, hi) if probe(S, a, b)["touching"] else (lo, mid)
    return hi


def configurations():
    """(name, orientation 1, orientation 2, direction from 1 to 2, exact normal or None)."""
    z = (0, 0, 1)
    diag = np.array([1, 1, 1]) / math.sqrt(3)
    # turn the cube's diagonal onto -z (a vertex pointing down); a unit axis, as Yade's Quaternion wants
    axis = np.cross(diag, [0, 0, -1])
    axis /= np.linalg.norm(axis)
    vertex_down = Quaternion(axis, math.acos(np.dot(diag, [0, 0, -1])))
    return [
        ("parallel faces", (1, 0, 0, 0), (1, 0, 0, 0), z, z),
        ("parallel faces, twisted 45", (1, 0, 0, 0), Quaternion(z, math.pi / 4), z, z),
        ("edge-edge crossed", Quaternion((1, 0, 0), math.pi / 4), Quaternion((0, 1, 0), math.pi / 4), z, z),
        ("edge-edge parallel", Quaternion((1, 0, 0), math.pi / 4), Quaternion((1, 0, 0), math.pi / 4), z, z),
        ("vertex-face", (1, 0, 0, 0), vertex_down, z, None),
        ("vertex-vertex", Quaternion(axis, -math.acos(np.dot(diag, [0, 0, -1]))), vertex_down, z, None),
        ("edge-face", (1, 0, 0, 0), Quaternion((1, 0, 0), math.pi / 4), z, None),
        ("oblique", Quaternion((1, 2, 3), 0.3), Quaternion((3, -1, 2), 1.1), np.array([1, 2, 3]) / math.sqrt(14), None),
    ]


@pytest.mark.parametrize("tilt", TILTS)
@pytest.mark.parametrize("name, q1, q2, direction, expected", configurations())
@pytest.mark.parametrize("kind", sorted(SHAPES))
def test_near_degenerate_contacts_never_give_nan_nor_a_wrong_normal(kind, name, q1, q2, direction, expected, tilt):
    shape, make_body, probe, S, m = scene_of(kind)
    # the tilt turns body 2 about an axis across the normal, away from the exact configuration
    if tilt:    # the (w, x, y, z) tuples as a Quaternion, whose own order is minieigen's (x, y, z, w)
        q2 = Quaternion((1, 0.3, 0), tilt) * (q2 if isinstance(q2, Quaternion) else Quaternion(*q2))
    a = S.bodies.append(make_body(shape, pos=(0, 0, 0), orientation=q1, material=m))
    b = S.bodies.append(make_body(shape, pos=(0, 0, 3), orientation=q2, material=m))
    direction = np.asarray(direction, float)
    # the distance at first touch along `direction`
    touch = first_touch(S, a, b, probe, lambda s: tuple(s * direction))
    for gap in [1e-6, 1e-12, 0.0, -1e-12, -1e-9, -1e-6, -1e-4, -1e-2, -0.1, -0.3, -0.6, -touch]:
        S.bodies[b].state.pos = tuple((touch + gap) * direction)
        g = probe(S, a, b)
        if gap > 1e-10:
            assert not g["touching"], (name, gap)
        if gap < -1e-10:
            assert g["touching"], (name, gap)
        if not g["touching"]:
            continue
        n = np.asarray(g["normal"])
        assert np.all(np.isfinite(n)) and abs(np.linalg.norm(n) - 1) < 1e-12, (name, gap, n)
        assert np.isfinite(g["penetrationDepth"]) and g["penetrationDepth"] >= 0, (name, gap)
        assert np.isfinite(g["contactArea"]) and g["contactArea"] >= 0, (name, gap)
        assert np.all(np.isfinite(g["contactPoint"])), (name, gap)
        if gap == -touch:
            continue   # centres together: any normal is right
        assert n @ direction > 0, (name, gap, n)
        if expected is not None and gap > -0.3 and (tilt == 0 or name != "edge-edge parallel"):
            # Turned by `tilt`, the exact normal (faces, crossed edges) stays within a few tilts of
            # the untilted one. Parallel edges have none once turned: their common normal is
            # the cross product of nearly parallel directions.
            assert math.acos(min(1.0, n @ np.asarray(expected, float))) <= 3 * tilt + 1e-7, (name, gap, n)
        if expected is not None and tilt == 0 and -1e-2 <= gap <= -1e-9:
            # abs: blocks count as touching once the overlap is deeper than 1e-12 of their
            # size, which shifts the bisected first touch by a few 1e-12 m
            assert g["penetrationDepth"] == pytest.approx(-gap, rel=1e-5, abs=1e-11), (name, gap)


@pytest.mark.parametrize("kind", sorted(SHAPES))
def test_accuracy_tolerance_is_checked_and_trades_accuracy(kind):
    shape, make_body, probe, S, m = scene_of(kind)
    a = S.bodies.append(make_body(shape, pos=(0, 0, 0), material=m))
    # a vertex of body 2 into a face of body 1, off-centre
    diag = np.array([1, 1, 1]) / math.sqrt(3)
    axis = np.cross(diag, [0, 0, -1])
    b = S.bodies.append(make_body(shape, pos=(0.1, 0.05, 3), orientation=Quaternion(axis / np.linalg.norm(axis),
                                                                              math.acos(-diag[2])), material=m))
    touch = first_touch(S, a, b, probe, lambda s: (0.1, 0.05, s))
    S.bodies[b].state.pos = (0.1, 0.05, touch - 1e-3)
    for bad in (0.0, -1e-8, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="accuracyTol"):
            probe(S, a, b, accuracyTol=bad)
    tight, loose = probe(S, a, b, accuracyTol=1e-12), probe(S, a, b, accuracyTol=1e-1)
    default = probe(S, a, b)
    assert tight["touching"] and loose["touching"] and default["touching"]
    # the default is as accurate as a tight tolerance; a loose one is not worse than 1 %
    assert default["penetrationDepth"] == pytest.approx(tight["penetrationDepth"], rel=1e-6)
    assert loose["penetrationDepth"] == pytest.approx(tight["penetrationDepth"], rel=1e-2)
