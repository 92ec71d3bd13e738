"""``yade.mpy``: scripts written for Yade's MPI module, run on Talus's decomposition.

A script written for Yade's ``mpy`` runs unchanged as ``mpirun -np N talus run script.py``:
every process runs the script (as under ``mpirun -np N yade script.py``), ``mp.rank`` and
``mp.numThreads`` are the process's rank and the process count, and ``mp.mpirun(nSteps)`` runs
the steps on Talus's decomposition (talus.dem.distributed): at the first step Zoltan splits the
scene over **all** processes, rank 0 included, each holding its spheres, the walls, facets and
boxes on every process. What that changes from Yade's mpy, where rank 0 (the master) holds the
walls only and the workers hold the spheres the script assigned them:

- ``b.subdomain = k`` is accepted (and checked) but not used: Zoltan's partition replaces it
  (printed once); ``mp.DOMAIN_DECOMPOSITION`` is Zoltan's partition too.
- ``mp.REALLOCATE_FREQUENCY`` > 0 keeps Talus's rebalancing on (the regions move when the
  measured imbalance passes talus.dem.distributed.rebalanceThreshold); 0, mpy's default, keeps
  the first partition's regions (bodies still migrate between them as they move).
- ``mp.DISTRIBUTED_INSERT``: each process inserted its own bodies (``O.bodies.insertAtId``);
  ``mp.mpirun`` gathers them so that every process holds the whole scene, then Zoltan splits it.
- what every process reads is the whole scene's: ``O.forces.f(wall)`` is the total force on the
  wall on every process (Yade's workers read their partial force), ``len(O.bodies)`` and loops
  over ``O.bodies`` count every body.
- ``mp.mergeScene()`` (and ``withMerge=True``) leaves the whole scene on every process, as it is
  on Yade's master after a merge (a collective checkpoint written and read back: the scene is
  whole, not split, until the next ``mp.mpirun``, which splits it again).
- ``print`` writes from rank 0 only (talus run under mpirun); ``mp.mprint`` writes from every
  rank up to ``mp.MAX_RANK_OUTPUT``, prefixed ``Master:``/``WorkerN:`` as in Yade.
- ``mp.sendCommand`` sends the command to the workers as Yade does; a worker runs the commands it
  receives once its script has ended (as Yade's workers do under mpiexec), until rank 0's script
  ends. ``mp.comm`` is an mpi4py communicator of every process (a duplicate of COMM_WORLD).
- the flags tuning mpy's own communications (OPTIMIZE_COM, USE_CPP_MPI, ERASE_REMOTE, ...) are
  accepted and have no effect: Talus's halo exchange replaces them.

``talus run script.py`` alone (no mpirun) runs the script in **one process**, with a printed
message: Talus does not spawn workers as ``mp.initialize(np)`` does in Yade (the decomposition
needs processes started by mpirun); ``mp.mpirun(nSteps)`` is then ``O.run(nSteps, True)``, as
Yade's for one process, and ``mp.sendCommand`` reaches rank 0 only.
"""

from __future__ import annotations

import atexit
import os
import sys
import tempfile
import time
import types

from talus.dem import distributed
from talus.dem.core.scenes import default_scene
from talus.dem.split import by_id

# mpy's flags: name -> what Talus does with it. Setting another upper-case name is refused.
_FLAGS = {
    "ACCUMULATE_FORCES": "always: the force on a wall is the sum over every process",
    "VERBOSE_OUTPUT": "wprint writes",
    "NO_OUTPUT": "mprint writes nothing",
    "COLOR_OUTPUT": "mprint's colours",
    "MAX_RANK_OUTPUT": "mprint writes from ranks up to it",
    "TIMEOUT": "seconds a worker waits for rank 0's next command after its script (0: for ever)",
    "YADE_TIMING": "O.timingEnabled during mpirun, timing.stats() after it",
    "DISTRIBUTED_INSERT": "each process inserted its own bodies: gathered before the split",
    "DOMAIN_DECOMPOSITION": "Zoltan's partition (always)",
    "REALLOCATE_FREQUENCY": "> 0: Talus's rebalancing on; 0: the first partition's regions kept",
    "MERGE_W_INTERACTIONS": "a merge always keeps the contacts",
    "AUTO_COLOR": "no effect (bodies keep their colours)",
    "FLUID_COUPLING": "refused (Talus's CFD-DEM coupling has its own decomposition)",
    "ENABLE_PFACETS": "refused (PFacets are not Talus shapes)",
}
_NO_EFFECT = ("SEND_SHAPES", "ERASE_REMOTE", "ERASE_REMOTE_MASTER", "OPTIMIZE_COM", "USE_CPP_MPI", "MERGE_SPLIT",
              "COPY_MIRROR_BODIES_WHEN_COLLIDE", "RESET_SUBDOMAINS_WHEN_COLLIDE", "SEND_BYTEARRAYS", "FAIR_SHARE",
              "MINIMAL_INTERSECTIONS", "REALLOCATE_MINIMAL", "MASTER_UPDATE_STATES", "USE_CPP_REALLOC", "USE_CPP_INTERS")
_FLAGS.update({name: "no effect: Talus's halo exchange replaces mpy's communications" for name in _NO_EFFECT})

ACCUMULATE_FORCES = True
VERBOSE_OUTPUT = False
NO_OUTPUT = False
COLOR_OUTPUT = True
MAX_RANK_OUTPUT = 5
TIMEOUT = 60
YADE_TIMING = False
DISTRIBUTED_INSERT = False
DOMAIN_DECOMPOSITION = False
REALLOCATE_FREQUENCY = 0
MERGE_W_INTERACTIONS = True
AUTO_COLOR = True
FLUID_COUPLING = False
ENABLE_PFACETS = False
SEND_SHAPES = False
ERASE_REMOTE = True
ERASE_REMOTE_MASTER = True
OPTIMIZE_COM = True
USE_CPP_MPI = True
MERGE_SPLIT = False
COPY_MIRROR_BODIES_WHEN_COLLIDE = True
RESET_SUBDOMAINS_WHEN_COLLIDE = False
SEND_BYTEARRAYS = True
FAIR_SHARE = True
MINIMAL_INTERSECTIONS = False
REALLOCATE_MINIMAL = False
MASTER_UPDATE_STATES = False
USE_CPP_REALLOC = True
USE_CPP_INTERS = False

# mpy's message tags (a script may receive on them)
_MASTER_COMMAND_ = 19
_RETURN_VALUE_ = 20

#: This process's rank and the process count (as Yade's mpy sets them at import).
rank = int(os.environ.get("OMPI_COMM_WORLD_RANK", "0"))
numThreads = distributed.RANKS
_REBALANCE = distributed.rebalanceThreshold    # Talus's default, for REALLOCATE_FREQUENCY > 0

_bcolors = ["\x1b[95m", "\x1b[94m", "\x1b[93m", "\x1b[92m", "\x1b[91m", "\x1b[90m"]
_told = set()           # the one-time notices already printed
_namespace = None       # where sendCommand's commands run (see _command_namespace)


class MpyError(ValueError):
    """A call of yade.mpy that Talus refuses, named in the message."""


def _refuse(message: str) -> Exception:
    """The error for ``message``: under mpirun one every process raises alike (reported once)."""
    if distributed.ACTIVE:
        from talus import _distributed
        return _distributed.CollectiveError(message)
    return MpyError(message)


def _mpi():
    """mpi4py's MPI (imported on first use: a script that never sends a message needs no mpi4py)."""
    try:
        from mpi4py import MPI
    except ImportError as e:
        raise MpyError(f"yade.mpy's comm and MPI need mpi4py (Debian's python3-mpi4py): {e}") from None
    return MPI


def mprint(*args, force: bool = False) -> None:
    """Print with the rank's prefix (``Master:``, ``WorkerN:``), from every rank up to
    MAX_RANK_OUTPUT (unless NO_OUTPUT), as Yade's: its workers' standard output is not discarded."""
    if (NO_OUTPUT or rank > MAX_RANK_OUTPUT) and not force:
        return
    colour, reset = (_bcolors[rank % len(_bcolors)], "\x1b[0m") if COLOR_OUTPUT else ("", "")
    who = "Master: " if rank == 0 else f"Worker{rank}: "
    out = sys.stdout if rank == 0 else sys.__stdout__     # talus run discards the workers' sys.stdout
    print(colour + who + "".join(f"{a} " for a in args) + reset, file=out, flush=True)


def wprint(*args) -> None:
    """mprint when VERBOSE_OUTPUT."""
    if VERBOSE_OUTPUT:
        mprint(*args)


def _tell(key: str, message: str) -> None:
    """Print ``message`` once per run, from rank 0."""
    if key not in _told:
        _told.add(key)
        if rank == 0:
            print(f"yade.mpy: {message}", file=sys.stdout, flush=True)


def _check_np(np, where: str) -> None:
    if np is None:
        return
    if isinstance(np, bool) or not isinstance(np, int) or np < 1:
        raise _refuse(f"mpy.{where}: np must be a process count (an integer >= 1), got {np!r}")
    if not distributed.ACTIVE:
        _tell("one", f"{where}(np={np}): this run has one process (talus run without mpirun): Talus does not "
                     f"spawn workers as Yade's mpy does, the script runs here in one process; run it as "
                     f"`mpirun -np {np} talus run script.py` to split it")
    elif np != numThreads:
        _tell("np", f"{where}(np={np}): the run has the {numThreads} processes mpirun started (Talus does not "
                    f"spawn more); the scene is split over them")


def initialize(np: int):
    """Yade's mpy.initialize(np): under mpirun, the processes are mpirun's; returns (rank, numThreads)."""
    _check_np(np, "initialize")
    return rank, numThreads


def disconnect() -> None:
    """Yade's mpy.disconnect(): the processes are mpirun's and stay until the script ends."""


def _check_flags() -> None:
    if FLUID_COUPLING:
        raise _refuse("mpy.FLUID_COUPLING = True: Talus couples the DEM with OpenFOAM through its coupling "
                      "engines, decomposed on both sides (docs/distributed-dem.md), not through mpy")
    if ENABLE_PFACETS:
        raise _refuse("mpy.ENABLE_PFACETS = True: PFacets are not Talus shapes")
    if isinstance(REALLOCATE_FREQUENCY, bool) or not isinstance(REALLOCATE_FREQUENCY, int) or REALLOCATE_FREQUENCY < 0:
        raise _refuse(f"mpy.REALLOCATE_FREQUENCY must be an integer >= 0 (0: no reallocation), got "
                      f"{REALLOCATE_FREQUENCY!r}")


def mpirun(nSteps: int, np: int | None = None, withMerge: bool = False) -> None:
    """Yade's mpy.mpirun: ``nSteps`` steps on every process (``O.run(nSteps, True)``), the scene
    split by Zoltan at its first step; ``withMerge``: the whole scene on every process after."""
    if isinstance(nSteps, bool) or not isinstance(nSteps, int) or nSteps < 0:
        raise _refuse(f"mpy.mpirun: nSteps must be a number of steps (an integer >= 0), got {nSteps!r}")
    _check_np(np, "mpirun")
    _check_flags()
    scene = default_scene()
    if distributed.ACTIVE and not distributed.is_split(scene):
        _before_split(scene)
    scene.timingEnabled = bool(YADE_TIMING)
    scene.run(nSteps, True)
    if ACCUMULATE_FORCES and distributed.is_split(scene):
        _sum_held_forces(scene)
    if withMerge:
        mergeScene()
    if YADE_TIMING:
        from talus.dem.analysis import timing
        timing.stats()


def _before_split(scene) -> None:
    """What the script's flags ask before Zoltan splits the scene (its next step)."""
    if DISTRIBUTED_INSERT and not getattr(scene, "_gathered", False):     # (a merged scene is whole already)
        _gather_inserted(scene)
        scene._gathered = True
    distributed.rebalanceThreshold = _REBALANCE if REALLOCATE_FREQUENCY > 0 else None
    assigned = len(getattr(scene, "_subdomains", {}))
    if assigned:
        _tell("subdomain", f"Zoltan partitions the scene over the {numThreads} processes, rank 0 included "
                           f"({assigned} bodies' b.subdomain not used)")


def _record(b) -> tuple:
    """What rebuilds body ``b`` (a sphere or a box) on another process."""
    kind = type(b.shape).__name__
    if kind not in ("Sphere", "Box"):
        raise _refuse(f"mpy.DISTRIBUTED_INSERT: body {b.id} is a {kind}: the bodies each process inserts are "
                      f"gathered as spheres and boxes only")
    size = b.shape.radius if kind == "Sphere" else tuple(b.shape.extents)
    material = b.material.id if b.material is not None else -1
    q = b.state.ori
    return (b.id, kind, tuple(b.state.pos), size, (q.w, q.x, q.y, q.z), tuple(b.state.vel), tuple(b.state.angVel),
            tuple(b.shape.color), b.shape.wire, b.dynamic, material, b.mask)


def _gather_inserted(scene) -> None:
    """DISTRIBUTED_INSERT: every process's bodies, gathered so that every process holds the whole
    scene in id order (ids nobody inserted left erased), which Zoltan then splits."""
    from talus.dem.core.bodies import box, sphere
    records = {}
    for r, mine in enumerate(_comm().allgather([_record(b) for b in scene.bodies])):
        for record in mine:
            if record[0] in records:
                raise _refuse(f"mpy.DISTRIBUTED_INSERT: body {record[0]} was inserted by rank {records[record[0]][0]} "
                              f"and by rank {r}: each id must be inserted by one process")
            records[record[0]] = (r, record)
    scene.bodies.clear()
    materials = len(scene.materials)
    for id in range(max(records, default=-1) + 1):
        if id not in records:
            scene.bodies.erase(scene.bodies.append(sphere((0, 0, 0), 1)))
            continue
        _, kind, pos, size, ori, vel, angVel, color, wire, dynamic, material, mask = records[id][1]
        material = material if 0 <= material < materials else -1
        if kind == "Sphere":
            spec = sphere(pos, size, material=material, fixed=not dynamic, color=color, wire=wire, mask=mask)
        else:
            spec = box(pos, size, orientation=ori, material=material, fixed=not dynamic, color=color, wire=wire,
                       mask=mask)
        b = scene.bodies[scene.bodies.append(spec)]
        b.state.vel, b.state.angVel = vel, angVel


def _sum_held_forces(scene) -> None:
    """The forces and torques on the bodies every process holds (walls, facets, boxes), summed
    over the processes now (collective), so that rank 0 alone reads them with O.forces.f until
    the next step, as Yade's master reads the forces on its bodies (ACCUMULATE_FORCES)."""
    split, cpp = distributed.domain(scene), scene._cpp
    owned = set(int(r) for r in split.ownedBodies(cpp)[0])
    alive = cpp.alive()
    held = [r for r in range(cpp.bodyCount()) if alive[r] and r not in owned and split.owns(r)]
    scene._summedForces = (scene.iter, {int(i): split.forceOf(cpp, int(i)) for i in split.globalIds(held)})


def mergeScene() -> None:
    """Yade's mpy.mergeScene: the whole scene on every process, not split until the next
    mpirun (collective: a checkpoint every process writes and reads back, contacts included)."""
    scene = default_scene()
    if not distributed.is_split(scene):
        return
    comm = _comm()
    path = comm.bcast(os.path.join(tempfile.gettempdir(), f"talus-mpy-merge-{os.getpid()}.h5") if rank == 0 else None)
    try:
        scene.save(path)
        scene.load(path, engines="current")
        scene._merged = True    # O.save from rank 0 alone then writes it (as from Yade's master)
    finally:
        comm.Barrier()
        if rank == 0 and os.path.exists(path):
            os.remove(path)


def _comm():
    """mpi4py's communicator of every process (a duplicate of COMM_WORLD: the script's messages
    never meet Talus's own)."""
    global comm
    if "comm" not in globals():
        comm = _mpi().COMM_WORLD.Dup()
    return comm


def _executors(executors) -> list[int]:
    if executors == "all":
        return list(range(numThreads))
    if executors == "slaves":
        return list(range(1, numThreads))
    listed = executors if isinstance(executors, list) else [executors]
    for w in listed:
        if isinstance(w, bool) or not isinstance(w, int) or not 0 <= w < numThreads:
            how = ("this run has one process (talus run without mpirun: Talus does not spawn workers); run it "
                   "under mpirun" if numThreads == 1 else f"the ranks are 0 to {numThreads - 1}")
            raise MpyError(f"mpy.sendCommand: executors={executors!r}: no rank {w!r}: {how}")
    return listed


def _command_namespace() -> dict:
    """Where commands run: Yade's names and this module's (comm, rank, mprint), as in Yade,
    which runs them in its mpy module."""
    global _namespace
    if _namespace is None:
        import yade
        _namespace = yade.script_namespace()
        _namespace.update({k: v for k, v in globals().items() if not k.startswith("__")})
        _namespace["comm"] = _comm()
    return _namespace


def sendCommand(executors, command: str, wait: bool = True, workerToWorker: bool = False):
    """Yade's mpy.sendCommand: rank 0 has ``executors`` ("all", "slaves", a rank or a list) run
    ``command``; with ``wait``, returns the result (a list for a list of executors). A worker
    runs it once its own script has ended. On a worker it returns None (unless workerToWorker)."""
    if rank > 0 and not workerToWorker:
        wprint("sendCommand ignored by worker", rank, ", pass workerToWorker=True to force it")
        return None
    if not isinstance(command, str):
        raise MpyError(f"mpy.sendCommand: command must be a string of Python, got {command!r}")
    listed = _executors(executors)
    comm = _comm() if numThreads > 1 else None
    sent = command if not wait else (f"resCommand={command};comm.send(resCommand,dest={rank},"
                                      f"tag={_RETURN_VALUE_})")
    requests = [comm.isend(sent, dest=w, tag=_MASTER_COMMAND_) for w in listed if w != rank]
    results = [eval(command, _command_namespace())] if rank in listed else []
    if wait:
        results += [comm.recv(source=w, tag=_RETURN_VALUE_) for w in listed if w != rank]
        return results if isinstance(executors, list) or executors in ("all", "slaves") else results[0]
    for r in requests:
        r.wait()
    return None


def _serve_commands() -> None:
    """A worker, its script ended: run rank 0's commands until rank 0's script ends (Yade's
    workers do so under mpiexec) or TIMEOUT seconds pass without one."""
    MPI = _mpi()
    if MPI.Is_finalized():
        return
    comm, status = _comm(), MPI.Status()
    while True:
        deadline = time.time() + TIMEOUT
        while not comm.Iprobe(source=MPI.ANY_SOURCE, tag=_MASTER_COMMAND_, status=status):
            if TIMEOUT and time.time() > deadline:
                mprint(f"no command from rank 0 for {TIMEOUT} s (mpy.TIMEOUT): ending", force=True)
                return
            time.sleep(0.001)
        command = comm.recv(source=status.Get_source(), tag=_MASTER_COMMAND_)
        if command == "exit":
            return
        try:
            exec(command, _command_namespace())
        except Exception as e:      # reported, and rank 0 not left waiting for a result
            mprint(f"command {command!r} failed: {e!r}", force=True)
            comm.send(None, dest=status.Get_source(), tag=_RETURN_VALUE_)


def _end_of_script() -> None:
    """Rank 0's script ended: its workers stop serving commands."""
    MPI = _mpi()
    if MPI.Is_finalized():
        return
    comm = _comm()
    for r in [comm.isend("exit", dest=w, tag=_MASTER_COMMAND_) for w in range(1, numThreads)]:
        r.wait()


# mpy's internals: their names, for the message when a script calls one.
_INTERNALS = ("splitScene", "parallelCollide", "sendRecvStates", "isendRecvForces", "waitForces", "checkAndCollide",
              "updateDomainBounds", "genLocalIntersections", "reallocateBodiesToSubdomains", "migrateBodies",
              "medianFilter", "eraseRemote", "bodyErase", "updateAllIntersections", "configure",
              "spawnedProcessWaitCommand", "declareMasterInteractive", "colorDomains", "mpiStats")


class _Module(types.ModuleType):
    """Checks what a script sets and asks for (a misspelt flag would otherwise be ignored)."""

    def __setattr__(self, name, value):
        if name.isupper() and not name.startswith("_") and name not in _FLAGS:
            raise _refuse(f"yade.mpy has no flag {name}: its flags are {', '.join(sorted(_FLAGS))}")
        super().__setattr__(name, value)
        if name in ("FLUID_COUPLING", "ENABLE_PFACETS", "REALLOCATE_FREQUENCY"):
            _check_flags()

    def __getattr__(self, name):
        if name == "comm":
            return _comm()
        if name == "MPI":
            return _mpi()
        if name.startswith("__"):
            raise AttributeError(name)
        what = ("one of mpy's internals (its own splitting and communications), which Talus replaces with its "
                "decomposition" if name in _INTERNALS else "not part of Yade's mpy as Talus serves it")
        raise AttributeError(f"yade.mpy.{name} is {what}; scripts use initialize, mpirun, mergeScene, "
                             f"sendCommand, mprint, comm, rank, numThreads and the flags (docs/distributed-dem.md)")


sys.modules[__name__].__class__ = _Module

if distributed.ACTIVE and numThreads > 1:
    _comm()     # collective: every process imports mpy (the script is the same)
    atexit.register(_serve_commands if rank > 0 else _end_of_script)
    # the workers' scripts end before rank 0's, which may still be sending them commands
    by_id.agree_at_end = False
