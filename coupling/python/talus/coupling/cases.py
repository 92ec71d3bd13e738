"""Helpers the coupled cases (cases/cfd_*.py) share: OpenFOAM's environment for its utilities,
and the coupled run of one sphere settling from rest (its case written by
:func:`talus.coupling.case_builder.cfd_case`)."""

from __future__ import annotations

import os
import shutil
import time
from dataclasses import dataclass

import numpy as np

__all__ = ["SettlingRun", "foam_environment", "settle_sphere"]


def foam_environment() -> dict:
    """The process environment with OpenFOAM's etc/ folder (its utilities need it)."""
    return dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


@dataclass
class SettlingRun:
    """A settling run: times [s] and settling velocities (-v_z) [m/s] at every exchange (from
    t = 0, v = 0), the stopped coupling, and the wall time of the coupled loop [s]."""
    t: np.ndarray
    v: np.ndarray
    coupling: object
    elapsed: float


def settle_sphere(case, *, diameter: float, density: float, position, dt: float,
                  fluid_steps: int, remove_case: bool = False) -> SettlingRun:
    """One sphere released from rest at ``position`` in the fluid at rest of ``case`` (a
    :class:`~talus.coupling.case_builder.FoamCase`: its fluid, gravity, solver and ranks),
    coupled for ``fluid_steps`` fluid steps; DEM step ``dt`` (lowered so that it divides the
    fluid step). ``remove_case``: the case's folder (a temporary one) is removed afterwards, also
    when the run fails."""
    from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere

    try:
        s = Scene()
        s.materials.append(FrictMat(density=density))
        s.bodies.append(sphere(tuple(position), diameter / 2))
        s.engines = [ForceResetter(), NewtonIntegrator(gravity=case.gravity, damping=0.0)]
        s.dt = dt
        coupling = case.coupling(s).start()
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
    finally:
        if remove_case:
            shutil.rmtree(case.path, ignore_errors=True)
