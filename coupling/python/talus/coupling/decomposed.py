"""FoamCoupling's particles when the DEM itself is decomposed over MPI processes (``mpirun -np N
talus run script.py``, talus.dem.distributed): each process exchanges with the fluid ranks the
coupled particles it owns, sent once (by their owner; ghosts never), and applies their forces.

What the coupling keeps per particle between exchanges (the force it applied, which the next
exchange replaces; the drag's coefficient and the velocity it was computed with, for the implicit
drag of the sub-steps) is kept by the particle's process and handed to its new process when the
DEM migrates the particle (``_coupling.ParticleRecords``), as the DEM's own per-body arrays travel
with their bodies: no process ever holds every particle. The persistent force the coupling
applied travels with the body in the DEM's arrays.

The calls below that say so are collective: every process makes them at the same steps (the
coupling's hooks run on every process alike, and the DEM re-detects on every process at once).
"""

from __future__ import annotations

import numpy as np

from talus.dem import distributed

# Per particle: the force applied (3), the drag's beta (1) and the velocity it was sent with (3).
_WIDTH = 7


class OwnedParticles:
    """The coupled particles this process owns: their rows in its arrays and their global ids
    (ascending), refreshed after each re-detection of the DEM (a migration changes them)."""

    def __init__(self, scene, ids, module):
        self.scene = scene
        self.coupled = None if ids is None else np.unique(np.asarray(ids, dtype=np.int64))  # None: every sphere
        self.records = module.ParticleRecords(_WIDTH)
        self._version = None
        self.rows = self.ids = None
        self.applied = self.beta = self.sent_velocity = None
        self.handedOver = 0   # records this process handed to others (particles that left it)

    def refresh(self) -> None:
        """The rows and ids again if the DEM's rows have changed since (collective then: the
        records of particles that changed process are handed over)."""
        version = self.scene._cpp.bodiesVersion
        if version == self._version:
            return
        self._version = version
        split = distributed.domain(self.scene)
        if split is None:   # not split yet (before the first step): every process holds the whole scene
            ids = self.coupled if self.coupled is not None else self.scene.sphere_ids()
            self.rows = self.ids = np.ascontiguousarray(ids, dtype=np.int64)
            self._take(np.zeros((len(ids), _WIDTH)))
            return
        rows, ids = split.ownedBodies(self.scene._cpp)
        keep = np.isin(rows, self.scene.sphere_ids()) if self.coupled is None else np.isin(ids, self.coupled)
        rows, ids = rows[keep], ids[keep]
        self.rows, self.ids = rows, ids
        self.records.hand_over(ids)
        self.handedOver += self.records.lastSent
        self._take(self.records.values)

    def store(self, forces, beta, velocities) -> None:
        """This exchange's forces, drag coefficients and the velocities sent, per owned particle."""
        self._take(np.column_stack([forces, beta, velocities]))
        self.records.store(self.ids, np.ascontiguousarray(self._values))

    def _take(self, values) -> None:
        self._values = values
        self.applied = np.ascontiguousarray(values[:, :3])
        self.beta = values[:, 3]
        self.sent_velocity = values[:, 4:7]

    # -- reductions over the processes (before the split each process sees every particle) --
    def total(self, values):
        """``values`` summed over the processes (collective once the scene is split)."""
        split = distributed.domain(self.scene)
        return list(values) if split is None else split.sum([float(v) for v in values])

    def smallest(self, value: float) -> float:
        """The smallest ``value`` over the processes (collective once the scene is split)."""
        split = distributed.domain(self.scene)
        return float(value) if split is None else split.min(float(value))


def collective(error: Exception) -> Exception:
    """``error``, raised on every process alike (a handshake's refusal, a particle outside the
    mesh: the processes learn them together), as the error talus run reports once before every
    process exits (any other error ends the run from the process that raised it)."""
    from talus import _distributed
    return _distributed.CollectiveError(f"{type(error).__name__}: {error}")
