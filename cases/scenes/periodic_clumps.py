"""Clumps of two spheres in a deforming periodic cell: a script written for one process, run as it
is by `talus run` and by `mpirun -np N talus run` (tests/dem/distributed/test_mpi_clumps_periodic.py).

Arguments: clumps, steps, output file (JSON), mode, and optionally `grow` (growParticles(1.05)
at a third of the steps: the clumps grow about their centres) and `rebalance` (under mpirun,
partition again at every re-detection the measured loads differ at all:
distributed.rebalanceThreshold 1, so that bodies land on processes that held no copy of them):

- `triax`: a loose periodic cloud (makeCloud, rMean 0.1, rRelFuzz 0.3, seed 1), each sphere made
  a clump of two spheres inside it (radii 0.7 r and 0.5 r, their centres 0.3 r and 0.5 r either
  side of the sphere's, along a direction of its own), every fourth left a free sphere,
  compacted isotropically to -100 kPa by PeriTriaxController (dynCell, maxStrainRate 1/s).
- `shear`: the same clumps in a cell compressed at 0.7/s along each axis and sheared (xz) at
  0.8/s by O.cell.velGrad.

FrictMat (E 1e7, poisson 0.3, friction 0.5 rad, density 1000), linear Cundall-Strack law,
Cundall damping 0.2, no gravity, dt half the P-wave step.

Output: every body's (unwrapped) position every 100 steps and after the last step, the cell's
hSize then, getStress() and O.energy's terms after the last step, the halo traffic per process.
"""
import json
import math
import sys

from yade import pack
from talus.dem import distributed

clumps, steps, output, mode = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
options = sys.argv[5:]
if mode not in ("triax", "shear") or not set(options) <= {"grow", "rebalance"}:
    raise SystemExit(f"mode {mode!r}, options {options}: triax or shear, then grow and rebalance or neither")
grow = "grow" in options
if "rebalance" in options:
    distributed.rebalanceThreshold = 1
sigma = -1e5
size = 2.0 * (clumps / 458.0) ** (1 / 3.0)

O.periodic = True
O.cell.hSize = Matrix3(size, 0, 0, 0, size, 0, 0, 0, size)
O.materials.append(FrictMat(young=1e7, poisson=.3, frictionAngle=.5, density=1000))
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (size, size, size), rMean=.1, rRelFuzz=.3, periodic=True, num=clumps, seed=1)
for k, (c, r) in enumerate(cloud):
    if k % 4 == 3:
        O.bodies.append(utils.sphere(c, r))
        continue
    # a direction of its own for each clump (the golden angle around z), so that clumps interlock
    a, z = 2.39996 * k, 1 - 2 * (k + .5) / clumps
    d = Vector3(math.sqrt(1 - z * z) * math.cos(a), math.sqrt(1 - z * z) * math.sin(a), z)
    O.bodies.appendClumped([utils.sphere(c - .3 * r * d, .7 * r), utils.sphere(c + .5 * r * d, .5 * r)])

engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
           InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                           [Law2_ScGeom_FrictPhys_CundallStrack()])]
if mode == "triax":
    engines.append(PeriTriaxController(label="triax", goal=(sigma, sigma, sigma), stressMask=7, dynCell=True,
                                       maxStrainRate=(1, 1, 1), maxUnbalanced=.1, relStressTol=1e-3))
else:
    O.cell.velGrad = Matrix3(-.7, 0, .8, 0, -.7, 0, 0, 0, -.7)
O.engines = engines + [NewtonIntegrator(damping=.2), PyRunner(command="sample()", iterPeriod=100)]
O.dt = .5 * PWaveTimeStep()
O.trackEnergy = True
samples, cells = [], []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process
    cells.append([list(O.cell.hSize.row(i)) for i in range(3)])


if grow:
    O.run(steps // 3, True)
    growParticles(1.05)
O.run(steps - O.iter, True)
sample()                                               # the state after the last step
result = {"positions": samples, "cells": cells, "stress": [list(getStress().row(i)) for i in range(3)],
          "energy": {k: O.energy[k] for k in O.energy.keys()}, "traffic": distributed.traffic(),
          "unbalanced": unbalancedForce()}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
