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


def walled_cloud(n=150, seed=1, **controller):
    scene = Scene()
    scene.materials.append(FrictMat(young=5e6, poisson=.5, frictionAngle=.5, density=2600, label="spheres"))
    scene.materials.append(FrictMat(young=5e6, poisson=.5, frictionAngle=0, density=2600, label="walls"))
    scene.bodies.append(aabbWalls(((0, 0, 0), (1, 1, 1)), material="walls"))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), -1, .3, n, False, .9, seed=seed)
    sp.toSimulation(scene, material="spheres")
    triax = TriaxialStressController(thickness=0, stressMask=7, **controller)
    triax.goal1 = triax.goal2 = triax.goal3 = -1e4
    scene.engines = frict_engines(GlobalStiffnessTimeStepper(timeStepUpdateInterval=10), triax)
    return scene, triax


def run_until(scene, condition, chunk=200, limit=40000):
    while not condition():
        assert scene.iter < limit, f"not reached in {limit} steps"
        scene.run(chunk)


def test_triax_walls_reach_isotropic_stress():
    scene, triax = walled_cloud(internalCompaction=False)
    run_until(scene, lambda: abs(triax.meanStress + 1e4) < 1e-3 * 1e4 and unbalancedForce(scene=scene) < .01)
    for k in range(6):
        axis = k // 2
        assert triax.stress(k)[axis] == pytest.approx(-1e4, rel=.02), k
    # porosity from the box between the walls and the spheres' volume
    box = triax.width * triax.height * triax.depth
    assert triax.porosity == pytest.approx(1 - triax.particlesVolume / box, rel=1e-12)
    triax._cpp.computeStressStrain(scene._cpp)   # strains are updated every computeStressStrainInterval steps
    assert triax.strain[0] == pytest.approx(math.log(triax.width / triax.width0), rel=1e-12)


def test_internal_compaction_grows_the_spheres_to_the_goal():
    scene, triax = walled_cloud(internalCompaction=True, maxMultiplier=1.004, finalMaxMultiplier=1.0004)
    r0 = scene.radii()[6:].copy()
    run_until(scene, lambda: abs(triax.meanStress + 1e4) < 1e-3 * 1e4 and unbalancedForce(scene=scene) < .01)
    growth = scene.radii()[6:] / r0
    assert np.allclose(growth, growth[0], rtol=1e-12) and growth[0] > 1.1    # homothetic growth
    assert triax.width == 1 and triax.height == 1 and triax.depth == 1       # walls did not move
    solid = np.sum(4 / 3 * np.pi * scene.radii()[6:] ** 3)
    assert triax.porosity == pytest.approx(1 - solid, rel=1e-6)


def test_strain_rate_control_and_homogenised_stress_equals_wall_stress():
    scene, triax = walled_cloud(internalCompaction=False)
    run_until(scene, lambda: abs(triax.meanStress + 1e4) < 1e-3 * 1e4 and unbalancedForce(scene=scene) < .01)
    triax.stressMask, triax.goal2 = 5, -0.05
    scene.run(600)
    assert triax.strainRate[1] == pytest.approx(-0.05, rel=.01)   # relaxed by strainDamping 0.99 per step
    assert triax.stress(1)[0] == pytest.approx(-1e4, rel=.05)
    # Walls stopped, let the packing settle: then the Love-Weber stress of the sample (sphere-wall
    # contacts with the branch to the wall) is the wall force over area, component by component.
    triax.dead = True
    for k in range(6):
        scene.bodies[k].state.vel = (0, 0, 0)
    scene.engines[-1].damping = .8
    run_until(scene, lambda: unbalancedForce(scene=scene) < 1e-9, chunk=500, limit=200000)
    triax._cpp.computeStressStrain(scene._cpp)
    volume = triax.width * triax.height * triax.depth
    stress = getStress(volume, scene=scene)
    walls = [-(triax.stress(2 * a)[a] + triax.stress(2 * a + 1)[a]) / 2 for a in range(3)]
    assert np.allclose(np.diag(stress), [-w for w in walls], rtol=1e-6, atol=0), (np.diag(stress), walls)


def test_checkpoint_restart_with_controllers_is_bit_identical(tmp_path):
    scene, triax = walled_cloud(n=80, internalCompaction=False)
    scene.run(300)
    scene.save(tmp_path / "triax.h5")
    scene.run(200)
    expected = scene.positions().copy()
    scene.load(tmp_path / "triax.h5")
    scene.run(200)
    assert np.array_equal(scene.positions(), expected)
    peri = periodic_cloud(n=60)
    peri.engines = frict_engines(PeriTriaxController(goal=(-1e4, -1e4, -1e4), stressMask=7, dynCell=True,
                                                     doneHook="pass"))
    peri.dt = .5 * PWaveTimeStep(peri)
    peri.run(300)
    peri.save(tmp_path / "peri.h5")
    peri.run(200)
    expected = peri.positions().copy()
    peri.load(tmp_path / "peri.h5")
    peri.run(200)
    assert np.array_equal(peri.positions(), expected)
