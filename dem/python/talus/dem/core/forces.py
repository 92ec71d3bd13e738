"""Forces and torques per body as Yade scripts use them: ``O.forces`` (Yade's ForceContainer).

    O.forces.f(id), O.forces.t(id)          # this step's resultant force and torque (Vector3)
    O.forces.addF(id, f), O.forces.addT(id, t)
    O.forces.setPermF(id, f)                # applied every step until changed (Yade's permanent force)
    O.forces()                              # Talus's zero-copy array of all forces (bodies x 3)

``addF`` adds to the force of the step being computed: call it from a PyRunner between the
InteractionLoop and NewtonIntegrator (as in Yade, where the integrator reads the container), or
with ``permanent=True`` (then it is a permanent force). The arrays are the scene's own; nothing is
copied.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from talus.dem import distributed
from talus.dem.base.linalg import Vector3

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

__all__ = ["ForceContainer"]


def _vector3(value, what: str) -> np.ndarray:
    v = np.asarray(value, dtype=float)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"O.forces: {what} must be 3 finite numbers, got {value!r}")
    return v


class ForceContainer:
    """``O.forces``: per-body force and torque access; calling it gives the force array."""

    def __init__(self, scene: "Scene"):
        self._scene = scene

    def __call__(self):
        """The forces of all bodies (a zero-copy array, bodies x 3)."""
        return self._scene._views.track(self._scene._cpp.force())

    def _row(self, array, id: int):
        self._scene._cpp.checkBody(int(id))
        return array[int(id)]

    def f(self, id: int, sync: bool = False):
        """Resultant force on a body in the last (or current) step."""
        if (split := distributed.domain(self._scene)) is not None:   # under mpirun: summed over processes
            return Vector3(self._summed(split, id)[:3])
        return Vector3(self._row(self._scene._cpp.force(), id))

    def t(self, id: int, sync: bool = False):
        """Resultant torque on a body in the last (or current) step."""
        if (split := distributed.domain(self._scene)) is not None:
            return Vector3(self._summed(split, id)[3:])
        return Vector3(self._row(self._scene._cpp.torque(), id))

    def _summed(self, split, id: int):
        """Body ``id``'s force and torque summed over the processes (collective), unless yade.mpy
        summed them at this step already (its mpirun does, for the walls, facets and boxes, so
        that rank 0 alone may read them, as Yade's master does)."""
        summed = getattr(self._scene, "_summedForces", None)
        if summed is not None and summed[0] == self._scene.iter and int(id) in summed[1]:
            return summed[1][int(id)]
        return split.forceOf(self._scene._cpp, int(id))

    m = t  # Yade's alias

    def addF(self, id: int, f, permanent: bool = False):
        if permanent:
            self._row(self._scene._cpp.extForce(), id)[:] += _vector3(f, "the force")
            return
        self._row(self._scene._cpp.force(), id)[:] += _vector3(f, "the force")

    def addT(self, id: int, t, permanent: bool = False):
        if permanent:
            self._row(self._scene._cpp.extTorque(), id)[:] += _vector3(t, "the torque")
            return
        self._row(self._scene._cpp.torque(), id)[:] += _vector3(t, "the torque")

    def setPermF(self, id: int, f):
        self._row(self._scene._cpp.extForce(), id)[:] = _vector3(f, "the permanent force")

    def setPermT(self, id: int, t):
        self._row(self._scene._cpp.extTorque(), id)[:] = _vector3(t, "the permanent torque")

    def permF(self, id: int):
        return Vector3(self._row(self._scene._cpp.extForce(), id))

    def permT(self, id: int):
        return Vector3(self._row(self._scene._cpp.extTorque(), id))

    def reset(self, resetAll: bool = True):
        """Zero this step's forces and torques, and the permanent ones too unless ``resetAll``
        is False."""
        self._scene._cpp.force()[:] = 0
        self._scene._cpp.torque()[:] = 0
        if resetAll:
            self._scene._cpp.extForce()[:] = 0
            self._scene._cpp.extTorque()[:] = 0

    def sync(self):
        """Yade merges its per-thread force buffers here; Talus's forces are always merged."""
