"""A script's per-body arrays and sums under ``mpirun -np N talus run``: each process's share.

The per-body arrays of a scene (``positions()``, ``velocities()``, ``forces()``, ``radii()``,
...: the particle exchange interface) are views of the storage the engines and couplings write
in place. Once the scene is split over the processes, a process's arrays hold its own rows: its
bodies, the walls, facets and boxes (every process holds them) and copies of its neighbours'
bodies (ghosts), by ascending id. An index by the script's ids (``s.velocities()[ids] = 0``)
would reach other bodies or run past the end; making the index collective would need a gather
and a scatter at every access. So a script written for both one process and mpirun says which
rows it means and adds up the processes' shares:

- ``rows(scene, ids)``: the rows of the bodies of ``ids`` this process acts on;
  ``s.velocities()[rows(s, ids)] = 0`` stops the same bodies in one process and under mpirun;
- ``total(x)`` adds every process's share (a sum over its rows), ``largest(x)`` takes the
  largest;
- ``once(f, ...)`` runs what the run must do once, not once per process, on process 0 and gives
  its result to every process (a folder made and its path shared, a fluid case written, a tool
  such as ``reconstructPar`` run).

In one process each is the plain value or call. ``total``, ``largest`` and ``once`` are
collective under mpirun: every process calls them at the same point of the script, as it runs
the script alike.
"""

from __future__ import annotations

import numpy as np

from talus.dem import distributed


def rows(scene, ids) -> np.ndarray:
    """The rows of ``scene``'s per-body arrays holding bodies ``ids`` that this process acts on,
    in the order of ``ids``. In one process (and under mpirun before the first step, every
    process holding the whole scene) the rows are the ids. Once the scene is split: the rows of
    the bodies of ``ids`` this process owns and of the walls, facets and boxes among them (every
    process holds those, and a write there is made alike on every process). A write through the
    rows is the owner's (its copies on the other processes follow at the next step); a sum over
    them is this process's share. Rows change as bodies move between processes: take them again
    after each run. Held in slabs (a packing read in slabs, before the first step): the rows of
    the ids this process holds. Erased bodies have no row."""
    ids = np.asarray(ids, dtype=np.int64).reshape(-1)
    d = distributed.domain(scene)
    if d is None:
        return ids
    if isinstance(d, distributed.HeldRows):
        held = np.frombuffer(d.globalId, dtype=np.int64)
        if not len(held):
            return np.zeros(0, dtype=np.int64)
        at = np.minimum(np.searchsorted(held, ids), len(held) - 1)
        return at[held[at] == ids]
    return d.rowsActedOn(ids)


def total(values):
    """``values`` (a number, or an array of numbers) summed over the processes, on every
    process: each process's share, such as a sum over its own rows, becomes the whole scene's.
    The shares are added in rank order, so every process gets the same bits."""
    if not distributed.ACTIVE:
        return values
    from talus import _distributed
    shares = np.asarray(values, dtype=np.float64)
    every = _distributed.gather_rows(shares.reshape(1, -1), -1)     # a row per process, in rank order
    summed = every.sum(axis=0)
    return float(summed[0]) if shares.ndim == 0 else summed.reshape(shares.shape)


def largest(value: float) -> float:
    """The largest of every process's ``value``, on every process."""
    if not distributed.ACTIVE:
        return value
    from talus import _distributed
    return -_distributed.smallest(-float(value))


def once(function, *args, **kwargs):
    """``function(*args, **kwargs)`` run by process 0 alone, its result (anything pickle takes)
    returned on every process, the others waiting for it. Not for a call that is itself
    collective (the others are not there to join it). An exception on process 0 is raised on
    every process, with its message."""
    if not distributed.ACTIVE:
        return function(*args, **kwargs)
    result, error = None, None
    if distributed.rank() == 0:
        try:
            result = function(*args, **kwargs)
        except Exception as e:      # the others must not wait for a result that never comes
            error = f"{type(e).__name__} on process 0: {e}"
    result, error = distributed.gather_objects((result, error) if distributed.rank() == 0 else None)[0]
    if error is not None:
        from talus import _distributed
        raise _distributed.CollectiveError(error)
    return result
