"""``O.bodies[id]`` under ``mpirun -np N talus run``: any body of the scene, on every process.

A script reads bodies by id (``O.bodies[ball].state.pos[1]`` in a PyRunner, a plot of two
spheres, a velocity set on one body). Under mpirun only the process owning a sphere or clump
holds its state, so reading it by id is **collective**, as a loop over ``O.bodies`` is: every
process runs the script, so every process reads the same ids in the same order, and the owner
sends the others the body's snapshot (talus.dem.split.bodies: state, shape, material, dynamic,
mask, clump) as it answers. The owner gets the body itself, the others the snapshot: a write
through it (``b.state.vel = ...``, ``b.dynamic``, ``b.state.blockedDOFs``) changes the snapshot
only, the owner making the same write to the body, and the ghosts take it at the end of the
PyRunner or loop, or when the next ``O.run``/``O.step`` starts (talus.dem.distributed.update_ghosts);
what that update does not carry (mass, inertia, blockedDOFs, dynamic, mask) a process holding a
copy of the body writes to its copy at once (talus.dem.split.bodies).
Walls, facets and boxes, which every process holds, are read as they are, without an exchange.

**The rule: code that only some processes run must not read a sphere or clump by id** (a branch
on the rank, on a process's own rows, in a PyRunner run by wall time, ``realPeriod``, which the
processes run at different steps). The processes say where they are in every by-id read and at
the points every process passes through alike (the start of a step, the end of each PyRunner's
command, the start of a loop over ``O.bodies``, the end of the script), all over a channel of
their own (a duplicate of MPI_COMM_WORLD), so that a read made by some processes only meets the
others at their next such point, or at a read of another id, and every process raises one
CollectiveError naming the rule and what each process was doing. A process left alone in a
read while the others wait in another collective call (a measurement such as
``unbalancedForce()``, which the others reached first) cannot be told: after ``patience``
seconds it prints the rule and ends the run, never hangs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from talus.dem import distributed
from talus.dem.split import bodies as split_bodies

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

#: Seconds a process waits for the other processes in a by-id read or at an agreement point
#: before it ends the run naming the rule (they are held in another collective call).
patience = 120.0

# Where a process is, as the others are told: a read of body `id`, or a point every process
# passes through alike.
READ, STEP, PYRUNNER, LOOP, END = 1, 2, 3, 4, 5
_DOING = {READ: "read O.bodies[{id}]", STEP: "started O.run or O.step", PYRUNNER: "ended a PyRunner's command",
          LOOP: "started a loop over O.bodies", END: "reached the end of the script"}
_HEAD = 3   # place, id, whether this process sent the body's snapshot (script/Snapshot.h)

RULE = ("under mpirun O.bodies[id] of a sphere or clump is collective: every process must read the same ids in the "
        "same order, as it runs the same script (the owner answers with the body, the others get a snapshot of it); "
        "code that only some processes run (a branch on the rank or on a process's own bodies, a PyRunner run by "
        "realPeriod) must not read bodies by id: read them before the branch, on every process")


def _doing(place: float, id: float) -> str:
    return _DOING[int(place)].format(id=int(id))


def _check(table: np.ndarray) -> None:
    """Raise on every process when the processes' rows (place, id, ...) say they are at
    different places of the script."""
    if (table[:, :2] != table[0, :2]).any():
        where = "; ".join(f"process {r} {_doing(*table[r, :2])}" for r in range(len(table)))
        from talus import _distributed     # under mpirun only: a build without the DEM over MPI has none
        raise _distributed.CollectiveError(f"the processes are at different places of the script ({where}): {RULE}")


#: Whether the end of the script is an agreement point (not when the processes go on talking
#: after it: yade.mpy's workers serve rank 0's commands once their own scripts end).
agree_at_end = True

_said: dict[int, tuple[np.ndarray, str]] = {}     # per agreement point: what this process sends, its message


def agree(place: int) -> None:
    """An agreement point (STEP, PYRUNNER, LOOP, END), which every process passes through alike
    (collective under mpirun; nothing in one process)."""
    if not distributed.ACTIVE:
        return
    from talus import _distributed     # under mpirun only: a build without the DEM over MPI has none
    if place not in _said:
        # the same width on every process in every exchange: a read's, an agreement's
        mine = np.zeros(_HEAD + _distributed.snapshot_doubles)
        mine[0], mine[1] = place, -1
        _said[place] = mine, (f"talus run: process {distributed.rank()} {_doing(place, -1)} and the other processes "
                              f"did not come to it: {RULE}")
    mine, waiting = _said[place]
    _check(_distributed.script_gather(mine, float(patience), waiting))


def body(scene: "Scene", id: int, view: Callable[[int, int], object]):
    """Body ``id`` of a scene split over the processes (collective for a sphere or clump, see
    the module): ``view(row, id)`` where this process owns it or holds it as every process
    does (a wall, facet or box), its snapshot elsewhere, None if it was erased."""
    local, row, agreed, table = scene._domain.readById(scene._cpp, id, float(patience), RULE)
    if not agreed:
        _check(table)
    if local or row >= 0:
        return None if row < 0 else view(row, id)
    sent = table[:, 2] == 1
    return split_bodies.RemoteBody(scene, table[sent.argmax(), _HEAD:], view) if sent.any() else None


def agreeing(callback: Callable[[], None], engine) -> Callable[[], None]:
    """A PyRunner's ``callback`` followed, under mpirun, by the agreement point at the end of its
    command (not when the engine runs by wall time, ``realPeriod``: the processes call it at
    different steps, as they skip its ghost update)."""
    if not distributed.ACTIVE:
        return callback

    def run():
        callback()
        if engine.realPeriod == 0:
            agree(PYRUNNER)
    return run
