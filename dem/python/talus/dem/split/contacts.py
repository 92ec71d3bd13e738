"""``O.interactions`` of a scene split over the processes (``mpirun -np N talus run``).

A process holds the contacts it computes: every contact of the spheres it owns (with each
other, with its ghosts, with the walls, facets and boxes every process holds). So:

- ``for i in O.interactions`` (and ``all()``, ``len``, ``countReal``, ``nr``) is collective: every
  process runs it and gets every contact of the scene once (each from the process counting it,
  the rule of the measurements), ordered by (id1, id2) — the order differs from one process's
  contact list, so a sum over them may differ in its last bits;
- ``O.interactions[id1, id2]``, ``has``, ``withBody`` and ``withBodyAll`` are collective too:
  every process calls them alike (as the script runs alike) and gets the answer of the process
  counting each contact, whichever process owns the bodies;
- ``erase(id1, id2)`` and ``clear()`` are called alike on every process (as the script runs
  alike), each erasing its copy.

Body ids are the script's (global) ids throughout.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from talus.dem import distributed
from talus.dem.files import vtk_split

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene


def _global(scene: "Scene", values: list[dict]) -> list[dict]:
    """``values`` (contacts as the core gives them, by rows) with the bodies' global ids."""
    if values:
        ids = scene._domain.globalIds([v["id1"] for v in values] + [v["id2"] for v in values])
        for k, v in enumerate(values):
            v["id1"], v["id2"] = int(ids[k]), int(ids[len(values) + k])
    return values


def every_contact(scene: "Scene", real_only: bool) -> list[dict]:
    """Every contact of the scene, once, on every process, ordered by (id1, id2) (collective)."""
    every = [v for part in distributed.gather_objects(_counted_here(scene, scene._cpp.contacts(bool(real_only))))
             for v in part]
    return sorted(every, key=lambda v: (v["id1"], v["id2"]))


def count(scene: "Scene", real_only: bool) -> int:
    """How many contacts (or pairs) the scene has (collective)."""
    return vtk_split.total(scene, len(_counted_here(scene, scene._cpp.contacts(bool(real_only)))))


def _counted_here(scene: "Scene", values: list[dict]) -> list[dict]:
    """Of ``values`` (contacts here, by rows), those this process counts, with global ids."""
    import numpy as np
    if values:
        counted = vtk_split.counted_contacts(scene, np.array([v["id1"] for v in values]),
                                             np.array([v["id2"] for v in values]))
        values = [v for v, c in zip(values, counted) if c]
    return _global(scene, values)


def pair(scene: "Scene", id1: int, id2: int) -> dict | None:
    """The contact of bodies ``id1`` and ``id2`` (its values, with global ids), None if they have
    none (collective: from the process counting it)."""
    d = scene._domain
    rows = [d.rowOf(int(i)) for i in (id1, id2)]
    values = scene._cpp.contact(*rows) if min(rows) >= 0 else None
    found = [v for part in distributed.gather_objects(_counted_here(scene, [values] if values else []))
             for v in part]
    return found[0] if found else None


def with_body(scene: "Scene", id: int, real_only: bool) -> list[dict]:
    """The contacts (or pairs) of body ``id``, ordered by (id1, id2) (collective: each from the
    process counting it)."""
    d = scene._domain
    row = d.rowOf(int(id))
    values = [v for v in scene._cpp.contactsOf(row) if v["isReal"] or not real_only] if row >= 0 else []
    every = [v for part in distributed.gather_objects(_counted_here(scene, values)) for v in part]
    return sorted(every, key=lambda v: (v["id1"], v["id2"]))
