"""ParaView output of a scene split over the processes (``mpirun -np N talus run``): the files one
process writes, with the same names and every body once.

Each process holds its own spheres (and ghosts, copies of its neighbours' spheres) and every
wall, facet and box. The VTK writers (talus.dem.files.export) take, on every process, the
spheres it owns and the contacts it counts (each contact on one process: the rule of the
measurements, ``MpiDomain::countsContact``), and gather their arrays to process 0, which writes
the file in id order, as one process does; a wall's, facet's or box's force is the sum of every
process's share (each computes its own spheres' contacts with it). Writing is collective: every
process calls the writer (as every process runs the same script and engines); process 0 alone
writes the files (and the ``.pvd`` series). Process 0 holds every written body's arrays while it
writes (about 200 bytes a sphere).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from talus import _dem
from talus.dem import distributed

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

_EVERY_PROCESS = ("Wall", "Facet", "Box")    # held whole by every process (replicated)


def is_split(scene: "Scene") -> bool:
    """Whether ``scene`` is split over the processes (the writers then gather)."""
    return distributed.is_split(scene)


def writes(scene: "Scene") -> bool:
    """Whether this process writes files: process 0 of a split scene, or the one process."""
    return not is_split(scene) or distributed.rank() == 0


def _whole_scene_needed(scene: "Scene") -> None:
    """Refuse output before the first step of a scene holding a packing read in slabs (each
    process holds its own part of the file until the split)."""
    if isinstance(distributed.domain(scene), distributed.HeldRows):
        distributed.refuse("file output (VTK, export.text) before the first step of a scene holding a packing read "
                           "in slabs (each process holds its own slab until the split)")


def owned(scene: "Scene", rows: np.ndarray) -> np.ndarray:
    """The rows of ``rows`` holding bodies this process owns (its ghosts left out); all of them
    in one process."""
    _whole_scene_needed(scene)
    if not is_split(scene):
        return rows
    own_rows, _ = scene._domain.ownedBodies(scene._cpp)
    return rows[np.isin(rows, own_rows)]


def global_ids(scene: "Scene", rows: np.ndarray) -> np.ndarray:
    """The ids the script gave the bodies in ``rows`` (the rows themselves in one process)."""
    _whole_scene_needed(scene)
    rows = np.asarray(rows, dtype=np.int64)
    if not is_split(scene):
        return rows
    return np.asarray(scene._domain.globalIds(rows.tolist()), dtype=np.int64).reshape(len(rows))


def counted_contacts(scene: "Scene", id1: np.ndarray, id2: np.ndarray) -> np.ndarray:
    """Per contact (rows ``id1``, ``id2``), whether this process counts it: a contact of two
    spheres on the process owning the lower id, one with a wall, facet or box on the sphere's."""
    if not is_split(scene):
        return np.ones(len(id1), dtype=bool)
    cpp = scene._cpp
    every = np.zeros(cpp.bodyCount(), dtype=bool)
    for kind in _EVERY_PROCESS:
        every[_dem.live_ids(cpp, kind)] = True
    own = np.zeros(cpp.bodyCount(), dtype=bool)
    own[scene._domain.ownedBodies(cpp)[0]] = True
    return np.where(every[id1] | every[id2], own[id1] | own[id2], own[np.minimum(id1, id2)])


def summed(scene: "Scene", values: np.ndarray) -> np.ndarray:
    """``values`` summed over the processes (collective; a wall's force, each process's share)."""
    values = np.asarray(values, dtype=float)
    if not is_split(scene):
        return values
    return np.asarray(scene._domain.sum(values.ravel().tolist())).reshape(values.shape)


def total(scene: "Scene", count: int) -> int:
    """``count`` summed over the processes (what a writer returns on every process)."""
    return int(summed(scene, np.array([float(count)]))[0])


def extremes(scene: "Scene", lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The box holding every process's box ``lo``..``hi`` (collective)."""
    if not is_split(scene):
        return lo, hi
    both = scene._domain.minima([*np.asarray(lo, dtype=float), *(-np.asarray(hi, dtype=float))])
    return np.asarray(both[:3]), -np.asarray(both[3:])


def gather(scene: "Scene", arrays: dict[str, np.ndarray], order: tuple[str, ...]) -> dict | None:
    """Every process's ``arrays`` (one entry per item, the same names, shapes and types on every
    process) put together on process 0, sorted by the arrays ``order`` (ids); None elsewhere
    (collective). In one process, ``arrays``."""
    if not is_split(scene):
        return arrays
    from talus import _distributed
    count = len(next(iter(arrays.values())))
    columns = [np.asarray(a).reshape(count, int(np.prod(np.shape(a)[1:]))) for a in arrays.values()]
    table = np.hstack([c.astype(float) for c in columns]) if columns else np.zeros((count, 0))
    whole = _distributed.gather_rows(np.ascontiguousarray(table), 0)
    if distributed.rank() != 0:
        return None
    out, start = {}, 0
    for (name, array), column in zip(arrays.items(), columns):
        width = column.shape[1]
        out[name] = whole[:, start:start + width].astype(np.asarray(array).dtype).reshape(
            (len(whole), *np.asarray(array).shape[1:]))
        start += width
    sorting = np.lexsort([out[key] for key in reversed(order)])
    return {name: a[sorting] for name, a in out.items()}
