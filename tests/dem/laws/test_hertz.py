"""Hertz-Mindlin contacts (Ip2_FrictMat_FrictMat_MindlinPhys + Law2_ScGeom_MindlinPhys_Mindlin):
stiffness constants equal Yade's, restitution equals an independent high-accuracy solution of the
same contact model, an elastic bounce conserves energy, the friction threshold on an incline."""
import math

import pytest

from talus.dem.analysis.analytic import hertz_contact_time, hertz_restitution, thornton_damping_ratio
from talus.dem import (FrictMat, InteractionLoop, Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin,
                       MatchMaker, Scene, sphere)

from test_contact_physics import engines, run_collision, slide_on_incline

E, NU, RHO, R = 1e8, 0.3, 2600.0, 0.01


def hertz(**ip2):
    return ([Ip2_FrictMat_FrictMat_MindlinPhys(**ip2)], [Law2_ScGeom_MindlinPhys_Mindlin()])


def single_collision(en=None, betan=None, v0=1.0):
    S = Scene()
    m = S.materials.append(FrictMat(young=E, poisson=NU, frictionAngle=0.5, density=RHO))
    S.bodies.append([sphere((0, 0, 0), R, material=m, fixed=True), sphere((0, 0, 2 * R + 1e-6), R, material=m)])
    S.bodies[1].state.vel = (0, 0, -v0)
    params = {"en": MatchMaker(algo="val", val=en)} if en is not None else ({"betan": betan} if betan is not None else {})
    S.engines = engines(hertz(**params))
    return S


def test_physics_constants_equal_yades():
    # Yade 2023.02a, Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5) between two FrictMat(young=1e7,
    # poisson=0.3) spheres of radius 0.1: kno 1638145.0384613846, kso 2023590.9298640632,
    # betan = betas 0.2330248576834424.
    S = Scene()
    m = S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    S.bodies.append([sphere((0, 0, 0), 0.1, material=m, fixed=True), sphere((0, 0, 0.199), 0.1, material=m)])
    S.engines = engines(hertz(en=0.5))
    S.dt = 1e-6
    S.step()
    from talus import _dem
    x = _dem.contact_extra(S._cpp)[0]
    assert x["kno"] == pytest.approx(1638145.0384613846, rel=1e-14)
    assert x["kso"] == pytest.approx(2023590.9298640632, rel=1e-14)
    assert x["betan"] == pytest.approx(0.2330248576834424, rel=1e-14) and x["betas"] == x["betan"]
    c = S.contacts()[0]
    assert c["kn"] == pytest.approx(1.5 * x["kno"] * math.sqrt(c["penetrationDepth"]), rel=1e-14)


@pytest.mark.parametrize("en", [1.0, 0.9, 0.5, 0.3])
def test_restitution_equals_the_contact_model(en):
    S = single_collision(en=en)
    mass = S.bodies[1].state.mass
    kno = 4 / 3 * E / (2 * (1 - NU ** 2)) * math.sqrt(R / 2)
    tc = hertz_contact_time(mass, kno, 1.0)
    S.dt = 2e-5 * tc                                         # the dashpot sees half-step velocities
    run_collision(S)
    e = S.bodies[1].state.vel[2] / 1.0
    expected = hertz_restitution(mass, kno, thornton_damping_ratio(en), 1.0)
    assert e == pytest.approx(expected, rel=1e-4)
    # Thornton's fit maps the requested en to the damping ratio to within about a percent.
    assert e == pytest.approx(en, rel=2e-2)


def test_restitution_does_not_depend_on_the_impact_speed():
    # The Hertz dashpot scales with u^(1/4): restitution is independent of the speed.
    values = []
    for v0 in (0.3, 3.0):
        S = single_collision(betan=0.2, v0=v0)
        S.dt = 2e-8
        run_collision(S)
        values.append(S.bodies[1].state.vel[2] / v0)
    assert values[0] == pytest.approx(values[1], rel=1e-4)


@pytest.mark.parametrize("friction", [0.0, 0.5])
def test_elastic_collision_conserves_energy(friction):
    # Oblique: frictionless, kinetic energy is conserved to 1e-6; with friction the contact
    # slips where the normal force vanishes (start and end), and the friction's dissipation
    # closes the balance to 1e-4. That gap does not shrink with dt: the shear spring is loaded
    # through lever arms r (Yade's avoidGranularRatcheting) while its force acts at the contact
    # point, r - u/2 from the centres, so their works differ at order u / r of the shear work.
    S = Scene()
    m = S.materials.append(FrictMat(young=E, poisson=NU, frictionAngle=friction, density=RHO))
    S.bodies.append([sphere((0, 0, 0), R, material=m), sphere((0.3 * R, 0.2 * R, 2 * R + 1e-6), R, material=m)])
    S.bodies[0].state.vel, S.bodies[1].state.vel = (0.02, 0, 0.5), (0, 0, -0.5)
    S.engines = engines(hertz())
    S.trackEnergy = True
    S.dt = 1e-8
    before = S.energy.total()
    run_collision(S)
    assert S.energy["elastPotential"] == 0
    assert abs(S.energy.total() - before) < (1e-6 if friction == 0 else 1e-4) * before
    if friction == 0:
        assert S.energy["plastDissip"] == 0
    else:
        assert S.energy["plastDissip"] > 1e-4 * before


def test_bad_parameters_are_refused():
    with pytest.raises(ValueError, match="only one of en, betan"):
        InteractionLoop([], *hertz(en=0.5, betan=0.1))
    with pytest.raises(ValueError, match=r"en must be in \(0, 1\]"):
        InteractionLoop([], *hertz(en=1.5))
    with pytest.raises(TypeError, match="no parameter"):
        Ip2_FrictMat_FrictMat_MindlinPhys(krot=1.0)


@pytest.mark.parametrize("angle_deg, slides", [(25.0, False), (28.0, False), (30.0, True), (35.0, True)])
def test_incline_slides_exactly_above_the_friction_angle(angle_deg, slides):
    # A non-rotating sphere resting on a wall at its static Hertz overlap, gravity tilted by
    # `angle` from the wall's normal: it sticks below the friction angle of 29 deg and slides
    # with acceleration g (sin a - cos a tan phi) above it.
    phi, a = math.radians(29.0), math.radians(angle_deg)
    estar = 1e7 / (2 * (1 - 0.3 ** 2))
    kno = 4 / 3 * estar * math.sqrt(0.05)      # against a wall Yade's geometry gives R* = r / 2
    mass, overlap, drift, acceleration = slide_on_incline(
        hertz(), a, phi, lambda mass: (mass * 9.81 * math.cos(a) / kno) ** (2 / 3))
    if slides:
        assert acceleration == pytest.approx(9.81 * (math.sin(a) - math.cos(a) * math.tan(phi)), rel=1e-6)
    else:
        ks = 8 * math.sqrt(0.05) * (1e7 / 2.6 / 2 / 1.7) * math.sqrt(overlap)
        assert abs(drift) <= 2 * mass * 9.81 * math.sin(a) / ks
