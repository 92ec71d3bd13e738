"""The reference for the Gauss-point calls: the same RVE file run directly in a talus.dem Scene,
the cell driven through O.cell.velGrad step by step with the calls' sub-steps."""

from __future__ import annotations

import os

import numpy as np


def subStepVelGrad(G: np.ndarray, k: int, nSteps: int, dt: float) -> np.ndarray:
    """Velocity gradient of sub-step k (0-based) of an increment G over nSteps steps:
    L dt = (G / n) (I + k / n G)^-1, which takes the cell from (I + k/n G) H0 to (I + (k+1)/n G) H0.
    The C++ function the RVEs use, so that a reference run applies bit-identical numbers (a
    different 3x3 inverse differs in the last bits, which a dense packing amplifies)."""
    from talus import _fem
    return np.array(_fem.subStepVelocityGradient(np.asarray(G, dtype=float), int(k), int(nSteps), float(dt)))


def replay(path: str | os.PathLike, grads, nSteps, law: str = "Law2_ScGeom_FrictPhys_CundallStrack",
           damping: float = 0.2):
    """Load the RVE file into a talus.dem Scene with the engines the calls use and apply the
    displacement gradients `grads` (each 2x2 or 3x3, relative to the previous configuration)
    one after the other, each over `nSteps` DEM steps (one count, or one per gradient: a
    driver's StepReport.nSteps); returns the Scene and the Love-Weber stress (3x3) after each."""
    from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop,
                           Ip2_FrictMat_FrictMat_FrictPhys, Matrix3, NewtonIntegrator, Scene, getStress)
    from talus.dem.step import engines
    S = Scene()
    S.load(os.fspath(path))
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [getattr(engines, law)()]),
                 NewtonIntegrator(damping=damping)]
    stresses = []
    counts = [nSteps] * len(grads) if np.isscalar(nSteps) else list(nSteps)
    for g, n in zip(grads, counts, strict=True):
        G = np.zeros((3, 3))
        g = np.asarray(g, dtype=float)
        G[:len(g), :len(g)] = g
        for k in range(n):
            S.cell.velGrad = Matrix3(*subStepVelGrad(G, k, n, S.dt).ravel())
            S.step()
        S.cell.velGrad = Matrix3.Zero
        stresses.append(getStress(scene=S))
    return S, np.array(stresses)
