"""A periodic cloud of spheres in a deforming cell: a script written for one process, run as it is
by `talus run` and by `mpirun -np N talus run` (the distributed DEM's parity case,
cases/dem/dem_mpi_parity.py, and tests/dem/distributed/test_mpi_periodic.py).

Arguments: spheres, steps, output file (JSON), mode, and optionally `finish` (triax only):

- `triax`: the seed's periodic triaxial test (as cases/yade/periodic_triaxial.py): a loose
  periodic cloud (makeCloud, rMean 0.1, rRelFuzz 0.3, seed 1; the cell's side grows with the
  cube root of the spheres, 2 m for 458) compacted isotropically to -100 kPa by
  PeriTriaxController (dynCell, maxStrainRate 1/s: at the tutorial's 10/s spheres of larger
  clouds overlap by half a radius), then, once its doneHook fires, compressed
  along z at 0.1/s to a log strain of -0.2 with -100 kPa kept on x and y. `finish` runs on past
  `steps` until then (the peak stress ratio), else the run stops after `steps`.
- `shear`: the same cloud in a cell deformed by O.cell.velGrad alone: compressed at 0.7/s along
  each axis and sheared (xz) at 0.8/s, so that the spheres come into contact as the cell shears.
- `iso`: the same cloud compressed by PeriIsoCompressor (Yade's stress measure) to -1 MPa, then
  relaxed to -200 kPa (about 1500 and 2000 steps for 300 spheres), its charLen and largest
  sphere found by itself (body 0's diameter, the largest over the spheres).
- `peri3d`: the same cloud driven by Peri3dController over `steps` steps: strains of -0.2 along
  x and y and an engineering shear strain xy of 0.2, the stress zz held at -20 kPa (its strain
  rate found by the controller's predictor, all rates capped at 1/s).

FrictMat (E 1e7, poisson 0.3, friction 0.5 rad, density 1000), linear Cundall-Strack law,
Cundall damping 0.2, no gravity, dt half the P-wave step.

Output: every body's (unwrapped) position every 100 steps and after the last step, the cell's
hSize then, getStress() after the last step, what the controller read every 50 steps
(PeriTriaxController: the stresses and strains with the stage; PeriIsoCompressor: its stress,
stiffness, stage and unbalanced force; Peri3dController: its stress, strain, strain rate and
progress), the step the compaction ended at, the halo traffic per process.
"""
import json
import sys

from yade import pack
from talus.dem import distributed

spheres, steps, output, mode = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
finish = len(sys.argv) > 5 and sys.argv[5] == "finish"
if mode not in ("triax", "shear", "iso", "peri3d"):
    raise SystemExit(f"mode {mode!r}: triax, shear, iso or peri3d")
sigma = -1e5
size = 2.0 * (spheres / 458.0) ** (1 / 3.0)

O.periodic = True
O.materials.append(FrictMat(young=1e7, poisson=.3, frictionAngle=.5, density=1000))
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (size, size, size), rMean=.1, rRelFuzz=.3, periodic=True, num=spheres, seed=1)
cloud.toSimulation()

engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
           InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                           [Law2_ScGeom_FrictPhys_CundallStrack()])]
if mode == "triax":
    engines.append(PeriTriaxController(label="triax", goal=(sigma, sigma, sigma), stressMask=7, dynCell=True,
                                       maxStrainRate=(1, 1, 1), maxUnbalanced=.1, relStressTol=1e-3,
                                       doneHook="compactionFinished()"))
elif mode == "iso":
    engines.append(PeriIsoCompressor(label="iso", stresses=[-1e6, -2e5], maxUnbalanced=.2,
                                     doneHook="state['compacted'] = O.iter"))
else:
    O.cell.velGrad = Matrix3(-.7, 0, .8, 0, -.7, 0, 0, 0, -.7)
engines.append(NewtonIntegrator(damping=.2))
if mode == "peri3d":                                   # after the integrator, as Yade's examples
    engines.append(Peri3dController(label="p3d", goal=(-.2, -.2, -2e4, 0, 0, .2), stressMask=0b000100,
                                    nSteps=steps, maxStrainRate=1, doneHook="O.pause()"))
O.engines = engines + [PyRunner(command="sample()", iterPeriod=100), PyRunner(command="history()", iterPeriod=50)]
O.dt = .5 * PWaveTimeStep()
samples, cells = [], []
read = {k: [] for k in ("i", "stage", "sxx", "syy", "szz", "exx", "eyy", "ezz")}
state = {"stage": 0, "compacted": None}


def sample():
    if O.iter <= steps:
        samples.append(distributed.positions().tolist())   # every body, on every process
        cells.append([list(O.cell.hSize.row(i)) for i in range(3)])


def history():
    if mode == "iso":
        for key in ("sigma", "state", "avgStiffness", "currUnbalanced"):
            read.setdefault(key, []).append(_plain(getattr(iso, key)))
    if mode == "peri3d":
        for key in ("stress", "strain", "strainRate", "progress"):
            read.setdefault(key, []).append(_plain(getattr(p3d, key)))
    if mode != "triax":
        return
    read["i"].append(O.iter)
    read["stage"].append(state["stage"])
    for a, axis in enumerate("xyz"):
        read["s" + axis * 2].append(float(triax.stress[a]))
        read["e" + axis * 2].append(float(triax.strain[a]))


def _plain(value):
    """A controller's read-out as JSON numbers (a vector as a list)."""
    return [float(x) for x in value] if hasattr(value, "__len__") else float(value)


def compactionFinished():
    state["compacted"] = O.iter
    O.cell.trsf = Matrix3.Identity
    triax.goal = (sigma, sigma, -.2)
    triax.stressMask = 3
    triax.maxStrainRate = (1., 1., .1)
    triax.doneHook = "triaxFinished()"
    triax.maxUnbalanced = 10
    state["stage"] = 1


def triaxFinished():
    O.pause()


O.run(steps, True)
sample()                                               # the state after the last step
stress = [list(getStress().row(i)) for i in range(3)]
if finish and mode == "triax":
    O.run(200000, True)                                # until triaxFinished pauses it
result = {"positions": samples, "cells": cells, "stress": stress, "history": read, "compacted": state["compacted"],
          "iter": O.iter, "traffic": distributed.traffic(), "unbalanced": unbalancedForce()}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
