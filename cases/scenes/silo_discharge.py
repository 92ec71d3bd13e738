"""A silo of facets discharging through its floor's orifice, spheres erased as they leave: a
script written for one process, run as it is by `talus run` and by `mpirun -np N talus run`
(the distributed DEM's parity case, cases/dem/dem_mpi_parity.py).

Arguments: spheres, steps, output file (JSON: the positions of every body by id every 100 steps,
NaN for the erased ones; the spheres left and the steps they were counted at; the halo traffic
per process; the floor's vertical force summed over its facets; under mpirun the load measured
per process and the rebalances, talus.dem.distributed.balance()); then optionally `side=N`, the
spheres along a side of the lattice (default: enough for eight layers, at least 8: a wide silo;
fewer make it tall), `rebalance=X`, talus.dem.distributed.rebalanceThreshold (a number, or
`none`), and `clumps=1`: three spheres of every four made clumps of two spheres inside them
(radii 0.7 and 0.5 of the sphere's), a clump erased with its members as it leaves.

A square box of facets open at the top (16 triangles), its floor with a square orifice four
diameters wide; spheres of radii 0.9-1 r on a jittered lattice above the floor, falling from
rest; FrictMat (poisson 0.3, friction 0.5 rad), Hertz-Mindlin with restitution 0.5, gravity
-9.81 along z. Every 50 steps a PyRunner erases the spheres that have fallen two radii below the
floor: it decides from talus.dem.distributed.positions() (every body's position, on every
process), so every process erases the same bodies, as the rule of O.bodies.erase under mpirun
asks.
"""
import json
import math
import sys

import numpy as np

from talus.dem import distributed

spheres, steps, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
options = dict(a.split("=", 1) for a in sys.argv[4:])
if "rebalance" in options:
    distributed.rebalanceThreshold = None if options["rebalance"] == "none" else float(options["rebalance"])
radius, young, density = 0.005, 1e6, 2600.0
rng = np.random.default_rng(7)
spacing = 2.1 * radius
side = int(options.get("side", max(8, math.ceil(math.sqrt(spheres / 8)))))
layers = math.ceil(spheres / side**2)
i, j, k = np.meshgrid(np.arange(side), np.arange(side), np.arange(layers), indexing="ij")
centres = (np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1) + 0.5) * spacing
centres = (centres + rng.uniform(-0.05 * radius, 0.05 * radius, centres.shape))[:spheres]
radii = radius * rng.uniform(0.9, 1.0, len(centres))
width, height = side * spacing, 1.3 * layers * spacing
a, b = width / 2 - 4 * radius, width / 2 + 4 * radius
exit_z = -2 * radius

material = O.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))


def rectangle(p, q, r, s):
    return [utils.facet((p, q, r), material=material), utils.facet((p, r, s), material=material)]


walls = []
for x in (0.0, width):
    walls += rectangle((x, 0, 0), (x, width, 0), (x, width, height), (x, 0, height))
for y in (0.0, width):
    walls += rectangle((0, y, 0), (width, y, 0), (width, y, height), (0, y, height))
floor = []
for x0, x1, y0, y1 in ((0, width, 0, a), (0, width, b, width), (0, a, a, b), (b, width, a, b)):
    floor += rectangle((x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0))
floor_ids = O.bodies.append(floor)
O.bodies.append(walls)
clumped = options.get("clumps") == "1"
falling, members = [], {}                           # spheres and clumps; each clump's members
for n, (c, r) in enumerate(zip(centres, radii)):
    if not clumped or n % 4 == 3:
        falling.append(O.bodies.append(utils.sphere(tuple(c), r, material=material)))
        continue
    d = Vector3(1, n % 3 - 1, n % 2)                # one of six directions
    d *= r / d.norm()
    clump, ids = O.bodies.appendClumped([utils.sphere(Vector3(*c) - .3 * d, .7 * r, material=material),
                                         utils.sphere(Vector3(*c) + .5 * d, .5 * r, material=material)])
    falling.append(clump)
    members[clump] = ids
left, erased = set(falling), []
samples, counts = [], []


def erase_fallen():
    z = distributed.positions()[:, 2]               # every body, on every process
    for i in sorted(i for i in left if z[i] < exit_z):
        O.bodies.erase(i, eraseClumpMembers=True)
        left.discard(i)
        erased.extend([i] + members.get(i, []))


def sample():
    p = distributed.positions()
    p[sorted(erased)] = np.nan                      # erased bodies: no position
    samples.append(p.tolist())
    counts.append([O.iter, len(left)])


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(gravity=(0, 0, -9.81)),
    PyRunner(command="erase_fallen()", iterPeriod=50),
    PyRunner(command="sample()", iterPeriod=100),
]
O.dt = 0.5 * radii.min() * math.sqrt(density / young)
O.run(steps, True)
sample()                                            # the state after the last step
result = {"positions": samples, "left": counts, "traffic": distributed.traffic(),
          "floor_force": sum(O.forces.f(i)[2] for i in floor_ids),     # each summed over the processes
          "balance": distributed.balance()}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
