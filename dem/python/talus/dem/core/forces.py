"""Forces and torques per body as Yade scripts use them: ``O.forces`` (Yade's ForceContainer).

    O.forces.f(id), O.forces.t(id)          # this step's resultant force and torque (Vector3)
    O.forces.addF(id, f), O.forces.addT(id, t)
    O.forces.setPermF(id, f)                # applied every step until changed (Yade's permanent force)
    O.forces()                              # Talus's zero-copy array of all forces (bodies x 3)

``addF`` adds to the force of the step being computed: call it from a PyRunner between the
InteractionLoop and NewtonIntegrator (as in Yade, where the integrator reads the container), or
with ``permanent=True`` (then it is a permanent force). The arrays are the scene's own; nothing is
copied. Under ``mpirun -np N talus run`` every process makes the same calls (it runs the same
script): ``addF``, ``addT`` and ``setPermF``/``setPermT`` act on the process counting the body
(its owner; process 0 for a wall, facet or box, which every process holds), ``f``, ``t``,
``permF`` and ``permT`` sum the processes' shares (collective).
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

    def _counted(self, array, id: int):
        """Body ``id``'s entry of ``array`` where a call changing it acts: its row in one process;
        under mpirun (every process makes the same call, as it runs the same script) on the
        process holding the body — once the scene is split, its owner, and process 0 alone for a
        wall, facet or box, which every process holds and whose force the processes' shares add
        up to — and None elsewhere (the split zeroes the other processes' permanent forces on
        walls, facets and boxes)."""
        split = distributed.domain(self._scene)
        if split is None:
            return self._row(array, id)
        row = split.rowOf(int(id))
        if row == distributed._NO_BODY:
            raise IndexError(f"O.forces: no body with id {int(id)} (erased, or not a body of the scene)")
        if row < 0 or not split.owns(row):
            return None     # held by another process, which makes the call
        if distributed.is_split(self._scene) and distributed.rank() != 0 and distributed.held_everywhere(self._scene, row):
            return None
        return array[row]

    def _add(self, array, id: int, value) -> None:
        entry = self._counted(array, id)
        if entry is not None:
            entry[:] += value

    def _set(self, array, id: int, value) -> None:
        entry = self._counted(array, id)
        if entry is not None:
            entry[:] = value

    def _permanent(self, array, id: int) -> Vector3:
        """A permanent force or torque: under mpirun once the scene is split, summed over the
        processes (collective; each body on the process counting it)."""
        if not distributed.is_split(self._scene):
            return Vector3(array[distributed.row_of(self._scene, int(id))])
        entry = self._counted(array, id)
        return Vector3(self._scene._domain.sum([0.0] * 3 if entry is None else [float(x) for x in entry]))

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
        cpp = self._scene._cpp
        self._add(cpp.extForce() if permanent else cpp.force(), id, _vector3(f, "the force"))

    def addT(self, id: int, t, permanent: bool = False):
        cpp = self._scene._cpp
        self._add(cpp.extTorque() if permanent else cpp.torque(), id, _vector3(t, "the torque"))

    def setPermF(self, id: int, f):
        self._set(self._scene._cpp.extForce(), id, _vector3(f, "the permanent force"))

    def setPermT(self, id: int, t):
        self._set(self._scene._cpp.extTorque(), id, _vector3(t, "the permanent torque"))

    def permF(self, id: int):
        return self._permanent(self._scene._cpp.extForce(), id)

    def permT(self, id: int):
        return self._permanent(self._scene._cpp.extTorque(), id)

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
