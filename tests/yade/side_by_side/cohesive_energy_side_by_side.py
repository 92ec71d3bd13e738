"""Law2_ScGeom6D_CohFrictPhys_CohesionMoment's elastic energies (normal, shear, bending,
twist) and NewtonIntegrator(kinSplit=True)'s O.energy keys, written so that the same file runs
in Yade (`yade -n -x`) and in Talus: the scene of Yade's simple-scene-energy-tracking.py (two
spinning spheres on a box) with moments. Prints one RESULT line
(tests/yade/test_cohesive_energy.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(CohFrictMat(young=3e8, poisson=0.3, frictionAngle=0.5, density=2600, isCohesive=False,
                               alphaKr=0.031, alphaKtw=0.031, momentRotationLaw=True, etaRoll=5.0, label="grains"))
law = Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True)
O.trackEnergy = True
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Box_Sphere_ScGeom6D()],
                             [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()], [law]),
             NewtonIntegrator(damping=0.2, kinSplit=True, gravity=(0, 0, -9.81))]
O.bodies.append(box(center=[0, 0, 0], extents=[.5, .5, .5], fixed=True, material="grains"))
O.bodies.append(sphere([0, 0, 1.499], 1, material="grains"))
O.bodies.append(sphere([0.05, 0, 3.49], 1, material="grains"))
O.bodies[1].state.angVel = (0, 3, 3)
O.bodies[2].state.angVel[0] = 2          # Yade's state vectors are references
O.dt = 1e-5
O.run(200, True)
out = {"energies": [law.normElastEnergy(), law.shearElastEnergy(), law.bendingElastEnergy(),
                    law.twistElastEnergy()],
       "keys": sorted(k for k in ("kinTrans", "kinRot", "kinetic") if k in O.energy.keys()),
       "contacts": O.interactions.countReal(), "angVel": list(O.bodies[2].state.angVel)}
print("RESULT " + json.dumps(out))
