"""Contacts as Yade scripts read them: ``O.interactions`` (Yade's InteractionContainer).

    for i in O.interactions:                    # the real contacts
        print(i.id1, i.id2, i.geom.penetrationDepth, i.phys.normalForce)
    i = O.interactions[3, 7]                    # either order; IndexError if there is no pair
    O.interactions.withBody(3)                  # the real contacts of body 3
    O.interactions.countReal(), len(O.interactions)

Each :class:`Interaction` is a snapshot taken when it is looked up: its geometry (``i.geom``:
Yade's ScGeom names) and physics (``i.phys``: FrictPhys / ViscElPhys names) hold the values of
that moment. Bulk work over all contacts is faster through ``O.contacts()`` or the exchange
interface. The contact list lives in C++ (sorted by id pair); nothing is stored here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterator

import numpy as np

from talus.dem.base.linalg import Vector3

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

__all__ = ["Interaction", "InteractionContainer", "ScGeom", "ContactPhys"]


class _Record:
    """Named read-only values of one contact (the base of geom and phys)."""

    _names: tuple = ()

    def __init__(self, values: dict):
        object.__setattr__(self, "_values", values)

    def __getattr__(self, name):
        if name in self._names:
            return self._values[name]
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r}; it has {', '.join(self._names)}")

    def __setattr__(self, name, value):
        raise AttributeError(f"{type(self).__name__}.{name} is read-only in Talus (a snapshot of the contact); "
                             "change the materials or the law's parameters instead")

    def __dir__(self):
        return list(self._names)


class ScGeom(_Record):
    """Sphere contact geometry: ``normal`` (from body 1 to 2), ``penetrationDepth``,
    ``contactPoint``, ``refR1``, ``refR2``, ``shearInc``."""
    _names = ("normal", "penetrationDepth", "contactPoint", "refR1", "refR2", "shearInc")


class ContactPhys(_Record):
    """Contact physics: stiffnesses ``kn``, ``ks``, dashpots ``cn``, ``cs``,
    ``tangensOfFrictionAngle``, the forces on body 2 ``normalForce`` and ``shearForce``."""
    _names = ("kn", "ks", "cn", "cs", "tangensOfFrictionAngle", "normalForce", "shearForce")


def _vector(value):
    return Vector3(np.asarray(value, dtype=float))


class Interaction:
    """One pair: ``id1``, ``id2``, ``isReal``, ``geom``, ``phys``, ``cellDist``. ``Interaction()``
    is Yade's blank one (ids 0, not real, no geometry or physics)."""

    __slots__ = ("id1", "id2", "isReal", "cellDist", "geom", "phys")

    def __init__(self, values: dict | None = None):
        if values is None:
            self.id1 = self.id2 = 0
            self.isReal, self.cellDist, self.geom, self.phys = False, (0, 0, 0), None, None
            return
        for name in ("normal", "contactPoint", "shearInc", "normalForce", "shearForce"):
            values[name] = _vector(values[name])
        self.id1, self.id2 = int(values["id1"]), int(values["id2"])
        self.isReal = bool(values["isReal"])
        self.cellDist = tuple(int(k) for k in values["cellDist"])
        self.geom = ScGeom(values) if self.isReal else None
        self.phys = ContactPhys(values) if self.isReal else None

    def __repr__(self):
        return f"<Interaction {self.id1}-{self.id2}{'' if self.isReal else ' (not real)'}>"


def _split_contacts():
    from talus.dem.split import contacts     # (imports the files package, which imports this one)
    return contacts


class InteractionContainer:
    """``O.interactions``: iteration over the real contacts, lookup by id pair, counts, erase."""

    def __init__(self, scene: "Scene"):
        self._scene = scene

    # Under mpirun (a scene split over the processes) see talus.dem.split.contacts: the
    # iteration and the counts are collective, the look-ups answer where the contact lives.
    def _split(self) -> bool:
        from talus.dem import distributed     # (imports this module's package)
        return distributed.is_split(self._scene)

    def __iter__(self) -> Iterator[Interaction]:
        if self._split():
            return (Interaction(values) for values in _split_contacts().every_contact(self._scene, True))
        return (Interaction(values) for values in self._scene._cpp.contacts())

    def __len__(self) -> int:
        """All pairs the collider keeps (real or only within the skin), as Yade's len()."""
        if self._split():
            return _split_contacts().count(self._scene, False)
        return self._scene._cpp.contactCount(False)

    def countReal(self) -> int:
        if self._split():
            return _split_contacts().count(self._scene, True)
        return self._scene._cpp.contactCount(True)

    def _contact(self, id1: int, id2: int) -> dict | None:
        """The values of the pair (id1, id2), None if it has none."""
        if not self._split():
            return self._scene._cpp.contact(id1, id2)
        return _split_contacts().pair(self._scene, id1, id2)

    def __getitem__(self, ids) -> Interaction:
        try:
            id1, id2 = (int(k) for k in ids)
        except (TypeError, ValueError):
            raise TypeError(f"O.interactions[id1, id2] takes two body ids, got {ids!r}") from None
        values = self._contact(id1, id2)
        if values is None:
            raise IndexError(f"no interaction between bodies {id1} and {id2}")
        return Interaction(values)

    def has(self, id1: int, id2: int) -> bool:
        """Whether bodies id1 and id2 have a pair, real or within the skin."""
        return self._contact(int(id1), int(id2)) is not None

    def withBody(self, id: int) -> list[Interaction]:
        """The real contacts of one body."""
        if self._split():
            return [Interaction(v) for v in _split_contacts().with_body(self._scene, int(id), True)]
        return [Interaction(v) for v in self._scene._cpp.contactsOf(int(id)) if v["isReal"]]

    def withBodyAll(self, id: int) -> list[Interaction]:
        """All pairs of one body, real or only within the skin."""
        if self._split():
            return [Interaction(v) for v in _split_contacts().with_body(self._scene, int(id), False)]
        return [Interaction(v) for v in self._scene._cpp.contactsOf(int(id))]

    def nr(self) -> int:
        """Number of pairs (Yade's ``nr``; the same as ``len``)."""
        return len(self)

    def erase(self, id1: int, id2: int) -> bool:
        """Remove a pair and its history; the collider finds it again while the bodies stay
        within the skin (as in Yade). Returns whether there was one. Under mpirun every process
        calls it alike and erases its copy (True if any process had the pair: collective)."""
        if self._split():
            d = self._scene._domain
            rows = [d.rowOf(int(i)) for i in (id1, id2)]
            here = min(rows) >= 0 and bool(self._scene._cpp.eraseContact(*rows))
            return _split_contacts().vtk_split.total(self._scene, int(here)) > 0
        return bool(self._scene._cpp.eraseContact(int(id1), int(id2)))

    def clear(self):
        """Remove every pair and its history (Yade's ``clear``)."""
        self._scene._cpp.eraseContacts()

    def all(self, onlyReal: bool = False) -> list[Interaction]:
        """Every pair (or only the real ones)."""
        if self._split():
            return [Interaction(v) for v in _split_contacts().every_contact(self._scene, onlyReal)]
        return [Interaction(v) for v in self._scene._cpp.contacts(onlyReal)]
