"""Yade's triaxial tutorial, small (examples/triax-tutorial/script-session1.py): spheres in a
box of six walls (aabbWalls), grown by a TriaxialStressController to an isotropic stress, then
compressed by the walls themselves (internalCompaction off: each wall servo-controlled by the
force the spheres put on it). A script written for one process, run as it is by `talus run` and
by `mpirun -np N talus run` (the distributed DEM's parity case dem.mpi.parity.triax-box,
cases/dem/dem_mpi_parity_walls.py, and tests/dem/distributed/test_mpi_clumps_walls.py).

Arguments: spheres, steps, output file (JSON: every body's position by id every 100 steps, the
walls' stresses, the porosity, the mean stress and the unbalanced force at the end, the halo
traffic per process). The spheres grow for the first 40 % of the steps, then the walls move.
"""
import json
import sys

from yade import pack
from talus.dem import distributed

spheres, steps, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
young = 5e6
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=radians(30), density=2600, label='spheres'))
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=0, density=0, label='walls'))
mn, mx = Vector3(0, 0, 0), Vector3(1, 1, 1)
wallIds = O.bodies.append(aabbWalls([mn, mx], thickness=0, material='walls'))
cloud = pack.SpherePack()
cloud.makeCloud(mn, mx, -1, 0.3333, spheres, False, 0.95, seed=1)
O.bodies.append([sphere(center, rad, material='spheres') for center, rad in cloud])
triax = TriaxialStressController(maxMultiplier=1. + 2e4 / young, finalMaxMultiplier=1. + 2e3 / young, thickness=0,
                                 stressMask=7, internalCompaction=True)
triax.goal1 = triax.goal2 = triax.goal3 = -10000
samples = []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process


def compress():
    # the packing grown: from now on the walls move, each by the force on it
    triax.internalCompaction = False
    triax.goal1 = triax.goal2 = triax.goal3 = -20000


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GlobalStiffnessTimeStepper(active=1, timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
    triax,
    NewtonIntegrator(damping=0.2),
    PyRunner(command='sample()', iterPeriod=100),
    PyRunner(command='compress()', iterPeriod=steps, firstIterRun=int(0.4 * steps)),
]
O.run(steps, True)
sample()                                               # the state after the last step
# Collective reads (every process calls them), then the file from process 0.
result = {"positions": samples, "traffic": distributed.traffic(), "unbalanced": unbalancedForce(),
          "stress": [list(triax.stress(k)) for k in range(6)], "porosity": triax.porosity,
          "meanStress": triax.meanStress, "dt": O.dt}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
