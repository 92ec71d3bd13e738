"""Kinematic bodies (imposed velocities, Translation/Rotation/HarmonicMotion engines), boxes
(Box-sphere contacts on faces, edges and corners), geom.facetCylinder, erase during a run."""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.dem import (FrictMat, ForceResetter, HarmonicMotionEngine, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       PWaveTimeStep, PyRunner, RotationEngine, Scene, TranslationEngine, box, facet, sphere)
from talus.dem.geometry import geom

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run
yade = shutil.which("yade")


def base(S, gravity=(0, 0, 0), damping=0.0, extra=()):
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 *extra, NewtonIntegrator(gravity=gravity, damping=damping)]


def test_translation_rotation_harmonic_engines():
    S = Scene()
    S.materials.append(FrictMat())
    f = S.bodies.append(facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)]))
    g = S.bodies.append(facet([(2, 0, 0), (3, 0, 0), (2, 1, 0)]))
    h = S.bodies.append(facet([(0, 0, 5), (1, 0, 5), (0, 1, 5)]))
    p0, q0, h0 = (S.bodies[i].state.pos for i in (f, g, h))
    omega, dt = 2.0, 1e-3
    base(S, extra=[TranslationEngine(translationAxis=(0, 0, 2), velocity=0.5, ids=[f]),
                   RotationEngine(angularVelocity=omega, rotationAxis=(0, 0, 1), rotateAroundZero=True,
                                  zeroPoint=(0, 0, 0), ids=[g]),
                   HarmonicMotionEngine(A=(0.1, 0, 0), f=(1, 0, 0), ids=[h])])
    S.dt = dt
    S.run(1000)
    t = S.time
    np.testing.assert_allclose(S.bodies[f].state.pos, p0 + (0, 0, 0.5 * t), atol=1e-12)
    q = S.bodies[g].state.pos                                  # exactly on its circle, at angle omega t
    assert np.hypot(q[0], q[1]) == pytest.approx(np.hypot(q0[0], q0[1]), rel=1e-12)
    assert math.atan2(q[1], q[0]) - math.atan2(q0[1], q0[0]) == pytest.approx(omega * t, rel=1e-12)
    assert S.bodies[g].state.angVel[2] == omega
    # x = A cos(w t + pi/2) - A cos(pi/2) = -A sin(w t), to the step's first-order error
    assert S.bodies[h].state.pos[0] - h0[0] == pytest.approx(-0.1 * math.sin(2 * math.pi * t), abs=2e-3 * 0.1 * 2 * math.pi)
    with pytest.raises(IndexError, match="no body with id 99"):
        S.engines = [*S.engines[:-1], TranslationEngine(velocity=1, ids=[99]), S.engines[-1]]
        S.step()


def test_turning_facet_shears_with_its_velocity_at_the_contact():
    """A sphere resting on a horizontal facet turned about z through the origin: the shear force
    on the sphere follows the facet's velocity at the contact point, omega x r (tangential), not
    the facet's centre velocity."""
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=1000, frictionAngle=0.8))
    ids = S.bodies.append([facet([(-1, -1, 0), (1, -1, 0), (0, 1.5, 0)])])
    s = S.bodies.append(sphere((0.5, 0, 0.0999), 0.1))
    base(S, gravity=(0, 0, -9.81), extra=[RotationEngine(angularVelocity=1.0, rotationAxis=(0, 0, 1),
                                                         rotateAroundZero=True, ids=ids)])
    S.dt = 0.2 * PWaveTimeStep(S)
    S.run(3)
    c = [d for d in S.contacts() if d["id2"] == s][0]
    direction = c["shearForce"] / np.linalg.norm(c["shearForce"])
    # omega x (0.5, 0, 0) is +y (up to the few steps turned); the facet centre moves along +x
    np.testing.assert_allclose(direction, (0, 1, 0), atol=1e-3)


def test_sphere_on_box_face_edge_corner():
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=1000))
    q = (math.cos(math.pi / 8), 0, 0, math.sin(math.pi / 8))   # 45 degrees about z
    k = S.bodies.append(box((0, 0, 0), (1, 0.5, 0.25), orientation=q, fixed=True))
    r = 0.1
    face = S.bodies.append(sphere((0, 0, 0.25 + r - 1e-3), r))                         # on the top face
    e = np.array([math.cos(math.pi / 4), math.sin(math.pi / 4), 0])                   # box x axis
    corner_point = 1.0 * e + 0.25 * np.array([0, 0, 1]) + 0.5 * np.array([-e[1], e[0], 0])
    outward = np.array([e[0] - e[1], e[1] + e[0], 1]) / math.sqrt(3)                    # diagonal outward
    corner = S.bodies.append(sphere(corner_point + (r - 2e-3) * outward, r))
    edge_point = -1.0 * e + 0.25 * np.array([0, 0, 1])                                 # middle of an edge
    edge_dir = (-e + np.array([0, 0, 1])) / math.sqrt(2)
    edge = S.bodies.append(sphere(edge_point + (r - 3e-3) * edge_dir, r))
    base(S)
    S.dt = 1e-7
    S.step()
    got = {c["id2"]: c for c in S.contacts() if c["id1"] == k}
    assert sorted(got) == [face, corner, edge]
    np.testing.assert_allclose(got[face]["normal"], (0, 0, 1), atol=1e-12)
    assert got[face]["penetrationDepth"] == pytest.approx(1e-3, rel=1e-6)
    np.testing.assert_allclose(got[corner]["normal"], outward, atol=1e-9)
    assert got[corner]["penetrationDepth"] == pytest.approx(2e-3, rel=1e-5)
    np.testing.assert_allclose(got[edge]["normal"], edge_dir, atol=1e-9)
    assert got[edge]["penetrationDepth"] == pytest.approx(3e-3, rel=1e-5)


def test_sphere_resting_on_box_and_dynamic_box():
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=1000))
    k = S.bodies.append(box((0, 0, -0.5), (2, 2, 0.5), fixed=True))
    s = S.bodies.append(sphere((0.3, 0.2, 0.11), 0.1))
    free = S.bodies.append(box((5, 0, 0), (0.1, 0.2, 0.3)))
    b = S.bodies[free]
    assert b.state.mass == pytest.approx(1000 * 8 * 0.1 * 0.2 * 0.3)
    np.testing.assert_allclose(b.state.inertia, b.state.mass / 3 * np.array([0.13, 0.1, 0.05]), rtol=1e-14)
    np.testing.assert_allclose(b.shape.extents, (0.1, 0.2, 0.3))
    base(S, gravity=(0, 0, -9.81), damping=0.5)
    S.dt = 0.2 * PWaveTimeStep(S)
    S.run(6000)
    c = [d for d in S.contacts() if d["id2"] == s][0]
    assert c["id1"] == k
    assert c["normalForce"][2] == pytest.approx(S.bodies[s].state.mass * 9.81, rel=1e-6)
    assert S.bodies[free].state.pos[2] < -1          # the free box falls through nothing


def test_facet_cylinder_geometry():
    specs = geom.facetCylinder((0.1, 0.2, 0.3), 0.5, 0.8, segmentsNumber=12, wallMask=4)
    assert len(specs) == 24
    v = np.array([s.vertices for s in specs]).reshape(-1, 3) - (0.1, 0.2, 0.3)
    np.testing.assert_allclose(np.hypot(v[:, 0], v[:, 1]), 0.5, rtol=1e-14)
    np.testing.assert_allclose(np.abs(v[:, 2]), 0.4, rtol=1e-14)
    assert len(geom.facetCylinder((0, 0, 0), 1, 1, segmentsNumber=5)) == 20
    with pytest.raises(ValueError, match="radii must be positive"):
        geom.facetCylinder((0, 0, 0), -1, 1)


@pytest.mark.skipif(yade is None, reason="yade is not installed")
def test_facet_cylinder_matches_yade():
    out = {who: np.array(twin.run(TWINS / "facet_cylinder.py", {}, who)) for who in ("talus", "yade")}
    assert out["talus"].shape == out["yade"].shape == (28, 3, 3)
    np.testing.assert_allclose(out["talus"], out["yade"], atol=1e-14)


def test_erase_during_a_run():
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=1000))
    S.bodies.append(box((0, 0, -0.5), (2, 2, 0.5), fixed=True))
    ids = S.bodies.append([sphere((x, 0, 0.099), 0.1) for x in (0, 0.3, 0.6)])
    base(S, gravity=(0, 0, -9.81), extra=[PyRunner(command=lambda: S.bodies.erase(ids[1]) if S.iter == 5 else None)])
    S.dt = 0.2 * PWaveTimeStep(S)
    S.run(4)
    assert {d["id2"] for d in S.contacts()} == set(ids)
    S.run(10)
    assert {d["id2"] for d in S.contacts()} == {ids[0], ids[2]}
    assert len(S.bodies) == 4 and [b.id for b in S.bodies] == [0, ids[0], ids[2]]
    assert S.bodies.append(sphere((5, 5, 5), 0.1)) == 4           # ids are not reused
    assert S.bodies[ids[1]] is None                                # an erased id, as in Yade
    assert S.bodies.erase(ids[1]) is False
    with pytest.raises(IndexError, match="no body with id 99"):
        S.bodies[99]
    # clumps: erasing a member takes it out of the clump, which keeps its mass properties (as
    # Yade's); erasing the clump frees the others
    cid, members = S.bodies.appendClumped([sphere((3, 0, 1), 0.1), sphere((3.2, 0, 1), 0.1), sphere((3.4, 0, 1), 0.1)])
    S.bodies.erase(members[0])
    assert list(S.bodies[cid].shape.members) == members[1:]
    assert S.bodies[cid].state.pos[0] == pytest.approx(3.2)
    S.bodies.erase(cid)
    assert all(S.bodies[m].isStandalone for m in members[1:])
    S.run(2)
