"""GlobalStiffnessTimeStepper and RayleighWaveTimeStep: analytic values on one contact, Yade's
values on identical input, the update rules (default step, 5 % growth cap, maxDt, O.dt by hand)."""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.dem import *  # noqa: F401,F403

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


def sphere_on_wall(coefficient=0.5, **kw):
    scene = Scene()
    scene.materials.append(FrictMat(young=1e7, poisson=0.3, density=2000))
    scene.bodies.append([wall(0, axis=2), sphere((0, 0, 0.099), 0.1)])
    stepper = GlobalStiffnessTimeStepper(timestepSafetyCoefficient=coefficient, **kw)
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                     [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     stepper, NewtonIntegrator(damping=0.9)]
    return scene, stepper


def test_one_contact_gives_the_oscillator_period():
    scene, stepper = sphere_on_wall(0.5)
    scene.step()
    (c,) = scene.contacts()
    m = scene.bodies[1].state.mass
    # normal along z: translational stiffness max(kn, ks) = kn; rotation I/(ks r^2) = 0.4 m / ks > m / kn
    expected = 1.41044 * 0.5 * math.sqrt(m / c["kn"])
    assert abs(scene.dt - expected) <= 1e-14 * expected
    assert abs(stepper.stiffnessTimeStep(scene) - expected) <= 1e-12 * expected


def test_rotational_stiffness_governs_when_shear_is_stiff():
    scene, stepper = sphere_on_wall(0.5)
    scene.materials[0].poisson = 1.0     # ks = kn: rotation 0.4 m / ks is the shorter period
    scene.step()
    (c,) = scene.contacts()
    m = scene.bodies[1].state.mass
    assert c["ks"] == c["kn"]
    expected = 1.41044 * 0.5 * math.sqrt(0.4 * m * 0.1 ** 2 / (c["ks"] * 0.1 ** 2))
    assert abs(scene.dt - expected) <= 1e-14 * expected


def test_default_dt_before_contacts_growth_cap_and_max_dt():
    scene, stepper = sphere_on_wall(0.5)
    scene.bodies[1].state.pos = (0, 0, 0.5)       # no contact yet
    scene.step()
    assert scene.dt == 0.5 * PWaveTimeStep(scene)
    scene, stepper = sphere_on_wall(0.5, maxDt=1e-5)
    scene.step()
    assert scene.dt == 1e-5
    scene, stepper = sphere_on_wall(0.5)
    scene.step()
    first = scene.dt
    scene.materials[0].young = 1e5   # new contacts would be softer, this one keeps its stiffness
    stepper._cpp.previousDt = first / 2
    scene.step()
    assert scene.dt == pytest.approx(1.05 * first / 2, rel=1e-15)   # at most 5 % more per update


def test_active_stepper_overrides_a_step_set_by_hand_and_inactive_does_not():
    scene, stepper = sphere_on_wall(0.5)
    scene.dt = 1e-6
    scene.step()
    assert scene.dt > 1e-4          # as in Yade 2023.02a (checked): O.dt does not deactivate it
    scene, stepper = sphere_on_wall(0.5, active=False)
    scene.dt = 1e-6
    scene.step()
    assert scene.dt == 1e-6


def test_rayleigh_time_step_formula():
    scene = Scene()
    scene.materials.append(FrictMat(young=2e7, poisson=0.2, density=3000))
    scene.bodies.append([sphere((0, 0, 0), 0.2), sphere((1, 0, 0), 0.05)])
    G = 2e7 / (2 * 1.2)
    expected = math.pi * 0.05 / (0.1631 * 0.2 + 0.876605) * math.sqrt(3000 / G)
    assert RayleighWaveTimeStep(scene) == pytest.approx(expected, rel=1e-14)


@pytest.mark.skipif(shutil.which("yade") is None, reason="yade is not installed")
def test_time_steps_equal_yades():
    ours, theirs = (twin.run(TWINS / "timestepper_side_by_side.py", {}, who) for who in ("talus", "yade"))
    assert ours["n"] == theirs["n"]
    assert ours["dt"][0] == pytest.approx(theirs["dt"][0], rel=1e-14)   # the same contacts, the same step
    assert np.allclose(ours["dt"], theirs["dt"], rtol=1e-12, atol=0)
    assert ours["rayleigh"] == pytest.approx(theirs["rayleigh"], rel=1e-14)
    assert ours["pwave"] == pytest.approx(theirs["pwave"], rel=1e-14)


def test_viscel_bounds_the_step_by_the_dashpot():
    scene = Scene()
    scene.materials.append(ViscElMat(en=0.01, et=0., young=1e7, poisson=0.5, density=2000))
    scene.bodies.append([box((0, 0, 0), (1, 1, 0), fixed=True), sphere((0, 0, 0.099), 0.1)])
    stepper = GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.5, viscEl=True)
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
                     InteractionLoop([Ig2_Box_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                                     [Law2_ScGeom_ViscElPhys_Basic()]),
                     stepper, NewtonIntegrator()]
    scene.step()
    (c,) = scene.contacts()
    m, inertia = scene.bodies[1].state.mass, scene.bodies[1].state.inertia[0]
    elastic = 1.41044 * 0.5 * math.sqrt(min(m / c["kn"], inertia / (c["ks"] * 0.1 ** 2)))
    viscous = 2 * 0.5 * m / c["cn"]     # cs = 0 for the young/poisson/en form: no rotational dashpot
    assert c["cs"] == 0 and viscous < elastic
    assert scene.dt == pytest.approx(viscous, rel=1e-15)
    stepper.viscEl = False
    assert stepper.stiffnessTimeStep(scene) == pytest.approx(elastic, rel=1e-15)


@pytest.mark.skipif(shutil.which("yade") is None, reason="yade is not installed")
@pytest.mark.parametrize("en", [0.5, 0.05])
def test_viscel_time_steps_equal_yades(en):
    """en = 0.5: the springs govern; en = 0.05: the dashpots do (the step then differs from
    viscEl=False's from the first step on)."""
    script = TWINS / "timestepper_viscel_side_by_side.py"
    ours, theirs = (twin.run(script, {"en": en, "viscEl": True}, who) for who in ("talus", "yade"))
    assert ours["n"] == theirs["n"] and ours["contacts"] == theirs["contacts"]
    assert np.allclose(ours["dt"], theirs["dt"], rtol=1e-14, atol=0)
    elastic_only = twin.run(script, {"en": en, "viscEl": False}, "talus")
    assert (elastic_only["dt"][0] > 1.5 * ours["dt"][0]) == (en == 0.05)
