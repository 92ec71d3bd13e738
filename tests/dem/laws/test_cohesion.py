"""Cohesive-frictional contacts (CohFrictMat, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys,
Law2_ScGeom6D_CohFrictPhys_CohesionMoment): stiffnesses, bond breakage at the normal and shear
strengths, rolling and twisting moments from the relative rotation (ScGeom6D), rolling
resistance on an incline against its analytic limit, energy balance with moments."""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (CohFrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_CohFrictMat_CohFrictMat_CohFrictPhys, Law2_ScGeom6D_CohFrictPhys_CohesionMoment,
                       NewtonIntegrator, Scene, sphere, wall)

R = 0.1


def engines(ip2=None, law=None, gravity=(0, 0, 0), damping=0.0):
    return [ForceResetter(), InsertionSortCollider(),
            InteractionLoop([], [ip2 or Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True)],
                            [law or Law2_ScGeom6D_CohFrictPhys_CohesionMoment()]),
            NewtonIntegrator(gravity=gravity, damping=damping)]


def bonded_pair(**material):
    """Two touching spheres, bonded at the first step; sphere 0 fixed."""
    S = Scene()
    params = dict(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, normalCohesion=1e5, shearCohesion=1e5)
    params.update(material)
    m = S.materials.append(CohFrictMat(**params))
    S.bodies.append([sphere((0, 0, 0), R, material=m, fixed=True), sphere((0, 0, 2 * R - 1e-9), R, material=m)])
    return S


def test_physics_and_bond_strengths():
    S = bonded_pair(momentRotationLaw=True, etaRoll=0.5, etaTwist=0.25, alphaKr=3.0)
    S.engines = engines()
    S.dt = 1e-5
    S.step()
    (c,), (x,) = S.contacts(), _dem.contact_extra(S._cpp)
    kn, ks = 1e7 * R, 0.3 * 1e7 * R                       # equal springs in series
    assert c["kn"] == pytest.approx(kn, rel=1e-14) and c["ks"] == pytest.approx(ks, rel=1e-14)
    assert x["kr"] == pytest.approx(R * R * ks * 3.0, rel=1e-14) and x["ktw"] == pytest.approx(R * R * ks * 2.0, rel=1e-14)
    assert x["maxRollPl"] == pytest.approx(0.5 * R) and x["maxTwistPl"] == pytest.approx(0.25 * R)
    assert x["normalAdhesion"] == pytest.approx(1e5 * R * R) and not x["cohesionBroken"]


def pull_until_broken(S, direction, step_force):
    """Raise a force on sphere 1 slowly (quasi-static, damped) until the bond breaks; returns
    the contact force of the last bonded step and the applied force."""
    F, last = 0.0, None
    while True:
        x = _dem.contact_extra(S._cpp)
        if not x or x[0]["cohesionBroken"]:
            return last, F
        last = S.contacts()[0]
        F += step_force
        S.persistent_forces()[1] = F * np.asarray(direction)
        S.run(10)


def test_bond_breaks_at_the_normal_strength():
    S = bonded_pair()
    S.engines = engines(damping=0.8)
    S.dt = 1e-5
    S.step()
    last, F = pull_until_broken(S, (0, 0, 1), 0.05)
    strength = 1e5 * R * R
    assert -last["normalForce"][2] == pytest.approx(strength, rel=1e-3)
    assert F == pytest.approx(strength, rel=1e-3)
    S.run(2000)
    assert S._cpp.realContactCount() == 0 and S.bodies[1].state.vel[2] > 0   # it flew off


def test_bond_breaks_at_the_shear_strength_plus_friction():
    # Pushed together by 300 N and sheared: the bond holds up to shearAdhesion + Fn tan(phi).
    S = bonded_pair(normalCohesion=1e7)
    S.engines = engines(damping=0.8)
    S.dt = 1e-5
    S.bodies[1].state.blockedDOFs = "XYZ"
    S.step()
    S.persistent_forces()[1] = (0, 0, -300)
    S.run(3000)
    F = 0.0
    while not _dem.contact_extra(S._cpp)[0]["cohesionBroken"]:
        last = S.contacts()[0]
        F += 0.1
        S.persistent_forces()[1] = (F, 0, -300)
        S.run(10)
    strength = 1e5 * R * R + np.linalg.norm(last["normalForce"]) * math.tan(0.5)
    assert np.linalg.norm(last["shearForce"]) == pytest.approx(strength, rel=1e-3)


@pytest.mark.parametrize("incremental", [False, True])
def test_moments_follow_the_relative_rotation(incremental):
    # Sphere 1 turned at an imposed rate about x (bending) then about z (twist, the normal):
    # moments kr * angle and ktw * angle, restoring on the turned sphere. The total form sees
    # the orientation of the step's start (one step of rotation less).
    S = bonded_pair(momentRotationLaw=True)
    S.engines = engines(law=Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=incremental))
    S.dt = 1e-5
    S.bodies[1].dynamic = False
    S.step()
    S.bodies[1].state.angVel = (0.5, 0, 0)
    S.run(1000)
    x = _dem.contact_extra(S._cpp)[0]
    lag = 0 if incremental else 1
    bend = 0.5 * (1000 - lag) * S.dt
    assert x["moment_bending"] == pytest.approx((-x["kr"] * bend, 0, 0), rel=1e-6, abs=1e-9 * x["kr"])
    S.bodies[1].state.angVel = (0, 0, 2.0)
    S.run(500)
    x = _dem.contact_extra(S._cpp)[0]
    twist = 2.0 * (500 - lag) * S.dt
    assert x["moment_twist"] == pytest.approx((0, 0, -x["ktw"] * twist), rel=1e-5, abs=1e-9 * x["ktw"])
    if not incremental:
        assert x["twist"] == pytest.approx(-twist, rel=1e-5)


@pytest.mark.parametrize("slope_deg, rolls", [(14.0, False), (16.0, True), (25.0, True)])
def test_rolling_resistance_on_an_incline(slope_deg, rolls):
    # A sphere on a wall with gravity tilted by `slope`, friction high enough that it never
    # slides, rolling limit etaRoll = 0.27 (tan 15.1 deg): below, the plastic rolling moment
    # etaRoll r Fn holds it; above, it rolls with a = g (l/r sin a - etaRoll cos a) / (2/5 + l/r)
    # (friction acts at the contact point, mid-overlap as in Yade's Law2: l = r - overlap/2). Without a bond,
    # moments need always_use_moment_law (as in Yade).
    eta, a = 0.27, math.radians(slope_deg)
    S = Scene()
    m = S.materials.append(CohFrictMat(young=1e7, poisson=0.3, frictionAngle=1.2, density=2000, isCohesive=False,
                                       momentRotationLaw=True, etaRoll=eta))
    S.bodies.append([wall(0, axis=2, material=m), sphere((0, 0, 1.0), R, material=m)])
    mass = S.bodies[1].state.mass
    overlap = mass * 9.81 * math.cos(a) / (1e7 * R)
    S.bodies[1].state.pos = (0, 0, R - overlap)
    S.engines = engines(Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(),
                        Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True),
                        gravity=(9.81 * math.sin(a), 0, -9.81 * math.cos(a)))
    S.dt = 1e-5
    S.run(10000)
    # The contact springs keep oscillating (nothing damps them): fit x(t) by a parabola over
    # many periods.
    t, x = [], []
    for _ in range(500):
        S.run(100)
        t.append(S.time)
        x.append(S.bodies[1].state.pos[0])
    accel = 2 * np.polyfit(t, x, 2)[0]
    if rolls:
        arm = (R - overlap / 2) / R
        expected = 9.81 * (arm * math.sin(a) - eta * math.cos(a)) / (0.4 + arm)
        assert accel == pytest.approx(expected, rel=1e-3)
    else:   # free rolling would cover 0.2 m in this time
        assert max(x) - min(x) < 1e-3 * R


def test_energy_balance_with_bonds_and_moments():
    # A bonded pair set spinning and vibrating, no damping: the moment springs store energy
    # and give it back.
    S = bonded_pair(momentRotationLaw=True)
    S.engines = engines()
    S.dt = 1e-6
    S.trackEnergy = True
    S.step()
    S.bodies[1].state.vel = (0.01, 0, 0.005)
    S.bodies[1].state.angVel = (0.3, -0.2, 0.5)
    before = S.energy.total()
    S.run(20000)
    assert S.energy["elastPotential"] > 0.05 * before
    assert abs(S.energy.total() - before) < 1e-3 * before


def test_cohesive_materials_need_their_law():
    S = Scene()
    S.materials.append(CohFrictMat())
    with pytest.raises(ValueError, match="CohFrictMat|normalCohesion"):
        S.materials.append(CohFrictMat(normalCohesion=float("nan")))


def test_set_cohesion_now_bonds_existing_contacts_once():
    S = bonded_pair()
    ip = Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()
    S.engines = engines(ip)
    S.dt = 1e-5
    S.step()
    assert _dem.contact_extra(S._cpp)[0]["cohesionBroken"]      # touching, not bonded
    ip.setCohesionNow = True                                      # as a Yade script does mid-run
    S.step()
    assert not _dem.contact_extra(S._cpp)[0]["cohesionBroken"]
    assert ip.setCohesionNow is False                             # one shot, reset by the law
