"""The same script under ``mpirun -np N talus run script.py``: the DEM split over MPI processes.

Every process runs the whole script and builds the scene it makes, except a packing read from a
file by ``ymport.text``/``textExt``, of which each process makes only its own slab
(talus.dem.files.slabs; until the first step, what needs the whole scene is refused). When the
script's first ``O.run``/``O.step`` starts, the spheres and clumps are partitioned (Zoltan's RCB,
or HSFC with ``TALUS_PARTITION=HSFC``; a clump by its centre of mass, its members going with it) and each process keeps its own, the walls, facets
and fixed boxes (every process holds them, moves them alike and computes their contacts with
its own spheres) and ghosts, copies of the spheres (and whole clumps) of its neighbours within reach
(dem/distributed/, docs/distributed-dem.md); a contact's state (Hertz-Mindlin, visco-elastic,
cohesive-frictional) moves with it. From then on:

- ``unbalancedForce()``, ``utils.kineticEnergy()`` (with ``findMaxId``), ``O.forces.f(id)`` of
  a wall, ``O.energy``, ``getStress``, ``getStressAndTangent``, ``bodyStressTensors``,
  ``avgNumInteractions``, ``fabricTensor``, ``porosity``, ``aabbExtrema``, ``PWaveTimeStep``,
  ``momentum``, ``angularMomentum``, ``sumForces``, ``totalForceInVolume``, ``getSpheresVolume``,
  ``getSpheresMass`` and the step GlobalStiffnessTimeStepper sets give the whole scene's value on
  every process (reductions: every process calls them), so a PyRunner testing them acts alike on
  all; TriaxialStressController and ServoPIDController move the walls alike on every process
  (the walls' forces summed exactly: the serial bits);
- ``print`` writes from process 0 only (the others' standard output is discarded);
- ``O.bodies[i]`` of a sphere or clump is collective: every process reads it (the owner gets the
  body, the others its snapshot: talus.dem.split.by_id, which names the rule for code some
  processes only run); an erased body is None on every process. ``for b in O.bodies``
  visits every body on every process (a snapshot for one owned elsewhere: talus.dem.split.bodies),
  ``positions()`` gathers every body's position, ``O.bodies.gather(ids)`` snapshots of any
  bodies, ``O.interactions`` gives every contact once (talus.dem.split.contacts), all on
  every process (collective); plots, VTK output and ``export.text`` are written by process 0.
- ``O.bodies.erase(i)`` must be called on every process with the same ids (from code every
  process runs alike, deciding from global values such as ``positions()``): each process erases
  its copy, whoever owns the body; a process that erased other bodies stops the run, naming the
  rule, at the next re-detection.
- kinematic engines (TranslationEngine, RotationEngine, ...) and force engines act on their
  ``ids`` where each body is owned (walls and facets: on every process alike).
- a periodic cell of spheres is split in its reduced coordinates (the processes' regions move
  with the cell as ``O.cell.velGrad``, PeriTriaxController, PeriIsoCompressor or
  Peri3dController deforms it; ghosts across its faces); every process updates the cell alike,
  from the same reductions (the controllers' stress, stiffness, mass and unbalanced force are
  exact sums: the serial bits), and a script must change
  ``O.cell`` alike on every process; its walls, facets and boxes (a floor under a bed periodic
  across x and y) every process holds whole, as in an open scene.

What is not distributed yet is refused, on every process alike, with its name: shapes other than
spheres, clumps of spheres, walls, facets and fixed boxes, a wall, facet or box moved by forces,
a clump of spheres of a packing read in slabs, engines other than ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator, PyRunner, GravityEngine,
GlobalStiffnessTimeStepper, PeriTriaxController, PeriIsoCompressor, Peri3dController,
TriaxialStressController, TriaxialCompressionEngine, ServoPIDController and the kinematic and force
engines, contact laws other than the
linear, Hertz-Mindlin, visco-elastic and cohesive-frictional ones, force engines on walls or
facets. ``O.save`` writes one checkpoint from every process, ``O.load`` reads one
(written at any process count) on every process; the scene is split again at its next step.
"""

from __future__ import annotations

import atexit
import os
import sys

from talus.dem.core.scenes import default_scene

#: Processes of the run (Open MPI's mpirun tells each process).
RANKS = int(os.environ.get("OMPI_COMM_WORLD_SIZE", "1"))
#: Whether the script's scene is split over them: `talus run` under mpirun (start()) only. A
#: program of its own under mpirun (an mpi4py driver of FEM x DEM RVEs, one scene per Gauss
#: point) keeps each scene in its process, and no call here becomes collective.
ACTIVE = False

#: Engines that act on bodies named by id: each process acts on those it owns (Scene::rowsActedOn).
_KINEMATIC = ("TranslationEngine", "RotationEngine", "HarmonicMotionEngine", "HelixEngine", "InterpolatingHelixEngine",
              "CombinedKinematicEngine")
_FORCES = ("ForceEngine", "InterpolatingDirectedForceEngine", "HarmonicForceEngine")
_ENGINES = ("ForceResetter", "InsertionSortCollider", "InteractionLoop", "NewtonIntegrator", "PyRunner",
            "GravityEngine", "GlobalStiffnessTimeStepper", "PeriTriaxController", "PeriIsoCompressor", "Peri3dController",
            "TriaxialStressController",
            "ServoPIDController", "TriaxialCompressionEngine", "VTKRecorder",
            *_KINEMATIC, *_FORCES)
_LAWS = ("Law2_ScGeom_FrictPhys_CundallStrack", "Law2_ScGeom_MindlinPhys_Mindlin", "Law2_ScGeom_ViscElPhys_Basic",
         "Law2_ScGeom6D_CohFrictPhys_CohesionMoment")
#: The measured imbalance (the slowest process's compute time over the mean between two
#: re-detections) above which the processes partition again, each body weighted by its measured
#: cost, at the next re-detection (as the weights and the regions change, positions do not: the
#: same bits). At least 1; None: never. Read when the scene is split (its first step).
rebalanceThreshold = 1.1
_rank = 0
_NO_BODY = -2    # what Domain.rowOf gives for an id that is no live body (Domain::noBody)


class NotDistributed(RuntimeError):
    """A feature the distributed DEM does not have yet, asked for under mpirun: raised on every
    process alike (the script is the same), so each stops on its own."""


def start() -> None:
    """Set up MPI for this process (``talus run`` under mpirun): standard output from process 0
    only, MPI finalised at exit."""
    global _rank, ACTIVE
    from talus import _distributed
    ACTIVE = True
    _release_default_binding()
    _rank, _ = _distributed.init()
    atexit.register(_distributed.finalize)
    if _rank != 0:
        sys.stdout = open(os.devnull, "w")


def _release_default_binding() -> None:
    """Give every thread of this process the CPUs mpirun may use, unless the user asked for a
    binding (``--bind-to`` sets OMPI_MCA_hwloc_base_binding_policy). Open MPI binds up to two
    processes to one core each by default: a process cannot then leave a core that other work
    keeps busy while every step waits for it, and the OpenMP threads of ``-j N`` share its one
    core. Threads already started get the wider set too (Linux sets it per thread)."""
    if "OMPI_COMM_WORLD_SIZE" not in os.environ or "OMPI_MCA_hwloc_base_binding_policy" in os.environ:
        return
    try:
        allowed = os.sched_getaffinity(os.getppid())
        if allowed <= os.sched_getaffinity(0):
            return
        for thread in os.listdir("/proc/self/task"):
            os.sched_setaffinity(int(thread), allowed)
    except OSError:     # a thread that ended meanwhile, or a set the system refuses: keep mpirun's
        pass


def refuse(what: str) -> None:
    """Raise NotDistributed for ``what`` when running under mpirun."""
    if ACTIVE:
        raise NotDistributed(f"{what} is not distributed yet: under mpirun ({RANKS} processes) the DEM runs "
                             f"{', '.join(_ENGINES)} with spheres, clumps, walls, facets and boxes and the contact laws "
                             f"{', '.join(_LAWS)} only; run "
                             f"this script in one process (talus run, without mpirun)")


def domain(scene):
    """The MPI domain of ``scene``, None when it runs in one process (before its split: None, or
    the ids of its rows when it holds a slab of a packing, HeldRows)."""
    return getattr(scene, "_domain", None)


def is_split(scene) -> bool:
    """Whether ``scene`` was split over the processes (its first step under mpirun has started)."""
    return domain(scene) is not None and not isinstance(domain(scene), HeldRows)


class HeldRows:
    """The rows of a scene built in slabs under mpirun, before its split (the domain of it until
    then): every process holds the bodies appended one by one and its own slab of each packing
    read in slabs (talus.dem.files.slabs), each row with the id it has in one process. Only
    what needs no other process's bodies works (O.bodies[id] of a body held here, len); the
    rest is refused by name until the first step splits the scene."""

    def __init__(self, rows: int):
        from array import array
        self.rank, self.ranks = _rank, RANKS
        self.globalId = array("q", range(rows))     # per row, ascending
        self.own = array("B", bytes(rows))          # per row: of this process's slab only
        self.globalCount = rows

    def added(self, row: int, id: int | None) -> int:
        """Record row ``row`` just added, as body ``id`` of this process's slab, or (None) as
        the next body, which every process adds; returns its id."""
        if row != len(self.globalId):
            raise RuntimeError(f"row {row} added out of order (expected {len(self.globalId)})")
        self.globalId.append(self.globalCount if id is None else id)
        self.own.append(id is not None)
        self.globalCount = max(self.globalCount, self.globalId[-1] + 1)
        return self.globalId[-1]

    def rowOf(self, id: int) -> int:
        import bisect
        row = bisect.bisect_left(self.globalId, id)
        return row if row < len(self.globalId) and self.globalId[row] == id else -1    # Domain::elsewhere

    def owns(self, row: int) -> bool:
        return row >= 0

    def min(self, value: float) -> float:
        """The smallest of every process's ``value`` (collective): a minimum over the bodies each
        holds is the whole scene's (PWaveTimeStep before the first step)."""
        from talus import _distributed
        return _distributed.smallest(float(value))

    def minima(self, values) -> list[float]:
        """Each of ``values``' smallest over the processes (collective), as ``min``: a body every
        process holds counts once or more alike (aabbExtrema and aabbWalls before the first step)."""
        return [self.min(value) for value in values]

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise NotDistributed(f"{name} of a scene holding a packing read in slabs, before its first step, "
                             f"is not distributed: each of the {RANKS} processes holds its own slab of the "
                             f"file until the first step splits the scene; call it after the first step")


def added(scene, row: int, id: int | None = None) -> int:
    """The id of the body just added at row ``row`` (``id`` for a sphere of a slab): the row in
    a scene built whole."""
    held = domain(scene)
    return held.added(row, id) if isinstance(held, HeldRows) else row


def clumpable_row(scene, id: int) -> int:
    """The row of body ``id`` to clump in a scene holding a packing read in slabs, before its
    split: a body every process holds (appended one by one), whose clump every process makes
    alike; a sphere of a slab (held by one process) is refused by name."""
    held = domain(scene)
    row = held.rowOf(int(id))
    if row < 0 or held.own[row]:
        refuse(f"a clump of body {id}, a sphere of a packing read in slabs (each process holds its own slab: clump "
               f"bodies every process appends, or read the packing whole)")
    return row


def append_slab(bodies, slab) -> range:
    """O.bodies.append of a slab of a file's spheres (talus.dem.files.slabs): the file's count of
    ids, of which this process adds its slab's; returns the ids (as a list of them would be)."""
    scene = bodies._scene
    if not isinstance(domain(scene), HeldRows):
        scene._domain = HeldRows(scene._cpp.bodyCount())
    held = domain(scene)
    start = held.globalCount
    next_id = start + slab.first
    rows = scene._cpp.bodyCount() + slab.size   # the per-row tables grown once, not chunk by chunk
    scene._appearance.ensure(rows)
    scene._reference.ensure(rows)
    for chunk in slab.chunks():
        bodies._append_specs(chunk, range(next_id, next_id + len(chunk)))
        next_id += len(chunk)
    held.globalCount = start + slab.count
    return range(start, start + slab.count)


def attach(scene) -> None:
    """Split ``scene`` over the processes (at its first step under mpirun; collective); once
    split, send what the script wrote into its bodies since the last step to their ghosts."""
    if not ACTIVE:
        return
    if is_split(scene):
        update_ghosts(scene)
        return
    for e in scene.engines:
        name = type(e).__name__
        if name not in _ENGINES:
            refuse(f"the engine {name}")
        for law in getattr(e, "lawFunctors", ()):
            if type(law).__name__ not in _LAWS:
                refuse(f"the contact law {type(law).__name__}")
        if name in _FORCES:     # on a wall or facet every process would add it: summed, it would count N times
            for i in e.ids:
                if row_of(scene, i, missing=None) is None:  # erased, or a sphere of another slab
                    continue
                body = scene.bodies[i]
                if body is not None and type(body.shape).__name__ != "Sphere":
                    refuse(f"{name} on body {i}, a {type(body.shape).__name__} (a force engine acts on spheres "
                           f"only under mpirun)")
    from talus import _distributed
    import numpy as np
    method = os.environ.get("TALUS_PARTITION", "RCB")
    _zero_permanent_force_copies(scene)
    held = domain(scene)
    if isinstance(held, HeldRows):
        _looks_by_id(scene, held)
        scene._reference_by_row = True
        scene._domain = _distributed.attach(scene._cpp, method, np.frombuffer(held.globalId, dtype=np.int64),
                                            np.frombuffer(held.own, dtype=np.uint8), held.globalCount)
    else:
        scene._domain = _distributed.attach(scene._cpp, method)
    scene._domain.rebalanceThreshold = _rebalance_threshold()


def held_everywhere(scene, row: int) -> bool:
    """Whether row ``row`` is a wall, facet or box, which every process holds under mpirun."""
    return scene._cpp.shapeKind(row) in ("Wall", "Facet", "Box")


def _zero_permanent_force_copies(scene) -> None:
    """At the split: the permanent forces and torques of the walls, facets and boxes kept by
    process 0 only (every process set them alike; their shares are summed)."""
    if rank() != 0:
        for row in range(scene._cpp.bodyCount()):
            if held_everywhere(scene, row):
                scene._cpp.extForce()[row] = 0
                scene._cpp.extTorque()[row] = 0


def update_ghosts(scene) -> None:
    """Send the state of the bodies each process owns to its copies on the other processes
    (collective; nothing in one process). Each step does it after the integration; a script's
    writes between two steps (``b.state.vel = ...`` in a loop over the bodies, a PyRunner, between
    two ``O.run``) need it once more, or the next contacts would be computed with the copies'
    old state: ``O.run``, ``O.step`` and the end of a loop over ``O.bodies`` call it, and each
    PyRunner's call ends with the same update in C++ (dem/engines/CallbackEngine.cpp), on its own scene."""
    if is_split(scene):
        scene._domain.updateGhosts(scene._cpp)


def _looks_by_id(scene, held: HeldRows) -> None:
    """Key the looks (colour, highlight, wire) of a scene built in slabs by body id, as they are
    once it is split (talus.dem.geometry.appearance), every process holding every body's: each
    process's own slab's looks other than the default are sent to all (collective)."""
    from talus import _distributed
    import numpy as np
    from talus.dem.geometry.appearance import DEFAULT_COLOR, Appearance
    ids = np.frombuffer(held.globalId, dtype=np.int64)
    scene._appearance.ensure(len(ids))
    color, highlight, wire = (getattr(scene._appearance, name)[:len(ids)] for name in ("color", "highlight", "wire"))
    new = Appearance()
    new.ensure(held.globalCount)
    new.color[ids], new.highlight[ids], new.wire[ids] = color, highlight, wire
    own = np.frombuffer(held.own, dtype=np.uint8).astype(bool)
    changed = own & ((color != DEFAULT_COLOR).any(axis=1) | highlight | wire)
    table = np.column_stack([ids[changed], color[changed], highlight[changed], wire[changed]])
    for row in _distributed.gather_rows(table, -1):
        new.color[int(row[0])], new.highlight[int(row[0])], new.wire[int(row[0])] = row[1:4], row[4], row[5]
    scene._appearance = new


def _rebalance_threshold() -> float:
    """rebalanceThreshold checked (the same on every process: the script is): infinity for None."""
    threshold = float("inf") if rebalanceThreshold is None else float(rebalanceThreshold)
    if not threshold >= 1:
        from talus import _distributed
        raise _distributed.CollectiveError(
            f"talus.dem.distributed.rebalanceThreshold {rebalanceThreshold} is below 1: it is the slowest "
            f"process's compute time over the mean above which the processes partition again (None: never)")
    return threshold


def row_of(scene, id: int, missing=IndexError) -> int | None:
    """The row of body ``id`` in this process's arrays, None if it was erased; raises for a
    body owned elsewhere (returns None if ``missing`` is None)."""
    d = domain(scene)
    if d is None:
        return id
    row = d.rowOf(int(id))
    if row == _NO_BODY:
        return None
    if missing is None and not d.owns(row):
        return None
    if not d.owns(row):
        raise IndexError(f"body {id} is owned by another process: under mpirun (rank {d.rank} of {d.ranks}) a "
                         f"body's state lives on the process that owns it; read it with O.bodies.gather([{id}]) or "
                         f"in a loop over O.bodies (both collective: every process runs them, as it runs the "
                         f"script), or every body's position with talus.dem.distributed.positions()")
    return row


def global_ids(scene, rows) -> list[int]:
    """The ids, in the scene the script built, of rows ``rows`` of this process's arrays (what a
    clump's member list and a member's clumpId hold); the rows themselves in one process."""
    d = domain(scene)
    return [int(r) for r in rows] if d is None else d.globalIds([int(r) for r in rows])


def erase(scene, id: int, eraseClumpMembers: bool = False) -> bool:
    """O.bodies.erase under mpirun: every process calls it with the same ids (as code every
    process runs alike does), and each erases its copy of the body, whichever process owns it
    (a clump frees its members, or erases them too with ``eraseClumpMembers``; a member leaves
    its clump, as in one process); False if it was erased already. A process that erased other
    bodies than the others stops every process at the next re-detection, naming the rule."""
    return domain(scene).erase(scene._cpp, int(id), bool(eraseClumpMembers))


def positions(scene=None):
    """Positions of every body (global ids) as an (N, 3) array, on every process (collective);
    in one process, O's positions."""
    if scene is None:
        scene = default_scene()
    d = domain(scene)
    return scene.positions().copy() if d is None else d.positions(scene._cpp)


def spheres(scene):
    """Centres and radii of the live spheres of ``scene`` (radius > 0), in id order, as
    (centres (N, 3), radii (N,)): once the scene is split, every process's own spheres on every
    process (collective; the centres unwrapped, as one process holds them); otherwise its rows'."""
    import numpy as np
    alive = np.asarray(scene._cpp.alive(), dtype=bool)
    radii = np.asarray(scene.radii())
    keep = alive & (radii > 0)
    centres = np.asarray(scene.positions())
    if not is_split(scene):
        return centres[keep], radii[keep]
    rows, ids = scene._domain.ownedBodies(scene._cpp)
    rows, ids = rows[keep[rows]], ids[keep[rows]]
    parts = gather_objects((ids, centres[rows], radii[rows]))
    ids = np.concatenate([p[0] for p in parts])
    order = np.argsort(ids, kind="stable")
    return np.concatenate([p[1] for p in parts])[order], np.concatenate([p[2] for p in parts])[order]


def gather_objects(value, root: int = -1) -> list:
    """Every process's ``value`` (any object pickle takes), a list in rank order, on process
    ``root`` (None elsewhere) or on every process when ``root`` is negative (collective); in one
    process, ``[value]``."""
    if not ACTIVE:
        return [value]
    import pickle
    import numpy as np
    from talus import _distributed
    raw = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    padded = raw + bytes(-len(raw) % 8)     # whole doubles: the bytes travel as they are
    table = np.concatenate([[float(len(raw))], np.frombuffer(padded, dtype=np.float64)]).reshape(-1, 1)
    whole = _distributed.gather_rows(table, root).reshape(-1)
    if root >= 0 and _rank != root:
        return None
    values, at = [], 0
    while at < len(whole):
        size = int(whole[at])
        values.append(pickle.loads(whole[at + 1:at + 1 + (size + 7) // 8].tobytes()[:size]))
        at += 1 + (size + 7) // 8
    return values


def rank() -> int:
    """This process's rank (0 in one process)."""
    return _rank


def smallest(value: float, scene=None) -> float:
    """The smallest of every process's ``value`` (critical time steps; collective under mpirun);
    in one process, ``value``."""
    if scene is None:
        scene = default_scene()
    d = domain(scene)
    return value if d is None else d.min(float(value))


def shared_seed(seed: int) -> int:
    """``seed``; when it is negative (draw at random) under mpirun, one random seed for every
    process (collective: each draws one, the smallest is taken), so that a random packing made
    without a seed (``makeCloud``, as many of Yade's examples do) is the same scene on every
    process, as the split needs; random from run to run as in one process."""
    if seed >= 0 or not ACTIVE or RANKS == 1:
        return seed
    import secrets
    from talus import _distributed
    return int(_distributed.smallest(float(secrets.randbelow(2 ** 31))))


def per_process(values: dict[str, float], scene=None) -> list[dict[str, float]]:
    """Every process's ``values`` (the same keys on every process), a dict per process, on every
    process (collective); in one process, ``[values]``."""
    if scene is None:
        scene = default_scene()
    d = domain(scene)
    if d is None:
        return [dict(values)]
    keys = sorted(values)
    table = [0.0] * (len(keys) * d.ranks)
    for k, key in enumerate(keys):
        table[d.rank * len(keys) + k] = float(values[key])
    table = d.sum(table)
    return [{key: table[r * len(keys) + k] for k, key in enumerate(keys)} for r in range(d.ranks)]


def traffic(scene=None) -> list[dict]:
    """What each process's halo sent (ghost updates at every step, migrations and ghost
    rebuilds at re-detections) and the seconds it spent in them and in the reductions, a dict
    per process, on every process (collective); empty in one process."""
    if scene is None:
        scene = default_scene()
    d = domain(scene)
    if d is None:
        return []
    return [{k: (v if k.endswith("seconds") else int(v)) for k, v in t.items()}
            for t in per_process(d.traffic(), scene)]


def reset_traffic(scene=None) -> None:
    """Zero what traffic() reports of the steps so far (to measure from a given step on)."""
    if scene is None:
        scene = default_scene()
    d = domain(scene)
    if d is not None:
        d.resetTraffic()


def balance(scene=None) -> dict:
    """The load measured at each re-detection, on every process (collective); empty in one process:
    ``processes`` (per process: its compute seconds, those CPU seconds not spent waiting in MPI
    calls; its spheres, ghosts and contacts now), ``rebalances``, ``imbalance`` (the slowest
    process's compute seconds over the mean, summed over the run), ``imbalance_before`` and
    ``imbalance_after`` (of the last rebalance), the fitted cost per body and per contact of a step
    (``per_body_seconds``, ``per_contact_seconds``), ``threshold`` and ``intervals`` (step,
    steps, imbalance, rebalanced), ``regions`` (each process's box: lower and upper corners) and
    ``ghost_distance``."""
    if scene is None:
        scene = default_scene()
    if not is_split(scene):
        return {}
    d = domain(scene)
    stats = d.balance()
    load = d.load(scene._cpp)
    mine = {"compute_seconds": stats.pop("compute_seconds"),
            **{k: load[k] for k in ("spheres", "ghosts", "contacts", "ghost_contacts")}}
    stats["processes"] = [{k: (v if k.endswith("seconds") else int(v)) for k, v in p.items()}
                          for p in per_process(mine, scene)]
    stats["imbalance"] = stats["slowest_seconds"] / stats["mean_seconds"] if stats["mean_seconds"] > 0 else 1.0
    stats["regions"] = [(list(lo), list(hi)) for lo, hi in load["regions"]]
    stats["ghost_distance"] = d.ghostDistance
    return stats


def is_collective(exc: BaseException) -> bool:
    """Whether every process raised ``exc`` alike (each may report it and stop on its own)."""
    if isinstance(exc, NotDistributed):
        return True
    from talus import _distributed
    if isinstance(exc, _distributed.CollectiveError):
        return True
    try:
        from talus import _distributed_checkpoint
    except ImportError:     # built without parallel HDF5
        return False
    return isinstance(exc, _distributed_checkpoint.CollectiveCheckpointError)


def stop_on_error(exc: BaseException, report) -> int:
    """Under mpirun, report ``exc`` (with ``report``) on process 0 when every process raised
    it, and return the exit status; any other error is reported by its process, which then ends
    the whole run (the others may be waiting for it in a collective)."""
    if is_collective(exc):
        if _rank == 0:
            report()
        return 1
    print(f"talus run: process {_rank} of {RANKS} failed; ending every process", file=sys.stderr)
    report()
    sys.stderr.flush()
    from talus import _distributed
    _distributed.abort(1)
    return 1
