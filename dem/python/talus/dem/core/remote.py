"""``for b in O.bodies:`` under ``mpirun -np N talus run``: every body of the scene, on every process.

A script written for one process loops over the bodies to sum (a mass, a kinetic energy), to
find an extreme (the highest sphere), to colour them or to erase those that left a box. Under
mpirun each process holds its own bodies only, so a loop over those would give each process its
share of a sum, silently. Instead the loop is **collective**: every process runs it (as it runs
the whole script) and visits every live body of the scene, in id order:

- a body this process owns, and every wall, facet and box (which every process holds), is the
  body itself (``O.bodies[id]``'s view), read and written as in one process;
- a body owned by another process is a snapshot taken when the loop started (:class:`RemoteBody`:
  id, state, shape, material, dynamic, mask, clump), the same numbers its owner reads. Writing
  its state changes the snapshot only: its owner, running the same loop, visits the same body
  with the same values and makes the same write to the body itself (the rule ``O.bodies.erase``
  follows too: every process erases the same ids, each its copy). Its looks (``shape.color``,
  ``highlight``, ``wire``) every process keeps for every body: written alike everywhere.

So a sum over the bodies is the whole scene's on every process (in id order, as in one process),
a loop erasing the bodies below a floor erases the same ids everywhere, and a write reaches every
body once. What a snapshot cannot give (a body's forces, its reference state) raises, naming
the rule. One loop exchanges the state of every body (25 numbers each) with every process:
for large scenes, prefer the measurements that reduce (``utils.kineticEnergy()``,
``aabbExtrema()``, ``O.bodies.gather(ids)`` for a few bodies).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterator

import numpy as np

from talus import _dem
from talus.dem.base.linalg import Quaternion, Vector3
from talus.dem.geometry.appearance import check_color
from talus.dem.geometry.shapes import Clump, ShapeSpec, Sphere

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

# Columns of a body's row in the exchanged table.
_ID, _POS, _VEL, _ANGVEL, _ORI, _MASS, _INERTIA = 0, slice(1, 4), slice(4, 7), slice(7, 10), slice(10, 14), 14, slice(15, 18)
_RADIUS, _DYNAMIC, _MATERIAL, _MASK, _CLUMP_ID, _IS_CLUMP, _BLOCKED = 18, 19, 20, 21, 22, 23, 24
_WIDTH = 25
_DOF_LETTERS = "xyzXYZ"


def _rule(id: int, owner_note: str) -> str:
    return (f"body {id} is owned by another process: in a loop over O.bodies under mpirun a body owned elsewhere "
            f"is a snapshot of it taken when the loop started ({owner_note})")


class RemoteState:
    """The state of a body owned by another process, as it was when the loop started. Its
    attributes can be set: the snapshot changes, and the owner makes the same write in its own
    run of the loop."""

    __slots__ = ("_id", "pos", "vel", "angVel", "ori", "mass", "inertia", "blockedDOFs")

    def __init__(self, id: int, row: np.ndarray):
        self._id = id
        self.pos, self.vel, self.angVel = Vector3(row[_POS]), Vector3(row[_VEL]), Vector3(row[_ANGVEL])
        self.ori = Quaternion(*row[_ORI])
        self.mass, self.inertia = float(row[_MASS]), Vector3(row[_INERTIA])
        mask = int(row[_BLOCKED])
        self.blockedDOFs = "".join(c for i, c in enumerate(_DOF_LETTERS) if mask & (1 << i))

    @property
    def se3(self):
        return self.pos, self.ori

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise AttributeError(_rule(self._id, f"its state.{name} is not part of the snapshot: read it on the process "
                                             f"owning the body, or run the script in one process"))

    def __repr__(self):
        return f"<RemoteState of body {self._id}>"


class RemoteBody:
    """A body owned by another process, as a loop over ``O.bodies`` sees it there (see the
    module's rule): ``id``, ``state``, ``shape`` (a Sphere or Clump with the body's radius and
    colour), ``material``, ``dynamic``, ``mask``, ``clumpId``."""

    __slots__ = ("id", "state", "shape", "dynamic", "mask", "clumpId", "isClump", "_material", "_scene")

    def __init__(self, scene: "Scene", row: np.ndarray):
        id = int(row[_ID])
        self.id, self._scene, self.state = id, scene, RemoteState(id, row)
        self.isClump = bool(row[_IS_CLUMP])
        spec = ShapeSpec("Clump" if self.isClump else "Sphere", tuple(row[_POS]), radius=float(row[_RADIUS]))
        self.shape = (_RemoteClump if self.isClump else _RemoteSphere)._view(scene, id, spec)
        self.dynamic, self.mask = bool(row[_DYNAMIC]), int(row[_MASK])
        self.clumpId, self._material = int(row[_CLUMP_ID]), int(row[_MATERIAL])

    groupMask = property(lambda b: b.mask)
    radius = property(lambda b: b.shape.radius)
    isClumpMember = property(lambda b: not b.isClump and b.clumpId >= 0)
    isStandalone = property(lambda b: not b.isClump and b.clumpId < 0)

    @property
    def material(self):
        return None if self.isClump else self._scene.materials[self._material]

    mat = material

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise AttributeError(_rule(self.id, f"its {name} is not part of the snapshot: read it on the process owning "
                                            f"the body, or run the script in one process"))

    def __eq__(self, other):
        return getattr(other, "id", None) == self.id and getattr(other, "_scene", None) is self._scene

    def __hash__(self):
        return hash((id(self._scene), self.id))

    def __repr__(self):
        return f"<Body {self.id} {self.shape} (a snapshot: owned by another process)>"


class _Looks:
    """The looks of a body owned by another process: every process keeps every body's (by id,
    talus.dem.geometry.appearance), so a loop setting colours sets them alike everywhere."""
    __slots__ = ()

    def _table(self, name: str):
        look = self._scene._appearance
        look.ensure(len(self._scene.bodies))
        return getattr(look, name)

    def _set(self, name: str, value):
        self._table(name)[self._id] = value

    color = property(lambda s: Vector3(s._table("color")[s._id]), lambda s, v: s._set("color", check_color(v)))
    highlight = property(lambda s: bool(s._table("highlight")[s._id]), lambda s, v: s._set("highlight", bool(v)))
    wire = property(lambda s: bool(s._table("wire")[s._id]), lambda s, v: s._set("wire", bool(v)))


class _RemoteSphere(_Looks, Sphere):
    """The shape of a sphere owned by another process: its radius (from the snapshot) and looks."""
    __slots__ = ()


class _RemoteClump(_Looks, Clump):
    """The shape of a clump owned by another process: its members are not in the snapshot."""
    __slots__ = ()

    @property
    def members(self) -> dict:
        raise AttributeError("Clump.members of a clump owned by another process is not part of the snapshot a loop "
                             "over O.bodies gives under mpirun: read it on the process owning the clump")


def _own_rows(scene: "Scene", domain) -> np.ndarray:
    """The table rows of the live bodies this process owns (walls, facets and boxes left out:
    every process holds them)."""
    cpp = scene._cpp
    rows, ids = domain.ownedBodies(cpp)
    alive = cpp.alive()[rows].astype(bool)
    rows, ids = rows[alive], ids[alive]
    table = np.empty((len(rows), _WIDTH))
    table[:, _ID] = ids
    for columns, array in ((_POS, cpp.pos()), (_VEL, cpp.vel()), (_ANGVEL, cpp.angVel()), (_INERTIA, cpp.inertia())):
        table[:, columns] = array[rows]
    table[:, _MASS], table[:, _RADIUS] = cpp.mass()[rows], cpp.radius()[rows]
    table[:, _DYNAMIC], table[:, _MATERIAL] = cpp.dynamic()[rows], cpp.materialIds()[rows]
    table[:, _BLOCKED] = cpp.blockedDofs()[rows]
    for k, row in enumerate(int(r) for r in rows):
        table[k, _ORI] = cpp.ori(row)
        table[k, _MASK] = _dem.group_mask(cpp, row)
        table[k, _IS_CLUMP] = cpp.shapeKind(row) == "Clump"
        clump = int(_dem.clump_id(cpp, row))
        table[k, _CLUMP_ID] = domain.globalIds([clump])[0] if clump >= 0 else -1
    return table


def every_body(scene: "Scene", views) -> Iterator:
    """Every live body of a scene split over the processes, in id order (collective; see the
    module): ``views(row, id)`` for the bodies held here as their own (owned, or a wall, facet
    or box), a RemoteBody for the others."""
    from talus import _distributed
    domain, cpp = scene._domain, scene._cpp
    table = _distributed.gather_rows(_own_rows(scene, domain), -1)   # every process's own bodies
    own_rows, own_ids = domain.ownedBodies(cpp)
    here = {int(i): int(r) for r, i in zip(own_rows, own_ids)}
    alive, ids, owned = cpp.alive(), domain.globalIds(list(range(cpp.bodyCount()))), set(here.values())
    for row, id in enumerate(ids):    # walls, facets and boxes: every process holds them
        if alive[row] and row not in owned and domain.owns(row):
            here[int(id)] = row
    remote = {int(i): k for k, i in enumerate(table[:, _ID]) if int(i) not in here}
    for id in sorted(here.keys() | remote.keys()):
        if id in remote:
            yield RemoteBody(scene, table[remote[id]])
        elif alive[here[id]]:   # (not erased by the loop meanwhile)
            yield views(here[id], id)
