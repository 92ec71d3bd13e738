"""Yade's DomainLimiter: removes the spheres and clumps whose centre left an axis-aligned box."""

from __future__ import annotations

import math

import numpy as np

from talus import _dem
from talus.dem.base.linalg import Vector3
from talus.dem.step.python_engines import PeriodicPythonEngine


class DomainLimiter(PeriodicPythonEngine):
    """Erases the standalone spheres and the clumps (with their members) whose position is
    outside [``lo``, ``hi``], when it runs (a periodic engine: ``iterPeriod``, ``virtPeriod``,
    ``realPeriod``, ``nDo``, ``initRun``; with none set it never runs, as in Yade). Counts them
    in ``nDeleted``, their mass in ``mDeleted``, the spheres' volume in ``vDeleted``. Other
    bodies (facets, walls, boxes) stay wherever they are. With ``mask`` > 0, only bodies whose
    group mask shares a bit with it."""

    def __init__(self, lo=(0.0, 0.0, 0.0), hi=(0.0, 0.0, 0.0), mDeleted: float = 0.0, vDeleted: float = 0.0,
                 mask: int = -1, iterPeriod: int = 0, virtPeriod: float = 0.0, realPeriod: float = 0.0, nDo: int = -1,
                 initRun: bool = False, label: str = "", dead: bool = False):
        super().__init__(iterPeriod, virtPeriod, realPeriod, nDo, initRun, label, dead)
        self.lo, self.hi, self.mask = lo, hi, int(mask)
        self.mDeleted, self.vDeleted = float(mDeleted), float(vDeleted)
        self._nDeleted = 0

    lo = property(lambda self: Vector3(self._lo), lambda self, v: setattr(self, "_lo", np.asarray(v, float).reshape(3)),
                  doc="lower corner of the domain")
    hi = property(lambda self: Vector3(self._hi), lambda self, v: setattr(self, "_hi", np.asarray(v, float).reshape(3)),
                  doc="upper corner of the domain")
    nDeleted = property(lambda self: self._nDeleted, doc="bodies erased so far (read-only, as in Yade)")

    def _action(self, scene):
        pos = np.asarray(scene._cpp.pos())
        candidates = np.concatenate([scene.sphere_ids(), _dem.live_ids(scene._cpp, "Clump")])
        if self.mask > 0:
            candidates = np.array([i for i in candidates if _dem.group_mask(scene._cpp, int(i)) & self.mask], dtype=int)
        # Outside in any coordinate, as Yade's p < lo or p > hi (a NaN position stays).
        outside = candidates[((pos[candidates] < self._lo) | (pos[candidates] > self._hi)).any(axis=1)]
        gone = [id for id in sorted(int(i) for i in outside) if not scene.bodies[id].isClumpMember]
        radius, mass = np.asarray(scene._cpp.radius()), np.asarray(scene._cpp.mass())
        for id in gone:
            self._nDeleted += 1
            self.mDeleted += float(mass[id])
            if radius[id] > 0:
                self.vDeleted += 4 / 3.0 * math.pi * float(radius[id]) ** 3
        for id in gone:
            scene.bodies.erase(id, eraseClumpMembers=True)

    def _io_state(self):
        return {"nDeleted": self._nDeleted}

    def _io_restore(self, state):
        self._nDeleted = int(state["nDeleted"])


__all__ = ["DomainLimiter"]
