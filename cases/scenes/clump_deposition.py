"""Clumps of two and three spheres and free spheres falling into a box of walls onto a fixed
Yade box (utils.box) lying on the floor: a script written for one process, run as it is by
`talus run` and by `mpirun -np N talus run` (the distributed DEM's clumps and boxes: the parity
case dem.mpi.parity.clumps, cases/dem/dem_mpi_parity_walls.py, and
tests/dem/distributed/test_mpi_clumps_walls.py).

Arguments: clumps and free spheres (every fourth a sphere), steps, output file (JSON: every
body's position by id every 100 steps, the halo traffic per process, the floor's and the box's
force summed over the processes, the kinetic energy, the energy terms (O.energy) and the
unbalanced force at the end).
"""
import json
import random
import sys

from talus.dem import distributed

clumps, steps, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
r = 0.03
across = max(2, int(round((clumps / 6) ** 0.5)))   # clumps in a layer: across x across
side = across * 5 * r
rng = random.Random(1)
for k in range(clumps):
    # on a lattice of 5 r (no two clumps overlapping), jittered, layer above layer
    x, y, z = ((k % across + 0.3 + 0.3 * rng.random()) * 5 * r, (k // across % across + 0.3 + 0.3 * rng.random()) * 5 * r,
               0.1 + k // across ** 2 * 4 * r)
    if k % 4 == 3:      # a free sphere among the clumps
        O.bodies.append(utils.sphere((x, y, z), r))
        continue
    members = [utils.sphere((x, y, z), r), utils.sphere((x + 1.2 * r, y, z + 0.3 * r), 0.8 * r)]
    if k % 2:
        members.append(utils.sphere((x, y + 1.1 * r, z - 0.4 * r), 0.9 * r))
    O.bodies.appendClumped(members)
walls = [O.bodies.append(utils.wall(0, axis=a, sense=1)) for a in range(3)]
walls += [O.bodies.append(utils.wall(side, axis=a, sense=-1)) for a in range(2)]
obstacle = O.bodies.append(utils.box((side / 2, side / 2, 0.02), (side / 5, side / 7, 0.02), fixed=True))
samples = []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
    PyRunner(command='sample()', iterPeriod=100),
]
O.dt = 0.8 * PWaveTimeStep()
O.trackEnergy = True
O.run(steps, True)
sample()                                               # the state after the last step
# Collective reads (every process calls them), then the file from process 0.
result = {"positions": samples, "traffic": distributed.traffic(), "unbalanced": unbalancedForce(),
          "floor_force": list(O.forces.f(walls[2])), "box_force": list(O.forces.f(obstacle)),
          "kinetic": utils.kineticEnergy(), "energy": {k: O.energy[k] for k in O.energy.keys()}}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
