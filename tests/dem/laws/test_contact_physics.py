"""Contact physics against analytic solutions: free fall, a single bounce, restitution of the
visco-elastic contact, energy of elastic collisions, the friction threshold on an incline."""
import math

import pytest

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, Law2_ScGeom_ViscElPhys_Basic,
                       NewtonIntegrator, Scene, ViscElMat, sphere, wall)
from talus.dem.analysis.analytic import spring_dashpot_restitution

LINEAR = ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])


def engines(laws, gravity=(0, 0, 0), damping=0.0):
    return [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *laws),
            NewtonIntegrator(gravity=gravity, damping=damping)]


def run_collision(scene, max_steps=10**7, chunk=200):
    """Step until a contact has formed and ended (no gravity: after the collision the bodies
    fly freely, so overshooting by part of a chunk changes nothing)."""
    touched = False
    for _ in range(max_steps // chunk):
        scene.run(chunk)
        n = scene._cpp.realContactCount()
        touched = touched or n > 0
        if touched and n == 0:
            return
    raise AssertionError("the collision did not end")


def test_free_fall_is_the_exact_parabola():
    # Leap-frog is exact for a constant force: with v(-dt/2) = 0 the positions lie on the
    # parabola x(t) = x0 - g dt t / 2 - g t^2 / 2.
    S = Scene()
    S.bodies.append(sphere((0, 0, 10), 0.1))
    S.engines = engines(LINEAR, gravity=(0, 0, -9.81))
    S.dt = 1e-3
    S.run(2000)
    t = S.time
    expected = 10 - 9.81 * S.dt * t / 2 - 9.81 * t * t / 2
    assert S.bodies[0].state.pos[2] == pytest.approx(expected, rel=1e-9)
    assert S.bodies[0].state.vel[2] == pytest.approx(-9.81 * t, rel=1e-9)


def test_single_bounce_follows_the_analytic_motion():
    # A sphere dropped on a wall, linear spring, no damping: the flight down is the parabola of
    # the free-fall test, the contact half an oscillation about the spring's static deflection
    # (z - r = -A + A cos wt + (v1 / w) sin wt, A = m g / kn, w = sqrt(kn / m)), the flight up
    # the parabola from r with the opposite speed. Leap-frog is second order, also across the
    # spring's kink at z = r, whose phase inside a step scatters the error: 1.9e-9 of the drop
    # at dt = tc / 34000, 5.1e-10 at tc / 69000.
    r, z0, g, dt = 0.01, 0.011, 9.81, 5e-8
    S = Scene()
    mat = S.materials.append(FrictMat(young=1e6, poisson=0.3, density=2600, frictionAngle=0.0))
    S.bodies.append(wall((0, 0, 0), axis=2, material=mat))
    S.bodies.append(sphere((0, 0, z0), r, material=mat))
    S.engines = engines(LINEAR, gravity=(0, 0, -g))
    S.dt = dt
    m = S.bodies[1].state.mass
    v0 = -g * dt / 2   # v(-dt/2) = 0, as in the free-fall test
    t1 = (v0 + math.sqrt(v0 * v0 + 2 * g * (z0 - r))) / g
    times, heights, stiffness = [], [], set()
    while S.time < 2.8 * t1:   # down, bounce, up to about the start's height
        S.run(500)
        times.append(S.time)
        heights.append(S.bodies[1].state.pos[2])
        stiffness |= {c["kn"] for c in S.contacts()}
    assert len(stiffness) == 1, "one contact, of one stiffness"
    kn = stiffness.pop()
    v1 = v0 - g * t1
    w, A, B = math.sqrt(kn / m), m * g / kn, v1 / math.sqrt(kn / m)
    T = (2 * math.pi + 2 * math.atan2(B, A)) / w   # the contact's duration

    def analytic(t):
        if t < t1:
            return z0 + v0 * t - g * t * t / 2
        if t - t1 <= T:
            return r - A + A * math.cos(w * (t - t1)) + B * math.sin(w * (t - t1))
        return r - v1 * (t - t1 - T) - g * (t - t1 - T) ** 2 / 2

    error = max(abs(z - analytic(t)) for t, z in zip(times, heights))
    assert error < 1e-9 * (z0 - r)
    assert min(heights) < r - 0.5 * A   # it did bounce


def test_damping_applies_to_gravity_as_in_yade():
    # Yade 2023.02a, same set-up (g = -10, damping 0.2, dt 0.01, 10 steps): v = -0.8, z = -0.044.
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    S.engines = engines(LINEAR, gravity=(0, 0, -10), damping=0.2)
    S.dt = 0.01
    S.run(10)
    assert S.bodies[0].state.vel[2] == pytest.approx(-0.8, rel=1e-12)
    assert S.bodies[0].state.pos[2] == pytest.approx(-0.044, rel=1e-12)


@pytest.mark.parametrize("against_wall", [False, True])
@pytest.mark.parametrize("en", [0.3, 0.5, 0.9])
def test_viscoelastic_restitution(en, against_wall):
    S = Scene()
    m = S.materials.append(ViscElMat(tc=1e-3, en=en, et=en, density=2000, frictionAngle=0.5))
    if against_wall:
        S.bodies.append([wall(0, axis=2, material=m), sphere((0, 0, 0.1001), 0.1, material=m)])
        S.bodies[1].state.vel = (0, 0, -1)
    else:
        S.bodies.append([sphere((0, 0, 0), 0.1, material=m), sphere((0, 0, 0.2001), 0.1, material=m)])
        S.bodies[0].state.vel, S.bodies[1].state.vel = (0, 0, 0.5), (0, 0, -0.5)
    S.engines = engines(([Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]))
    # The dashpot sees the half-step velocity: the error is first order in dt / tc.
    S.dt = 2e-5 * 1e-3
    mass = S.bodies[1].state.mass
    run_collision(S)
    v = S.velocities()
    separation_speed = v[1, 2] - (0.0 if against_wall else v[0, 2])
    # As Yade: the spring and dashpot are those of the reduced mass m/2 of two such spheres (a
    # wall takes the sphere's mass) and the force never pulls, so the restitution is en only
    # for two free spheres whose force could pull; a wall stops the sphere's whole mass.
    tc, reduced = 1e-3, mass / 2
    kn = (math.pi ** 2 + math.log(en) ** 2) / tc ** 2 * reduced
    cn = -2 * math.log(en) / tc * reduced
    expected = spring_dashpot_restitution(mass if against_wall else reduced, kn, cn)
    assert separation_speed == pytest.approx(expected, rel=1e-4)
    assert abs(separation_speed - en) > 1e-3   # not en: the force does not pull


def test_elastic_collision_conserves_energy():
    # Oblique and frictionless (friction would rightly dissipate energy while sliding).
    S = Scene()
    m = S.materials.append(FrictMat(young=1e7, density=2000, frictionAngle=0.0))
    S.bodies.append([sphere((0, 0, 0), 0.1, material=m), sphere((0.05, 0.03, 0.2001), 0.1, material=m)])
    S.bodies[0].state.vel, S.bodies[1].state.vel = (0.1, 0, 0.5), (0, 0, -0.5)
    S.engines = engines(LINEAR)
    mass = S.bodies[0].state.mass
    tc = math.pi * math.sqrt(mass / 2 / (1e7 * 0.1))      # kn = E r for equal spheres
    # The error comes from the discrete start and end of the contact, O((dt / tc)^2).
    S.dt = 1e-4 * tc

    def energy():
        v, w = S.velocities(), S.angular_velocities()
        inertia = S._cpp.inertia()
        return 0.5 * mass * float((v * v).sum()) + 0.5 * float((inertia * w * w).sum())

    before = energy()
    run_collision(S)
    assert abs(energy() - before) < 1e-6 * before


def slide_on_incline(laws, a, phi, overlap):
    """A non-rotating sphere (r 0.1, E 1e7, poisson 0.3, density 2000, friction angle phi) resting
    on a wall at the overlap `overlap(mass)`, gravity tilted by `a` from the wall's normal. After
    the start-up transient (the fresh contact has no shear force yet), two instants 30 000 steps
    of 1e-5 s apart: a sliding body accelerates exactly as Coulomb friction says, a sticking one
    only oscillates on its shear spring. Returns (mass, overlap, displacement, mean acceleration)
    along the slope between the two."""
    S = Scene()
    m = S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=phi, density=2000))
    S.bodies.append([wall(0, axis=2, material=m), sphere((0, 0, 1.0), 0.1, material=m)])
    mass = S.bodies[1].state.mass
    delta = overlap(mass)
    S.bodies[1].state.pos = (0, 0, 0.1 - delta)
    S.bodies[1].state.blockedDOFs = "XYZ"
    S.engines = engines(laws, gravity=(9.81 * math.sin(a), 0, -9.81 * math.cos(a)))
    S.dt = 1e-5
    S.run(20000)
    x1, v1, t1 = S.bodies[1].state.pos[0], S.bodies[1].state.vel[0], S.time
    S.run(30000)
    x2, v2, t2 = S.bodies[1].state.pos[0], S.bodies[1].state.vel[0], S.time
    return mass, delta, x2 - x1, (v2 - v1) / (t2 - t1)


@pytest.mark.parametrize("angle_deg, slides", [(25.0, False), (28.0, False), (30.0, True), (35.0, True)])
def test_block_on_incline_slides_exactly_above_the_friction_angle(angle_deg, slides):
    # A non-rotating sphere resting on a wall, gravity tilted by `angle` from the wall's
    # normal: it must stay (up to the elastic shear displacement) below the friction angle of
    # 29 deg and slide with acceleration g (sin a - cos a tan phi) above it.
    phi = math.radians(29.0)
    a = math.radians(angle_deg)
    mass, _, drift, acceleration = slide_on_incline(
        LINEAR, a, phi, lambda mass: mass * 9.81 * math.cos(a) / (1e7 * 0.1))   # at rest: kn = E r against a wall
    if slides:
        assert acceleration == pytest.approx(9.81 * (math.sin(a) - math.cos(a) * math.tan(phi)), rel=1e-6)
    else:
        spring = 2 * mass * 9.81 * math.sin(a) / (0.3 * 1e7 * 0.1)  # peak-to-peak on ks = E r nu
        assert abs(drift) <= spring


def test_physics_parameters_equal_yades():
    # Stiffnesses Yade 2023.02a gives for the same pairs (Ip2_FrictMat_FrictMat_FrictPhys,
    # Ip2_ViscElMat_ViscElMat_ViscElPhys for two equal spheres).
    S = Scene()
    m1 = S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.4, density=2000))
    m2 = S.materials.append(FrictMat(young=3e7, poisson=0.2, frictionAngle=0.6, density=2000))
    v = S.materials.append(ViscElMat(tc=1e-3, en=0.5, et=0.6, density=2000, frictionAngle=0.3))
    S.bodies.append([sphere((0, 0, 0), 0.1, material=m1), sphere((0, 0, 0.2499), 0.15, material=m2),
                     wall((0, 0, -0.095), axis=2, material=m1)])
    S.bodies.append([sphere((5, 0, 0), 0.1, material=v), sphere((5, 0, 0.19), 0.1, material=v)])
    S.engines = engines(([Ip2_FrictMat_FrictMat_FrictPhys(), Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                         [Law2_ScGeom_FrictPhys_CundallStrack(), Law2_ScGeom_ViscElPhys_Basic()]))
    S.dt = 1e-6
    S.step()
    got = {(c["id1"], c["id2"]): c for c in S.contacts()}
    yade = {(0, 1): (1636363.6363636365, 450000.0, 0.4227932187381618),
            (2, 0): (1000000.0, 300000.0, 0.4227932187381618),
            (2, 3): (1980198.0198019801, 592885.3754940712, 0.30933624960962325),
            (3, 4): (43354219.11896042, 12124210.560003292, 0.30933624960962325)}
    for pair, (kn, ks, tan_phi) in yade.items():
        assert got[pair]["kn"] == pytest.approx(kn, rel=1e-12)
        assert got[pair]["ks"] == pytest.approx(ks, rel=1e-12)
        assert got[pair]["tangensOfFrictionAngle"] == pytest.approx(tan_phi, rel=1e-12)
    assert got[(3, 4)]["cn"] == pytest.approx(5806.896240809606, rel=1e-12)
    assert got[(3, 4)]["cs"] == pytest.approx(1222.7093538199315, rel=1e-12)


def test_persistent_torque_spins_a_free_sphere_at_torque_over_inertia():
    """The exchange interface's persistent torques stay applied step after step, as the
    persistent forces do (forces() and torques() are this step's and reset every step)."""
    S = Scene()
    S.materials.append(FrictMat(density=1000))
    S.bodies.append(sphere((0, 0, 0), 0.1))
    S.engines = engines(LINEAR)
    S.dt = 1e-3
    S.persistent_torques()[0] = (0, 0, 2e-3)
    S.run(100)
    inertia = 0.4 * S.masses()[0] * 0.1 ** 2
    assert S.angular_velocities()[0][2] == pytest.approx(2e-3 / inertia * 0.1, rel=1e-12)
    assert tuple(S.torques()[0]) == (0, 0, 2e-3)
