"""``O.bodies.gather(ids)``: the bodies ``ids`` as snapshots, whichever process owns them.

Under ``mpirun -np N talus run`` a body's state lives on the process that owns it, and
``O.bodies[id]`` reads it with one exchange per id (talus.dem.split.by_id). ``gather`` reads
many in one: every process calls it with the same ids (from code every process runs alike, as a
PyRunner) and gets the same snapshots; it exchanges a few numbers per id, whatever the scene's size. In one
process it gives the same snapshots of O's bodies, so a script reads them alike either way.
A snapshot is read-only and does not follow the body afterwards: gather again to see it move.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from talus.dem.base.linalg import Quaternion, Vector3


@dataclass(frozen=True)
class GatheredState:
    """What ``b.state`` reads, as it was when gathered: ``pos``, ``vel``, ``angVel``, ``ori``,
    ``mass``, ``inertia``."""
    pos: Vector3
    vel: Vector3
    angVel: Vector3
    ori: Quaternion
    mass: float
    inertia: Vector3


@dataclass(frozen=True)
class GatheredBody:
    """A snapshot of one body: ``id``, ``dynamic``, ``radius`` (0 for shapes without one) and
    ``state``."""
    id: int
    dynamic: bool
    radius: float
    state: GatheredState


def from_table(ids, table: np.ndarray) -> list[GatheredBody]:
    """Snapshots from the domain's gather (a row per id: position, velocity, angular velocity,
    orientation w x y z, mass, inertia, radius, dynamic; dem/distributed/collect/Gather.h)."""
    out = []
    for id, row in zip(ids, np.asarray(table)):
        state = GatheredState(Vector3(row[0:3]), Vector3(row[3:6]), Vector3(row[6:9]), Quaternion(*row[9:13]),
                              float(row[13]), Vector3(row[14:17]))
        out.append(GatheredBody(int(id), bool(row[18]), float(row[17]), state))
    return out


def of_body(body) -> GatheredBody:
    """The snapshot of a body of a scene in one process."""
    s = body.state
    state = GatheredState(Vector3(s.pos), Vector3(s.vel), Vector3(s.angVel), Quaternion(s.ori), float(s.mass),
                          Vector3(s.inertia))
    return GatheredBody(int(body.id), bool(body.dynamic), float(body.radius), state)
