"""Helpers the coupled cases (cases/cfd_*.py) share: a fresh, meshed copy of an OpenFOAM case
folder, and the coupled run of one sphere settling from rest."""

from __future__ import annotations

import os
import shutil
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

__all__ = ["SettlingRun", "foam_environment", "mesh_case", "settle_sphere"]


def foam_environment() -> dict:
    """The process environment with OpenFOAM's etc/ folder (its utilities need it)."""
    return dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


def mesh_case(source, procs: int = 1, edit: Callable[[Path], None] | None = None, prefix: str = "talus_cfd_") -> Path:
    """A copy of the case folder ``source`` in a new temporary folder, changed by ``edit(work)``
    (e.g. the mesh size in system/blockMeshDict), meshed with blockMesh and, for ``procs > 1``,
    decomposed with decomposePar (system/decomposeParDict must ask for ``procs`` ranks). The
    utilities' output goes to ``work/log.<utility>``; a failure raises with that log's name.
    New cases are written by :func:`talus.coupling.case_builder.cfd_case` instead."""
    work = Path(tempfile.mkdtemp(prefix=prefix))
    shutil.copytree(source, work, dirs_exist_ok=True)
    if edit is not None:
        edit(work)
    from talus.coupling.case_builder import mesh_and_decompose
    mesh_and_decompose(work, procs=procs)
    return work


@dataclass
class SettlingRun:
    """A settling run: times [s] and settling velocities (-v_z) [m/s] at every exchange (from
    t = 0, v = 0), the stopped coupling, and the wall time of the coupled loop [s]."""
    t: np.ndarray
    v: np.ndarray
    coupling: object
    elapsed: float


def settle_sphere(case, *, diameter: float, density: float, position, rhoFluid: float, nu: float,
                  gravity: float, dt: float, fluid_steps: int, solver: str = "talusPointForceFoam",
                  nProcs: int = 1) -> SettlingRun:
    """One sphere released from rest at ``position`` in the meshed case folder ``case`` (fluid at
    rest), coupled with ``solver`` on ``nProcs`` fluid ranks for ``fluid_steps`` fluid steps;
    gravity -``gravity`` along z, DEM step ``dt`` (lowered so that it divides the fluid step)."""
    from talus.coupling.foam import FoamCoupling
    from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere

    s = Scene()
    s.materials.append(FrictMat(density=density))
    s.bodies.append(sphere(tuple(position), diameter / 2))
    s.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -gravity), damping=0.0)]
    s.dt = dt
    coupling = FoamCoupling(s, case, rhoFluid=rhoFluid, nu=nu, gravity=(0, 0, -gravity), nProcs=nProcs,
                            solver=solver).start()
    t, v = [0.0], [0.0]
    start = time.perf_counter()
    try:
        for _ in range(fluid_steps):
            s.run(coupling.substeps, True)
            t.append(s.time)
            v.append(-float(s.velocities()[0][2]))
        elapsed = time.perf_counter() - start
    finally:
        coupling.stop()
    return SettlingRun(np.array(t), np.array(v), coupling, elapsed)
