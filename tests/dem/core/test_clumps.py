"""Clumps: rigid aggregates of spheres (Yade's appendClumped), their mass properties, exact
rotation of aspherical bodies, contact forces on members, and the comparison with Yade."""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator, PWaveTimeStep, Scene, growParticles, sphere,
                       wall)

TWINS = Path(__file__).parents[1] / "yade_twins" / "clumps"  # the scripts Yade and Talus both run
yade = shutil.which("yade")


def engines(gravity=(0, 0, 0), damping=0.0):
    return [ForceResetter(), InsertionSortCollider(),
            InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
            NewtonIntegrator(gravity=gravity, damping=damping)]


def test_mass_properties_and_members():
    S = Scene()
    S.materials.append(FrictMat(density=2000))
    r = 0.1
    cid, ids = S.bodies.appendClumped([sphere((0, 0, 0), r), sphere((0.3, 0, 0), r)])
    c = S.bodies[cid]
    m1 = 2000 * 4 / 3 * math.pi * r ** 3
    assert c.isClump and list(c.shape.members) == ids and all(S.bodies[i].clumpId == cid for i in ids)
    assert not c.isClumpMember and all(S.bodies[i].isClumpMember and not S.bodies[i].isClump for i in ids)
    assert c.state.mass == pytest.approx(2 * m1, rel=1e-14)
    np.testing.assert_allclose(c.state.pos, (0.15, 0, 0), atol=1e-15)
    # principal moments: two spheres, axis through both centres, and two equal transverse ones
    axial, transverse = 2 * 0.4 * m1 * r * r, 2 * (0.4 * m1 * r * r + m1 * 0.15 ** 2)
    np.testing.assert_allclose(sorted(c.state.inertia), [axial, transverse, transverse], rtol=1e-12)
    with pytest.raises(ValueError, match="is a Clump; clump members must be spheres, facets or boxes"):
        S.bodies.clump([cid])
    # A member clumped again leaves its clump, which keeps its mass (Yade's clump()).
    other = S.bodies.clump([ids[0]])
    assert S.bodies[ids[0]].clumpId == other and list(c.shape.members) == ids[1:]
    assert c.state.mass == pytest.approx(2 * m1, rel=1e-14)


def test_overlapping_members_by_grid_integration():
    """discretization > 0 integrates the union of overlapping spheres: two spheres of radius r
    at distance r overlap in a lens of volume 5/12 pi r^3 (counted once instead of twice). The
    grid's cell is the bounding box's shortest side (2 r) / discretization, as Yade's."""
    S = Scene()
    S.materials.append(FrictMat(density=1000))
    r = 0.1
    twice, _ = S.bodies.appendClumped([sphere((0, 0, 0), r), sphere((r, 0, 0), r)])
    once, _ = S.bodies.appendClumped([sphere((0, 1, 0), r), sphere((r, 1, 0), r)], discretization=40)
    exact = 1000 * (2 * 4 / 3 - 5 / 12) * math.pi * r ** 3
    assert S.bodies[twice].state.mass == pytest.approx(1000 * 8 / 3 * math.pi * r ** 3, rel=1e-14)
    assert S.bodies[once].state.mass == pytest.approx(exact, rel=3e-3)
    np.testing.assert_allclose(S.bodies[once].state.pos, (r / 2, 1, 0), atol=1e-4 * r)


def test_dzhanibekov_flip_conserves_momentum_and_energy():
    """A free clump spun about its intermediate principal axis flips over and back (tennis-racket
    theorem) while its angular momentum stays exactly constant and its kinetic energy within
    Yade's first-order scheme error (measured 8.1e-4 at dt = 1e-4, 4.0e-4 at dt = 5e-5)."""
    def run(dt):
        S = Scene()
        S.materials.append(FrictMat(density=1000))
        cid, _ = S.bodies.appendClumped([sphere((0.3, 0, 0), 0.1), sphere((-0.3, 0, 0), 0.1),
                                         sphere((0, 0.15, 0), 0.1), sphere((0, -0.15, 0), 0.1)])
        c = S.bodies[cid]
        I = c.state.inertia
        assert I[0] < I[1] < I[2]
        R = c.state.ori.toRotationMatrix()
        c.state.angVel = R @ np.array([1e-3, 2 * math.pi, 1e-3])   # about the intermediate axis
        L0 = c.state.angMom.copy()
        S.engines = engines()
        S.dt = dt
        middle, energies = [], []
        for _ in range(40):
            S.run(int(round(0.1 / dt)))
            R = c.state.ori.toRotationMatrix()
            body = R.T @ c.state.angMom / I       # body-frame angular velocity from the momentum
            middle.append(body[1])
            energies.append(0.5 * body @ (I * body))
        np.testing.assert_allclose(c.state.angMom, L0, rtol=0, atol=1e-15 * np.linalg.norm(L0))
        return min(middle), max(middle), max(abs(e / energies[0] - 1) for e in energies)
    lo, hi, drift = run(1e-4)
    assert lo < -0.99 * 2 * math.pi and hi > 0.99 * 2 * math.pi   # it flipped
    assert drift < 1e-3
    _, _, finer = run(5e-5)
    assert finer < 0.6 * drift                                      # converges with dt


def test_clump_resting_on_wall_has_the_static_forces():
    """Three unequal spheres clumped, resting on a wall: the three normal forces balance the
    weight and its moment about the centroid (a statically determinate tripod)."""
    S = Scene()
    S.materials.append(FrictMat(young=1e8, poisson=0.3, density=2000, frictionAngle=0.5))
    S.bodies.append(wall(0, axis=2, sense=1))
    spheres = [((0, 0, 0.1), 0.1), ((0.25, 0, 0.08), 0.08), ((0, 0.2, 0.06), 0.06)]
    cid, ids = S.bodies.appendClumped([sphere(c, r) for c, r in spheres])
    S.engines = engines(gravity=(0, 0, -9.81), damping=0.5)
    S.dt = 0.3 * PWaveTimeStep(S)
    S.run(20000)
    c = S.bodies[cid]
    assert np.linalg.norm(c.state.vel) < 1e-9
    mg = c.state.mass * 9.81
    xy = np.array([S.bodies[i].state.pos[:2] for i in ids])
    A = np.vstack([np.ones(3), xy[:, 0], xy[:, 1]])
    expected = np.linalg.solve(A, mg * np.array([1, c.state.pos[0], c.state.pos[1]]))
    forces = {d["id2"]: d["normalForce"] for d in S.contacts()}
    assert sorted(forces) == ids                  # the three members touch the wall, not each other
    got = np.array([forces[i][2] for i in ids])
    np.testing.assert_allclose(got, expected, rtol=1e-6)


def test_members_never_touch_each_other_and_blocked_rotation():
    S = Scene()
    S.materials.append(FrictMat(young=1e7, density=1000))
    S.bodies.append(wall(0, axis=2, sense=1))
    cid, ids = S.bodies.appendClumped([sphere((0, 0, 0.3), 0.1), sphere((0.12, 0, 0.35), 0.1)])  # overlapping
    S.bodies[cid].state.blockedDOFs = "XYZ"
    ori = S.bodies[cid].state.ori
    S.engines = engines(gravity=(0, 0, -9.81), damping=0.3)
    S.dt = 0.3 * PWaveTimeStep(S)
    S.run(3000)
    assert all(d["id1"] == 0 for d in S.contacts())        # only wall contacts
    assert S.bodies[cid].state.ori == ori                   # landed on one sphere without turning
    assert S.bodies[ids[0]].state.pos[2] < 0.1


@pytest.mark.skipif(yade is None, reason="yade is not installed (./setup.sh installs it)")
@pytest.mark.parametrize("friction", [False, True])
def test_clump_drop_matches_yade(friction):
    """The same clump dropped on a wall in Yade and Talus, frictionless and frictional: member
    positions every 200 steps through the landing, tipping and rocking agree within 1e-6
    (measured 2e-15 and 4e-14)."""
    ours, theirs = (twin.run(TWINS / "clump_drop.py", {"friction": friction}, who) for who in ("talus", "yade"))
    assert ours["mass"] == pytest.approx(theirs["mass"], rel=1e-13)
    np.testing.assert_allclose(ours["inertia"], theirs["inertia"], rtol=1e-12)
    m_ours, m_yade = np.array(ours["members"]), np.array(theirs["members"])
    relative = m_yade - np.array(theirs["centroid"])[:, None, :]
    assert np.abs(relative - relative[0]).max() > 0.05        # it did turn
    assert m_yade[:, :, 2].min() < 0.1                        # and landed
    assert np.abs(m_ours - m_yade).max() < 1e-6


def test_growing_a_clump_scales_it_homothetically():
    """growParticles grows a clump about its centroid, as Yade does: members' offsets and radii
    x s, mass x s^3 and principal moments x s^5 (updateMass), the clump's position,
    orientation and velocities kept, its members moving with it rigidly."""
    S = Scene()
    S.materials.append(FrictMat(density=2000))
    cid, ids = S.bodies.appendClumped([sphere((0, 0, 0), 0.1), sphere((0.15, 0.02, 0.01), 0.08),
                                       sphere((0.05, 0.12, -0.03), 0.05)])
    free = S.bodies.append(sphere((1, 1, 1), 0.1))
    c = S.bodies[cid].state
    c.vel, c.angVel = (0.1, -0.2, 0.3), (1, 2, -0.5)
    pos, ori, mass, inertia = np.array(c.pos), np.array(c.ori), c.mass, np.array(c.inertia)
    offsets = np.array([S.bodies[i].state.pos for i in ids]) - pos
    radii = np.array([S.bodies[i].shape.radius for i in ids])
    growParticles(1.3, scene=S)
    assert c.mass == pytest.approx(mass * 1.3 ** 3, rel=1e-14)
    np.testing.assert_allclose(c.inertia, inertia * 1.3 ** 5, rtol=1e-14)
    np.testing.assert_array_equal(c.pos, pos)
    np.testing.assert_array_equal(c.ori, ori)
    np.testing.assert_array_equal(c.vel, (0.1, -0.2, 0.3))
    grown = np.array([S.bodies[i].state.pos for i in ids]) - pos
    np.testing.assert_allclose(grown, 1.3 * offsets, rtol=1e-14, atol=1e-16)
    np.testing.assert_allclose([S.bodies[i].shape.radius for i in ids], 1.3 * radii, rtol=1e-15)
    for i, arm in zip(ids, grown):
        np.testing.assert_allclose(S.bodies[i].state.vel, np.array(c.vel) + np.cross(c.angVel, arm), atol=1e-15)
    assert S.bodies[free].shape.radius == pytest.approx(0.13, rel=1e-15)
    # updateMass=False: the clump grows, its mass and moments stay (Yade's too)
    growParticles(1.1, updateMass=False, scene=S)
    assert c.mass == pytest.approx(mass * 1.3 ** 3, rel=1e-14)
    np.testing.assert_allclose(np.array([S.bodies[i].state.pos for i in ids]) - pos, 1.43 * offsets, rtol=1e-14,
                               atol=1e-16)
    # dynamicOnly: a fixed clump does not grow, neither do its members
    S.bodies[cid].dynamic = False
    growParticles(2.0, scene=S)
    assert S.bodies[ids[0]].shape.radius == pytest.approx(0.143, rel=1e-14)
    assert c.mass == pytest.approx(mass * 1.3 ** 3, rel=1e-14)


@pytest.mark.skipif(yade is None, reason="yade is not installed (./setup.sh installs it)")
def test_clump_growth_matches_yade():
    """A clump grown eight times in flight and while resting on a wall (once without masses),
    beside a free sphere, in Yade and Talus: mass and moments after each growth agree to 1e-13
    (measured 9e-16), the members' offsets from the centroid (world frame, so turning with the
    clump) and positions every 200 steps within 1e-6 (measured 8e-17 in flight, 3e-8 and 9e-8
    once it rests on the wall: Talus gives the members the clump's rigid velocity at the growth,
    Yade at its next step)."""
    ours, theirs = (twin.run(TWINS / "clump_growth.py", {}, who) for who in ("talus", "yade"))
    assert len(ours["grown"]) == len(theirs["grown"]) == 8
    for a, b in zip(ours["grown"], theirs["grown"]):
        assert a["mass"] == pytest.approx(b["mass"], rel=1e-13)
        np.testing.assert_allclose(a["inertia"], b["inertia"], rtol=1e-13)
        np.testing.assert_allclose(a["offsets"], b["offsets"], rtol=0, atol=1e-6)
        np.testing.assert_allclose(a["radii"], b["radii"], rtol=1e-14)
    assert theirs["grown"][-1]["mass"] > 1.1 * theirs["grown"][0]["mass"]   # the clump did grow
    m_ours, m_yade = np.array(ours["members"]), np.array(theirs["members"])
    assert m_yade[:, :, 2].min() < 0.11                                      # and rests on the wall
    assert np.abs(m_ours - m_yade).max() < 1e-6
    np.testing.assert_allclose(ours["free"], theirs["free"], rtol=0, atol=1e-6)
