"""Yade's Peri3dController: stress or strain control of all six components of the periodic
cell (see dem/control/Peri3dController.h for the algorithm)."""

from __future__ import annotations

from typing import Callable

import numpy as np

from talus import _dem
from talus.dem.control.controllers import cpp_attribute, done_hook_attribute
from talus.dem.step.engines import Engine
from talus.dem.base.linalg import Vector2

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

    goal = cpp_attribute("goal", kind=_vector6("goal"))
    stressMask = cpp_attribute("stressMask", kind=int)
    nSteps = cpp_attribute("nSteps", kind=int)
    maxStrainRate = cpp_attribute("maxStrainRate", kind=float)
    maxStrain = cpp_attribute("maxStrain", kind=float)
    mod = cpp_attribute("mod", kind=float)
    youngEstimation = cpp_attribute("youngEstimation", kind=float)
    poissonEstimation = cpp_attribute("poissonEstimation", kind=float)
    progress = cpp_attribute("progress", kind=float)
    strain = cpp_attribute("strain", kind=_vector6("strain"))
    stressIdeal = cpp_attribute("stressIdeal", kind=_vector6("stressIdeal"))
    stress = cpp_attribute("stress", kind=_vector6("stress"))
    strainRate = cpp_attribute("strainRate", kind=_vector6("strainRate"))
    stressRate = cpp_attribute("stressRate", kind=_vector6("stressRate"))
    stressGoal = cpp_attribute("stressGoal", kind=_vector6("stressGoal"))
    strainGoal = cpp_attribute("strainGoal", kind=_vector6("strainGoal"))
    ps, pe = cpp_attribute("ps"), cpp_attribute("pe")
    pathSizes, pathsCounter = cpp_attribute("pathSizes"), cpp_attribute("pathsCounter")
    lenPs, lenPe = cpp_attribute("lenPs", kind=int), cpp_attribute("lenPe", kind=int)
    xxPath, yyPath, zzPath, yzPath, zxPath, xyPath = (_path(i) for i in range(6))

    doneHook = done_hook_attribute()

    def _io_state(self):
        return {name: np.array(v) if isinstance(v := getattr(self._cpp, name), np.ndarray) else v for name in _STATE}

    def _io_restore(self, state):
        for name, value in state.items():
            setattr(self._cpp, name, value)


__all__ = ["Peri3dController"]
