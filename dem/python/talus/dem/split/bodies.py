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
  ``highlight``, ``wire``) and reference state (``state.refPos``, ``refOri``) every process keeps
  for every body: written alike everywhere.

So a sum over the bodies is the whole scene's on every process (in id order, as in one process),
a loop erasing the bodies below a floor erases the same ids everywhere, and a write reaches every
body once. What a snapshot cannot give (its bound, its angular momentum, a clump's members)
raises, naming the rule. One loop exchanges the state of every body (27 numbers each) with every process:
for large scenes, prefer the measurements that reduce (``utils.kineticEnergy()``,
``aabbExtrema()``, ``O.bodies.gather(ids)`` for a few bodies).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterator

import numpy as np

from talus.dem import distributed
from talus.dem.base.linalg import Quaternion, Vector3
from talus.dem.geometry.appearance import check_color
from talus.dem.geometry.shapes import Clump, ShapeSpec, Sphere

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

# Columns of a body's snapshot (dem/distributed/script/Snapshot.h makes them).
_ID, _POS, _VEL, _ANGVEL, _ORI, _MASS, _INERTIA = 0, slice(1, 4), slice(4, 7), slice(7, 10), slice(10, 14), 14, slice(15, 18)
_RADIUS, _DYNAMIC, _MATERIAL, _MASK, _CLUMP_ID, _IS_CLUMP, _BLOCKED = 18, 19, 20, 21, 22, 23, 24
_OWNER, _DAMPED = 25, 26
_DOF_LETTERS = "xyzXYZ"


def _rule(id: int, owner_note: str) -> str:
    return (f"body {id} is owned by another process: under mpirun a body owned elsewhere is a snapshot of it, taken "
            f"when a loop over O.bodies started or O.bodies[{id}] was read ({owner_note})")


def _field(name: str, make, held=None):
    """A snapshot's attribute: made from its row when read (most loops read a few of them), or
    what the loop wrote into it. ``held(view)`` names where the attribute lives on this
    process's copy of the body (a Body view of its row), for what the ghost update does not carry:
    written there too, so that every copy has it at once, as the owner's body does (a copy's
    mask decides which pairs this process's collider makes, its mass a new contact's stiffness
    under the visco-elastic laws). The others (pos, vel, ...) reach the copies with the update."""
    def get(self):
        return self._written[name] if name in self._written else make(self._row)

    def set(self, value):
        self._written[name] = value
        if held is not None:
            row = self._scene._domain.rowOf(self._body_id)     # this process's copy, if it holds one
            if row >= 0:
                setattr(held(self._view(row, self._body_id)), name, value)
    return property(get, set)


def _blocked(row) -> str:
    mask = int(row[_BLOCKED])
    return "".join(c for i, c in enumerate(_DOF_LETTERS) if mask & (1 << i))


class RemoteState:
    """The state of a body owned by another process, as it was when the loop started. Its
    attributes can be set: the snapshot changes, and the owner makes the same write in its own
    run of the loop."""

    __slots__ = ("_id", "_row", "_written", "_scene", "_view")

    def __init__(self, scene: "Scene", id: int, row: np.ndarray, view):
        self._id, self._row, self._written, self._scene, self._view = id, row, {}, scene, view

    pos = _field("pos", lambda row: Vector3(row[_POS]))
    vel = _field("vel", lambda row: Vector3(row[_VEL]))
    angVel = _field("angVel", lambda row: Vector3(row[_ANGVEL]))
    ori = _field("ori", lambda row: Quaternion(*row[_ORI]))
    mass = _field("mass", lambda row: float(row[_MASS]), held=lambda copy: copy.state)
    inertia = _field("inertia", lambda row: Vector3(row[_INERTIA]), held=lambda copy: copy.state)
    blockedDOFs = _field("blockedDOFs", _blocked, held=lambda copy: copy.state)
    isDamped = _field("isDamped", lambda row: bool(row[_DAMPED]))

    @property
    def se3(self):
        return self.pos, self.ori

    # The reference state, which every process keeps for every body (State._reference): a loop
    # writing it writes it alike on every process.
    def _states(self):
        scene = self._scene
        if scene._reference_by_row:
            distributed.refuse("State.refPos and refOri in a scene holding a packing read in slabs (each process "
                               "kept its own slab's only)")
        scene._reference.ensure(len(scene.bodies))
        return scene._reference

    def _set_ori(self, value):
        q = value if isinstance(value, Quaternion) else Quaternion(*value)
        self._states().ori[self._id] = (q.w, q.x, q.y, q.z)

    refPos = property(lambda s: Vector3(s._states().pos[s._id]),
                      lambda s, v: s._states().pos.__setitem__(s._id, np.asarray(v, dtype=float).reshape(3)))
    refOri = property(lambda s: Quaternion(*s._states().ori[s._id]), _set_ori)

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        written = object.__getattribute__(self, "_written")
        if name in written:
            return written[name]
        raise AttributeError(_rule(self._id, f"its state.{name} is not part of the snapshot: read it on the process "
                                             f"owning the body, or run the script in one process"))

    def __setattr__(self, name, value):
        if hasattr(type(self), name) or name in self.__slots__:
            object.__setattr__(self, name, value)
        else:   # (isDamped, ...): kept here; the owner makes the same write to the body, and checks it
            self._written[name] = value

    _body_id = property(lambda s: s._id)

    def __repr__(self):
        return f"<RemoteState of body {self._id}>"


class RemoteBody:
    """A body owned by another process, as a loop over ``O.bodies`` sees it there (see the
    module's rule): ``id``, ``state``, ``shape`` (a Sphere or Clump with the body's radius and
    colour), ``material``, ``dynamic``, ``mask``, ``clumpId``. ``view(row, id)`` is a Body view
    of a row of this process's arrays (for its copy of the body, if it holds one)."""

    __slots__ = ("id", "state", "_shape", "_row", "_scene", "_written", "_view")

    def __init__(self, scene: "Scene", row: np.ndarray, view):
        self.id, self._scene, self._row, self._shape, self._written = int(row[_ID]), scene, row, None, {}
        self._view = view
        self.state = RemoteState(scene, self.id, row, view)

    @property
    def shape(self):
        if self._shape is None:
            spec = ShapeSpec("Clump" if self.isClump else "Sphere", tuple(self._row[_POS]),
                             radius=float(self._row[_RADIUS]))
            self._shape = (_RemoteClump if self.isClump else _RemoteSphere)._view(self._scene, self.id, spec)
        return self._shape

    dynamic = _field("dynamic", lambda row: bool(row[_DYNAMIC]), held=lambda copy: copy)
    mask = _field("mask", lambda row: int(row[_MASK]), held=lambda copy: copy)
    groupMask = mask
    clumpId = property(lambda b: int(b._row[_CLUMP_ID]))
    isClump = property(lambda b: bool(b._row[_IS_CLUMP]))
    radius = property(lambda b: float(b._row[_RADIUS]))
    isClumpMember = property(lambda b: not b.isClump and b.clumpId >= 0)
    isStandalone = property(lambda b: not b.isClump and b.clumpId < 0)
    subdomain = property(lambda b: int(b._row[_OWNER]))     # the rank owning it (Yade's Body.subdomain)
    _body_id = property(lambda b: b.id)

    @property
    def material(self):
        return None if self.isClump else self._scene.materials[int(self._row[_MATERIAL])]

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
    """The snapshots (the columns above, dem/distributed/script/Snapshot.h) of the live bodies
    this process owns (walls, facets and boxes left out: every process holds them)."""
    rows, _ = domain.ownedBodies(scene._cpp)
    return domain.snapshots(scene._cpp, rows[scene._cpp.alive()[rows].astype(bool)])


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
            yield RemoteBody(scene, table[remote[id]], views)
        elif alive[here[id]]:   # (not erased by the loop meanwhile)
            yield views(here[id], id)
    distributed.update_ghosts(scene)    # what the loop wrote, to the other processes' copies
