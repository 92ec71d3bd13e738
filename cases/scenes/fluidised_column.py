"""A small fluidised column coupled with OpenFOAM (talusVolumeAveragedFoam): a script written for one
process, run as it is by `talus run` and by `mpirun -np N talus run` (the CFD-DEM parity case,
cases/cfd/cfd_mpi_parity.py; the DEM split over the processes, the fluid over its own ranks).

Spheres (d = 1 mm, rho_p = 2500, FrictMat, linear Cundall-Strack law) start on a jittered lattice
1.25 mm apart in an 8 x 8 mm column with walls (the DEM's and the mesh's), fall onto the floor
through water-like fluid (rho = 1000, nu = 1e-5) that enters at the floor (the inlet, ramped)
and leaves at the top; the volume-averaged solver's drag is re-evaluated at every DEM sub-step
(implicitDrag). With `periodic`, the column is the fluidised bed's (cases/cfd/cfd_fluidised_bed.py):
periodic across x and y (a periodic cell 8 x 8 mm wide and 64 mm tall, the mesh's x and y
patches cyclic), a floor wall at the inlet and a lid at the outlet, no side walls.

Arguments: the fluid case folder (written, meshed and decomposed by the caller:
cfd_mpi_parity.fluid_case), its fluid ranks, the fluid steps, the output file, and optionally the
layers of spheres (8: 288 spheres), the solver (talusVolumeAveragedFoam, or
talusPointForceFoam with a point-force case), a vertical velocity the spheres start with
(m/s, default 0: thrown down, they cross the DEM processes' boundaries within a few fluid steps)
and the column (`walled`, the default, or `periodic`). The output (JSON): every body's
position every 20 fluid steps and after the last, the hydrodynamic force on all particles after
each exchange, each process's particles, messages and fluid ranks exchanged with at the last exchange, and the
particles whose coupling records it handed to another process after the DEM migrated them).
"""
import json
import sys

import numpy as np
from talus.coupling import FoamCoupling
from talus.dem import distributed

case, procs, steps, output = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
L, D, SPACING, LAYERS = 8e-3, 1e-3, 1.25e-3, int(sys.argv[5]) if len(sys.argv) > 5 else 8
SOLVER = sys.argv[6] if len(sys.argv) > 6 else "talusVolumeAveragedFoam"
DROP = float(sys.argv[7]) if len(sys.argv) > 7 else 0.0
COLUMN = sys.argv[8] if len(sys.argv) > 8 else "walled"
if COLUMN not in ("walled", "periodic"):
    raise SystemExit(f"column {COLUMN!r}: walled or periodic")
RHO, NU, G = 1000.0, 1e-5, 9.81

if COLUMN == "periodic":
    O.periodic = True
    O.cell.setBox(L, L, 8 * L)
O.materials.append(FrictMat(young=5e6, poisson=0.3, frictionAngle=0.3, density=2500))
jitter = np.random.default_rng(1).uniform(-0.1e-3, 0.1e-3, size=(6 * 6 * LAYERS, 3))
k = 0
for layer in range(LAYERS):
    for j in range(6):
        for i in range(6):
            x = np.array([0.875e-3 + i * SPACING, 0.875e-3 + j * SPACING, 0.75e-3 + layer * SPACING]) + jitter[k]
            O.bodies.append(utils.sphere(tuple(x), D / 2))
            k += 1
if COLUMN == "periodic":     # the fluidised bed's floor and lid (the mesh's inlet and outlet)
    O.bodies.append([utils.wall(0, axis=2, sense=1), utils.wall(2 * L, axis=2, sense=-1)])
else:
    for axis in range(3):
        O.bodies.append(utils.wall(0, axis=axis, sense=1))
        if axis < 2:
            O.bodies.append(utils.wall(L, axis=axis, sense=-1))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -G), damping=0.2),
]
O.dt = 0.5 * PWaveTimeStep()
O.velocities()[:6 * 6 * LAYERS, 2] = DROP   # the spheres thrown down at the start (default: at rest)
coupling = FoamCoupling(O, case, rhoFluid=RHO, nu=NU, gravity=(0, 0, -G), solver=SOLVER,
                        nProcs=procs, implicitDrag=True).start()
samples, lift = [], []


def sample():
    samples.append(distributed.positions().tolist())   # every body, on every process


def hydrodynamic():
    # the vertical hydrodynamic force on all particles (each process holds its own particles')
    lift.append(sum(p["fz"] for p in distributed.per_process({"fz": float(np.sum(coupling.lastForces[:, 2]))})))


O.engines = O.engines + [PyRunner(command="sample()", iterPeriod=20 * coupling.substeps),
                         PyRunner(command="hydrodynamic()", iterPeriod=coupling.substeps)]
O.run(steps * coupling.substeps, True)
sample()
particles = distributed.per_process({"particles": len(coupling.lastForces), "messages": coupling.link.lastMessages,
                                     "fluid_ranks": coupling.link.lastFluidPeers,
                                     "handed_over": coupling._owned.handedOver if coupling._owned else 0})
coupling.stop()
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump({"positions": samples, "lift": lift, "processes": particles, "substeps": coupling.substeps,
                   "exchanges": coupling.exchanges}, f)
