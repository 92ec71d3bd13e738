"""A checkpoint in the middle of a deposition, written and read by a script written for one
process, run as it is by `talus run` and by `mpirun -np N talus run` (the distributed
checkpoint's tests and timings: tests/dem/distributed/test_mpi_checkpoint.py,
cases/dem/dem_mpi_checkpoint.py).

Arguments: mode, spheres, steps, checkpoint file, output file (JSON), and optionally the contact
law (linear, or hertz: Hertz-Mindlin, whose contacts keep their shear force) and flags:
`energy` (the energy tracked from the start: O.energy's terms in the output), `clumps` (three
spheres of every four made clumps of two spheres inside them, radii 0.7 r and 0.5 r).
- `save`: spheres falling onto the walls of a box; `steps` steps, O.save, `steps` steps more;
- `load`: O.load (the engines come from the file), then `steps` steps.
The output holds the positions of every body by id after the last step, the seconds O.save or
O.load took (the slowest process's), the file's size and the contacts after the first part.
"""
import json
import os
import sys
import time

from yade import pack
from talus.dem import distributed

mode, spheres, steps, checkpoint, output = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
law = sys.argv[6] if len(sys.argv) > 6 else "linear"
flags = set(sys.argv[7:])
energy = "energy" in flags


def slowest(seconds):
    """The largest of every process's seconds (collective)."""
    return max(p["seconds"] for p in distributed.per_process({"seconds": seconds}))


result = {}
if mode == "save":
    physics, contactLaw = {
        "linear": (Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack()),
        "hertz": (Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5), Law2_ScGeom_MindlinPhys_Mindlin()),
    }[law]
    O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    side = (spheres / 400.0) ** (1 / 3.0)
    cloud = pack.SpherePack()
    cloud.makeCloud((0, 0, 0), (side, side, side), rMean=0.05, rRelFuzz=0.3, num=spheres, seed=1)
    if "clumps" in flags:
        for k, (c, r) in enumerate(cloud):
            if k % 4 == 3:
                O.bodies.append(utils.sphere(c, r))
            else:
                d = Vector3(1, k % 3 - 1, k % 2)                     # one of six directions
                d *= r / d.norm()
                O.bodies.appendClumped([utils.sphere(c - .3 * d, .7 * r), utils.sphere(c + .5 * d, .5 * r)])
    else:
        cloud.toSimulation()
    for axis in range(3):
        O.bodies.append(utils.wall(0, axis=axis, sense=1))
        if axis < 2:
            O.bodies.append(utils.wall(side, axis=axis, sense=-1))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [physics], [contactLaw]),
        NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
    ]
    O.dt = 0.7 * PWaveTimeStep()
    O.trackEnergy = energy
    O.run(steps, True)
    start = time.perf_counter()
    O.save(checkpoint)
    result["save_seconds"] = slowest(time.perf_counter() - start)
    result["bytes"] = os.path.getsize(checkpoint)
else:
    start = time.perf_counter()
    O.load(checkpoint)
    result["load_seconds"] = slowest(time.perf_counter() - start)
O.run(steps, True)
result["positions"] = distributed.positions().tolist()
result["iter"] = O.iter
if O.trackEnergy:
    result["energy"] = dict(O.energy.items())
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
