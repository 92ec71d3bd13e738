"""Yade's Peri3dController: stress or strain control of all six components of the periodic
cell (see dem/control/Peri3dController.h for the algorithm)."""

from __future__ import annotations

from typing import Callable

import numpy as np

from talus import _dem
from talus.dem.controllers import _done_hook, _forward
from talus.dem.engines import Engine
from talus.dem.linalg import Vector2

_PATHS = ("xxPath", "yyPath", "zzPath", "yzPath", "zxPath", "xyPath")
_STATE = ("progress", "stress", "strain", "strainRate", "stressRate", "stressIdeal", "stressGoal", "strainGoal",
          "ps", "pe", "pathSizes", "pathsCounter", "lenPs", "lenPe")


def _vector6(name: str):
    def convert(value):
        v = np.asarray(value, dtype=float).reshape(-1)
        if v.shape != (6,) or not np.all(np.isfinite(v)):
            raise ValueError(f"Peri3dController: {name} must be 6 finite numbers (xx, yy, zz, yz, zx, xy), got {value!r}")
        return v
    return convert


def _path(index: int):
    """The (progress, value) points of one component, read as a list of Vector2 as in Yade."""
    name = _PATHS[index]

    def get(self):
        return [Vector2(p) for p in self._cpp.paths[index]]

    def set(self, points):
        pts = np.asarray(points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) == 0 or not np.all(np.isfinite(pts)):
            raise ValueError(f"Peri3dController: {name} must be a non-empty list of (progress, value) pairs, "
                             f"got {points!r}")
        paths = self._cpp.paths
        paths[index] = [p for p in pts]
        self._cpp.paths = paths
    return property(get, set, doc=f"{name}: (progress, value) points of the {name[:2]} component")


class Peri3dController(Engine):
    """Prescribes each of the 6 components (xx, yy, zz, yz, zx, xy) of the periodic cell's
    strain (shears as engineering strains) or, with its bit of ``stressMask`` set, of the
    Love-Weber stress, to reach ``goal`` in ``nSteps`` steps along the linear paths ``xxPath``
    ... ``xyPath`` ((progress, value) points, relative to the last one unless its value is 0).
    Stress components are followed by a strain-rate predictor corrected by ``mod``; the first
    step of an all-stress run uses ``youngEstimation`` and ``poissonEstimation``. Rates are scaled
    down together to ``maxStrainRate``. When ``progress`` reaches 1 or a strain exceeds
    ``maxStrain``, ``doneHook`` runs (each step from then), or, without one, the engine dies and
    the run pauses. Put it after the NewtonIntegrator, as Yade's examples do.

    Read-outs: ``stress``, ``strain``, ``strainRate``, ``stressRate``, ``stressIdeal``,
    ``stressGoal``, ``strainGoal``, ``progress``, ``ps``/``pe`` (stress/strain components) and
    ``lenPs``/``lenPe``, ``pathSizes``, ``pathsCounter``. ``strain``, ``stressIdeal`` and
    ``progress`` may be given to continue a previous loading, as Yade's examples do."""

    def __init__(self, goal=(0,) * 6, stressMask: int = 0, nSteps: int = 1000, maxStrainRate: float = 1e3,
                 maxStrain: float = 1e6, mod: float = .1, youngEstimation: float = 1e20, poissonEstimation: float = .25,
                 xxPath=((1, 1),), yyPath=((1, 1),), zzPath=((1, 1),), yzPath=((1, 1),), zxPath=((1, 1),),
                 xyPath=((1, 1),), doneHook: str | Callable[[], None] = "", strain=(0,) * 6, stressIdeal=(0,) * 6,
                 progress: float = 0, label: str = ""):
        if int(nSteps) <= 0:
            raise ValueError(f"Peri3dController: nSteps must be positive, got {nSteps}")
        self._cpp = _dem.Peri3dController()
        self.goal, self.stressMask, self.nSteps, self.maxStrainRate = goal, stressMask, nSteps, maxStrainRate
        self.maxStrain, self.mod, self.youngEstimation = maxStrain, mod, youngEstimation
        self.poissonEstimation = poissonEstimation
        self.xxPath, self.yyPath, self.zzPath, self.yzPath, self.zxPath, self.xyPath = (
            xxPath, yyPath, zzPath, yzPath, zxPath, xyPath)
        self.strain, self.stressIdeal, self.progress = strain, stressIdeal, progress
        self.doneHook, self.label = doneHook, label

    goal = _forward("goal", kind=_vector6("goal"))
    stressMask = _forward("stressMask", kind=int)
    nSteps = _forward("nSteps", kind=int)
    maxStrainRate = _forward("maxStrainRate", kind=float)
    maxStrain = _forward("maxStrain", kind=float)
    mod = _forward("mod", kind=float)
    youngEstimation = _forward("youngEstimation", kind=float)
    poissonEstimation = _forward("poissonEstimation", kind=float)
    progress = _forward("progress", kind=float)
    strain = _forward("strain", kind=_vector6("strain"))
    stressIdeal = _forward("stressIdeal", kind=_vector6("stressIdeal"))
    stress = _forward("stress", kind=_vector6("stress"))
    strainRate = _forward("strainRate", kind=_vector6("strainRate"))
    stressRate = _forward("stressRate", kind=_vector6("stressRate"))
    stressGoal = _forward("stressGoal", kind=_vector6("stressGoal"))
    strainGoal = _forward("strainGoal", kind=_vector6("strainGoal"))
    ps, pe = _forward("ps"), _forward("pe")
    pathSizes, pathsCounter = _forward("pathSizes"), _forward("pathsCounter")
    lenPs, lenPe = _forward("lenPs", kind=int), _forward("lenPe", kind=int)
    xxPath, yyPath, zzPath, yzPath, zxPath, xyPath = (_path(i) for i in range(6))

    doneHook = _done_hook()

    def _io_state(self):
        return {name: np.array(v) if isinstance(v := getattr(self._cpp, name), np.ndarray) else v for name in _STATE}

    def _io_restore(self, state):
        for name, value in state.items():
            setattr(self._cpp, name, value)


__all__ = ["Peri3dController"]
