"""Spheres on a shaking floor of facets, pushed by a moving wall and stirred by a turning paddle:
a script written for one process, run as it is by `talus run` and by `mpirun -np N talus run`
(the distributed DEM's test of kinematic and force engines, tests/dem/distributed/).

Arguments: spheres, steps, output file (JSON: the positions of every body by id every 100 steps,
the halo traffic per process, the vertical force on the floor and the force on the pushing wall,
each summed over its processes).

The floor (two facets) oscillates vertically (HarmonicMotionEngine), the wall at x = 0 moves in
(TranslationEngine), a paddle of two facets turns about the vertical axis through the box's
centre (RotationEngine, orbiting it); gravity comes from a GravityEngine, and a ForceEngine pushes
the first ten spheres sideways. Linear Cundall-Strack contacts (FrictMat).
"""
import json
import sys

from yade import pack
from talus.dem import distributed

spheres, steps, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
side = (spheres / 400.0) ** (1 / 3.0)
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0.14), (side, side, 0.14 + 1.5 * side), rMean=0.04, rRelFuzz=0.3, num=spheres, seed=1)
first = len(O.bodies)
cloud.toSimulation()
floor = O.bodies.append([utils.facet(((-1, -1, 0), (side + 1, -1, 0), (side + 1, side + 1, 0))),
                         utils.facet(((-1, -1, 0), (side + 1, side + 1, 0), (-1, side + 1, 0)))])
pusher = O.bodies.append(utils.wall(0, axis=0, sense=1))
O.bodies.append([utils.wall(side, axis=0, sense=-1), utils.wall(0, axis=1, sense=1), utils.wall(side, axis=1, sense=-1)])
c = side / 2
paddle = O.bodies.append([utils.facet(((c - 0.3, c, 0.02), (c + 0.3, c, 0.02), (c + 0.3, c, 0.12))),
                          utils.facet(((c - 0.3, c, 0.02), (c + 0.3, c, 0.12), (c - 0.3, c, 0.12)))])
samples = []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GravityEngine(gravity=(0, 0, -9.81), warnOnce=False),
    ForceEngine(force=(0.02, 0, 0), ids=range(first, first + 10)),
    HarmonicMotionEngine(A=(0, 0, 0.005), f=(0, 0, 20), ids=floor),
    TranslationEngine(translationAxis=(1, 0, 0), velocity=0.05, ids=[pusher]),
    RotationEngine(rotationAxis=(0, 0, 1), angularVelocity=3.0, rotateAroundZero=True, zeroPoint=(c, c, 0),
                   ids=paddle),
    NewtonIntegrator(damping=0.3),
    PyRunner(command='sample()', iterPeriod=100),
]
O.dt = 0.7 * PWaveTimeStep()
O.run(steps, True)
sample()                                               # the state after the last step
result = {"positions": samples, "traffic": distributed.traffic(),
          "floor_force": sum(O.forces.f(i)[2] for i in floor), "pusher_force": O.forces.f(pusher)[0]}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
