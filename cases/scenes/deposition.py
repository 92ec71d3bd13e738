"""Spheres falling onto the walls of a box under gravity: a script written for one process, run
as it is by `talus run` and by `mpirun -np N talus run` (the distributed DEM's parity case,
cases/dem/dem_mpi_parity.py).

Arguments: spheres, steps, output file (JSON: the positions of every body by id every 100 steps,
the halo traffic per process, the final unbalanced force).
"""
import json
import sys

from yade import pack
from talus.dem import distributed

spheres, steps, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
side = (spheres / 400.0) ** (1 / 3.0)
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (side, side, 2 * side), rMean=0.04, rRelFuzz=0.3, num=spheres, seed=1)
cloud.toSimulation()
for axis in range(3):
    O.bodies.append(utils.wall(0, axis=axis, sense=1))
    if axis < 2:
        O.bodies.append(utils.wall(side, axis=axis, sense=-1))
samples = []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process
    print(O.iter, unbalancedForce())


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
    PyRunner(command='sample()', iterPeriod=100),
]
O.dt = 0.7 * PWaveTimeStep()
O.run(steps, True)
sample()                                               # the state after the last step
# Collective reads (every process calls them), then the file from process 0.
result = {"positions": samples, "traffic": distributed.traffic(), "unbalanced": unbalancedForce(),
          "floor_force": O.forces.f(spheres + 4)[2]}   # the floor (the fifth wall), summed over processes
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
