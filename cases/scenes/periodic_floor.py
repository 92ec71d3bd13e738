"""Spheres settling onto a floor in a periodic cell: a script written for one process, run as it
is by `talus run` and by `mpirun -np N talus run` (tests/dem/distributed/test_mpi_periodic.py:
the distributed DEM's walls, facets and boxes in a periodic cell).

Arguments: spheres, steps, output file (JSON), the floor (`wall`: utils.wall; `facet`: two
facets across the cell; `box`: a fixed utils.box across it; `none`: no floor, the spheres
falling freely, to time the floors against), the cell (`fixed`, or `shear`:
sheared by O.cell.velGrad, x growing with z at 2/s, so that the spheres above the floor are
carried along x and cross the cell's faces).

The spheres (d 0.08 m, rRelFuzz 0.2, about 8 layers of a jittered lattice 0.1 m apart, seed 1)
fill a cell of side 0.1 m times the square root of an eighth of the spheres in x and y (0.7 m
for 300), periodic across them, and fall under gravity onto the floor at z = 0.05 m; the cell
is 2 m tall, so that no sphere reaches the floor's image across z. The floors that
are not walls reach beyond the cell along x and y (the collider's allowBiggerThanPeriod, as
Yade's): a sphere meets them where it is along those axes. FrictMat (E 1e7, friction 0.5 rad),
linear Cundall-Strack law, Cundall damping 0.3, dt 0.7 of the P-wave step.

Output: every body's (unwrapped) position every 100 steps and after the last, the cell then,
the floor's force summed over the processes, the collider's re-detections, the CPU seconds of
the run and the halo traffic per process.
"""
import json
import math
import sys
import time

import numpy as np
from talus.dem import distributed

spheres, steps, output, floor, cell = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
if floor not in ("wall", "facet", "box", "none") or cell not in ("fixed", "shear"):
    raise SystemExit(f"floor {floor!r}: wall, facet or box; cell {cell!r}: fixed or shear")
SPACING, Z0, H = 0.1, 0.05, 2.0
L = SPACING * math.ceil(math.sqrt(spheres / 8))   # about 8 layers

O.periodic = True
O.cell.hSize = Matrix3(L, 0, 0, 0, L, 0, 0, 0, H)
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
rng = np.random.default_rng(1)
row = round(L / SPACING)
for k in range(spheres):
    layer, i, j = k // row ** 2, k % row, k // row % row
    x = np.array([(i + 0.5) * SPACING, (j + 0.5) * SPACING, Z0 + (layer + 0.6) * SPACING])
    x += rng.uniform(-0.005, 0.005, 3)
    O.bodies.append(utils.sphere(tuple(x), 0.04 * (1 + rng.uniform(-0.2, 0.2))))
if floor == "none":
    floors = []
elif floor == "wall":
    floors = [O.bodies.append(utils.wall(Z0, axis=2, sense=1))]
elif floor == "facet":
    a, b = -0.5 * L, 1.5 * L
    floors = O.bodies.append([utils.facet([(a, a, Z0), (b, a, Z0), (b, b, Z0)], fixed=True),
                              utils.facet([(a, a, Z0), (b, b, Z0), (a, b, Z0)], fixed=True)])
else:
    floors = [O.bodies.append(utils.box((0.5 * L, 0.5 * L, Z0 - 0.02), (L, L, 0.02), fixed=True))]
if cell == "shear":
    O.cell.velGrad = Matrix3(0, 0, 2, 0, 0, 0, 0, 0, 0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()],
                          allowBiggerThanPeriod=True),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(),
                     Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3),
    PyRunner(command="sample()", iterPeriod=100),
]
O.dt = 0.7 * PWaveTimeStep()
samples, cells = [], []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process
    cells.append([list(O.cell.hSize.row(i)) for i in range(3)])


start = time.process_time()
O.run(steps, True)
cpu = time.process_time() - start
sample()                                               # the state after the last step
force = [sum((O.forces.f(i)[d] for i in floors), 0.0) for d in range(3)]
result = {"positions": samples, "cells": cells, "floor_force": force, "rebuilds": O.engines[1].rebuilds,
          "cpu_seconds": [p["cpu"] for p in distributed.per_process({"cpu": cpu})],
          "traffic": distributed.traffic()}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
