"""The base of engines whose work is written in Python (particle factories, the domain limiter,
random re-insertion): a C++ CallbackEngine calls them at their place in O.engines, every step
or, as Yade's PeriodicEngine, every ``iterPeriod`` steps, ``virtPeriod`` simulated seconds or
``realPeriod`` wall-clock seconds (whichever comes first), at most ``nDo`` times (-1: no limit),
and at the first step with ``initRun``. A periodic engine with no period set never runs, as in
Yade.

Such an engine works on O, the scene of the script (talus.dem.O)."""

from __future__ import annotations

import numpy as np

from talus import _dem
from talus.dem.step.engines import Engine
from talus.dem.core.scenes import default_scene

_NEVER = 2 ** 62   # an iteration period no run reaches


def colliderSkin(scene, engine: str) -> float:
    """The distance the scene's collider grows bounding boxes by (its verletDist; negative:
    that fraction of the smallest sphere's radius), for engines that look for free places."""
    colliders = [e for e in scene.engines if type(e).__name__ in ("InsertionSortCollider", "FlatGridCollider")]
    if not colliders:
        raise RuntimeError(f"{engine}: no collider in O.engines (needed to find free places)")
    verletDist = colliders[0].verletDist
    if verletDist >= 0:
        return verletDist
    radii = np.asarray(scene._cpp.radius())[scene.sphere_ids()]
    return -verletDist * radii.min() if len(radii) else 0.0


class PythonEngine(Engine):
    """An engine whose ``_action(scene)`` runs at every step (Yade's GlobalEngine)."""

    def __init__(self, label: str = "", dead: bool = False):
        self._cpp = _dem.CallbackEngine()
        self._cpp.iterPeriod = 1
        self._cpp.initRun = True    # the first step too
        self._cpp.callback = self._call
        self.label, self.dead = label, dead

    def _call(self):
        O = default_scene()
        if not any(e is self._cpp for e in O._cpp.engines):
            raise RuntimeError(f"{type(self).__name__} runs in talus.dem.O (the script's scene), which does not hold it")
        self._action(O)

    def _action(self, scene):
        raise NotImplementedError


class PeriodicPythonEngine(PythonEngine):
    """A PythonEngine that runs as Yade's PeriodicEngine (the module's docstring)."""

    def __init__(self, iterPeriod: int = 0, virtPeriod: float = 0.0, realPeriod: float = 0.0, nDo: int = -1,
                 initRun: bool = False, label: str = "", dead: bool = False):
        super().__init__(label, dead)
        self._periods = {"iterPeriod": 0, "virtPeriod": 0.0, "realPeriod": 0.0}
        self.iterPeriod, self.virtPeriod, self.realPeriod = iterPeriod, virtPeriod, realPeriod
        self.nDo, self.initRun = nDo, initRun

    def _period(name: str, kind):
        def get(self):
            return self._periods[name]

        def set(self, value):
            value = kind(value)
            if value < 0:
                raise ValueError(f"{type(self).__name__}.{name} must be >= 0, got {value}")
            self._periods[name] = value
            self._schedule()
        return property(get, set, doc=f"Yade's PeriodicEngine.{name} (0: not by this measure)")

    iterPeriod = _period("iterPeriod", int)
    virtPeriod = _period("virtPeriod", float)
    realPeriod = _period("realPeriod", float)
    del _period

    nDo = property(lambda self: self._cpp.nDo, lambda self, v: setattr(self._cpp, "nDo", int(v)),
                   doc="runs after which the engine stops running (-1: no limit)")
    initRun = property(lambda self: self._cpp.initRun, lambda self, v: setattr(self._cpp, "initRun", bool(v)),
                       doc="run at the first step too")
    nDone = property(lambda self: self._cpp.nDone, doc="runs so far")
    iterLast = property(lambda self: self._cpp.iterLast, doc="iteration of the last run")
    virtLast = property(lambda self: self._cpp.virtLast, doc="simulated time of the last run")

    def _schedule(self):
        """The C++ engine's periods: the engine's own, or one no run reaches when none is set."""
        p = self._periods
        idle = not (p["iterPeriod"] or p["virtPeriod"] or p["realPeriod"])
        self._cpp.iterPeriod = _NEVER if idle else p["iterPeriod"]
        self._cpp.virtPeriod = p["virtPeriod"]
        self._cpp.realPeriod = p["realPeriod"]


__all__: list[str] = []
