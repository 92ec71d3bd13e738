"""The scene (Yade's Omega ``O``): materials, bodies, engines, time step and clock."""

from __future__ import annotations

import atexit
import builtins
import math
import numbers
import shutil
import tempfile
import time
import warnings
from typing import Iterable, Sequence

import numpy as np

from talus import _dem
from talus.dem import distributed
from talus.dem.geometry.appearance import Appearance
from talus.dem.core.reference import ReferenceStates
from talus.dem.core.body_container import BodyContainer
from talus.dem.core.cell import Cell
from talus.dem.analysis.energy import EnergyTracker
from talus.dem.step.engines import Engine, collapseDispatchers
from talus.dem.core.forces import ForceContainer
from talus.dem.core.interactions import InteractionContainer
from talus.dem.files.io import CheckpointMethods
from talus.dem.core.omega import OmegaMethods
from talus.dem.core.materials import Material, default_material
from talus.dem.core.scene_checks import check_engines, check_time_step
from talus.dem.core.scenes import add_scene, default_scene
from talus.dem.geometry.shape_registry import shape_kinds
from talus.dem.core.views import ArrayViews
from talus.dem.split import by_id

# Whether a contact overlapping beyond maxOverlapRatio stops the run in a new scene (see
# Scene.overlapStops). Yade has no such check: a run started as `yade -x` would start it sets
# False (yade.yade_run_defaults).
OVERLAP_STOPS = True

_TMP_FOLDER = None   # O.tmpFilename's folder, made at its first call


def _applyGeometrySettings(cpp, engines):
    """Each shape kind's contact settings of a scene from its engines (the block and particle
    contacts': their geometry functors' options)."""
    for kind in shape_kinds():
        if kind.configure is not None:
            kind.configure(cpp, engines)


class MaterialContainer:
    """``O.materials``: append returns the index; look up by index or label."""

    def __init__(self, scene: "Scene"):
        self._scene = scene
        self._materials: list[Material] = []

    def append(self, material: Material | Sequence[Material]):
        """Add a material (returns its index) or a list of them (returns their indices)."""
        if isinstance(material, (list, tuple)):
            return [self.append(m) for m in material]
        if not isinstance(material, Material):
            raise TypeError(f"O.materials.append takes a material (FrictMat, ViscElMat, ...), got {material!r}")
        if material._scene is not None:
            raise ValueError(f"{material!r} is already in a scene; create another material for this one")
        index = self._scene._cpp.addMaterial(material._cpp)
        # From now on the Python object edits the scene's copy (as in Yade, changes apply to
        # contacts created afterwards).
        material._bind(self._scene, self._scene._cpp.material(index))
        self._materials.append(material)
        return index

    def resolve(self, material) -> int:
        """Index of a material given as index, label or Material; -1 means the last one (created
        as Yade's default FrictMat if there is none)."""
        if isinstance(material, Material):
            for i, m in enumerate(self._materials):
                if m is material:
                    return i
            return self.append(material)
        if isinstance(material, str):
            for i, m in enumerate(self._materials):
                if m.label == material:
                    return i
            raise ValueError(f"no material labelled {material!r}")
        if material == -1:
            if not self._materials:
                self.append(default_material())
            return len(self._materials) - 1
        if not 0 <= material < len(self._materials):
            raise ValueError(f"unknown material index {material} (the scene has {len(self._materials)} materials)")
        return int(material)

    def __getitem__(self, i: int | str) -> Material:
        """By index (negative counts from the end) or by label (KeyError if none has it)."""
        if isinstance(i, str):
            for m in self._materials:
                if m.label == i:
                    return m
            raise KeyError(f"no material labelled {i!r} in O.materials")
        return self._materials[i]

    def __iter__(self):
        return iter(self._materials)

    def __len__(self) -> int:
        return len(self._materials)


def _labelled(engines):
    """The labelled objects of an engine list: the engines, their functors (an InteractionLoop's,
    a collider's bound functors), the parts of a combined engine and a ParallelEngine's slaves."""
    for e in engines:
        if isinstance(e, (list, tuple)):      # a group of a ParallelEngine's slaves
            yield from _labelled(e)
            continue
        if getattr(e, "label", ""):
            yield e
        bound = getattr(e, "boundDispatcher", None)
        yield from _labelled([*getattr(e, "geomFunctors", ()), *getattr(e, "physFunctors", ()),
                              *getattr(e, "lawFunctors", ()), *getattr(bound, "functors", ()),
                              *getattr(e, "comb", ()), *getattr(e, "slaves", ())])


class Scene(OmegaMethods, CheckpointMethods):
    """A simulation. ``talus.dem.O`` is the default one, as Yade's ``O``."""

    # The scene's split over processes under mpirun (talus.dem.distributed.domain), None in one
    # process: an attribute of the class, so that asking costs no AttributeError from __getattr__.
    _domain = None
    _reference_by_row = False   # under mpirun, a scene read in slabs: refPos/refOri of its slab only

    def __init__(self):
        self._cpp = _dem.Scene()
        add_scene(self)
        self.materials = MaterialContainer(self)
        self.bodies = BodyContainer(self)
        self.cell = Cell(self)
        self.energy = EnergyTracker(self)
        self.interactions = InteractionContainer(self)
        self._appearance = Appearance()
        self._reference = ReferenceStates()
        self.forces = ForceContainer(self)
        self.tags: dict[str, str] = {}          # Yade's O.tags: free-form labels of the run
        self._runLimitsMoved: bool | None = None   # a run is going on: whether a stop limit was set since
        self.stopAtIter = 0                     # a run stops when the step count reaches it (0: never)
        self.stopAtTime = 0.0                   # ... or when the time reaches it (0: never)
        self._engines: list[Engine] = []
        self._pending: list[Engine] | None = None   # engines set during a step (see engines)
        self._views = ArrayViews()           # arrays handed out by the exchange interface
        self._openRunPending = False         # O.run() without count and without wait (see run)
        self._created = time.monotonic()
        self._cpp.overlapStops = OVERLAP_STOPS
        self._overlapWarned = False

    def reset(self):
        """Forget everything: bodies, materials, engines, contacts, clock (Yade's O.reset)."""
        self.__init__()

    def tmpFilename(self) -> str:
        """A new file name in a folder that is removed when Python exits (Yade's O.tmpFilename)."""
        global _TMP_FOLDER
        if _TMP_FOLDER is None:
            _TMP_FOLDER = tempfile.mkdtemp(prefix="talus-")
            atexit.register(shutil.rmtree, _TMP_FOLDER, True)
        return tempfile.mktemp(dir=_TMP_FOLDER)

    def resetTime(self):
        """Set the step count and the time back to zero (Yade's O.resetTime)."""
        self._cpp.iter = 0
        self._cpp.time = 0.0

    @property
    def realtime(self) -> float:
        """Wall-clock seconds since the scene was created (Yade's O.realtime)."""
        return time.monotonic() - self._created

    @property
    def numThreads(self) -> int:
        """OpenMP threads the step uses (``talus run -j N``)."""
        return _dem.threadCount()

    dt = property(lambda s: s._cpp.dt, lambda s, v: s._set_dt(v), doc="time step (s)")
    time = property(lambda s: s._cpp.time, doc="simulated time (s)")
    iter = property(lambda s: s._cpp.iter, doc="completed steps")

    @property
    def periodic(self) -> bool:
        """Space is the periodic repetition of ``O.cell`` (spheres only)."""
        return self._cpp.periodic

    @periodic.setter
    def periodic(self, value: bool):
        self._cpp.setPeriodic(bool(value))

    @property
    def trackEnergy(self) -> bool:
        """Accumulate the energy terms of ``O.energy`` (gravity's work, damping, friction and
        dashpot dissipation) from now on; off by default (then it costs nothing)."""
        return _dem.track_energy(self._cpp)

    @trackEnergy.setter
    def trackEnergy(self, value: bool):
        _dem.set_track_energy(self._cpp, bool(value))

    @property
    def maxOverlapRatio(self) -> float:
        """A contact overlapping more than this fraction of its smaller radius stops the run with
        an error naming the two bodies and the stable time step (0 disables the check)."""
        return self._cpp.maxOverlapRatio

    @maxOverlapRatio.setter
    def maxOverlapRatio(self, value: float):
        if not value >= 0:
            raise ValueError(f"O.maxOverlapRatio must be >= 0, got {value}")
        self._cpp.maxOverlapRatio = float(value)

    @property
    def overlapStops(self) -> bool:
        """True (Talus's default): a contact overlapping beyond maxOverlapRatio stops the run with
        its error. False (Yade's behaviour, the default of `talus run`): the run goes on, with one
        warning giving the first such contact, and ``overlapSteps`` counts the steps that had one."""
        return self._cpp.overlapStops

    @overlapStops.setter
    def overlapStops(self, value: bool):
        self._cpp.overlapStops = bool(value)

    @property
    def overlapSteps(self) -> int:
        """Steps that had a contact overlapping beyond maxOverlapRatio while overlapStops was False."""
        return self._cpp.overlapSteps

    def _warn_of_overlaps(self):
        if self._cpp.overlapSteps and not self._overlapWarned:
            self._overlapWarned = True
            warnings.warn(f"{self._cpp.firstOverlap}; the run goes on, as in Yade (O.overlapStops = True "
                          "would stop it)", RuntimeWarning, stacklevel=3)

    @property
    def maxEnergyGrowth(self) -> float:
        """With O.trackEnergy, a total energy grown by more than this fraction of the energy that
        flowed (checked every 100 steps) stops the run with an error naming the fastest body and
        the stable time step. 0 (default) disables: energy put in by what the tracker does not see
        (a coupling's external forces, growing particles) would count as growth."""
        return self._cpp.maxEnergyGrowth

    @maxEnergyGrowth.setter
    def maxEnergyGrowth(self, value: float):
        if not (math.isfinite(value) and value >= 0):
            raise ValueError(f"O.maxEnergyGrowth must be a finite number >= 0, got {value}")
        self._cpp.maxEnergyGrowth = float(value)

    @property
    def timingEnabled(self) -> bool:
        """Time every engine (and its labelled stages) each step; see talus.dem.analysis.timing.stats()."""
        return self._cpp.timingEnabled

    @timingEnabled.setter
    def timingEnabled(self, value: bool):
        self._cpp.timingEnabled = bool(value)

    @property
    def fusedSteps(self) -> int:
        """Steps whose usual engines (ForceResetter, collider, InteractionLoop,
        NewtonIntegrator) ran as the shared stages of the step's scheduler, in parallel regions
        entered once for all of them (docs/dem.md, "The step"); every step of a scene with
        those engines, whatever the other engines, the laws, the timing or the size."""
        return self._cpp.fusedSteps

    @property
    def fusedOtherEnginesSeconds(self) -> float:
        """Wall seconds the serial stages (PyRunners, couplings, controllers...: the engines
        that declare no stage) took: the rest of the steps' time is the DEM's own."""
        return self._cpp.fusedOtherEnginesSeconds

    def _set_dt(self, value: float):
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"O.dt is a number of seconds, got {value!r}")
        # Zero is Yade's way to apply what acts on velocities (a cell's velGrad, a clump's
        # velocity to its members) without moving anything. A negative value is Yade's way to
        # hand the step back to the time stepper (the step itself is kept until it acts).
        if value < 0 and value > -float("inf"):
            self.dynDt = True
            return
        if not (value >= 0 and value < float("inf")):
            raise ValueError(f"O.dt must be zero or positive and finite, got {value}")
        self._cpp.dt = float(value)

    def _timeStepper(self):
        """The time stepper among the engines (None without one)."""
        steppers = [e for e in self.engines if isinstance(getattr(e, "_cpp", None), _dem.GlobalStiffnessTimeStepper)]
        if len(steppers) > 1:
            raise RuntimeError(f"Multiple ({len(steppers)}) TimeSteppers in the simulation?!")
        return steppers[0] if steppers else None

    @property
    def dynDt(self) -> bool:
        """The time stepper of the engines is active (Yade's O.dynDt); setting it switches the
        stepper on or off (a step set by hand is kept only while it is off). False without one;
        setting True without one is an error, as in Yade."""
        stepper = self._timeStepper()
        return stepper is not None and bool(stepper.active)

    @dynDt.setter
    def dynDt(self, value: bool):
        stepper = self._timeStepper()
        if stepper is None:
            if value:
                raise RuntimeError("No TimeStepper found in O.engines.")
            return
        stepper.active = bool(value)

    @property
    def engines(self) -> list[Engine]:
        """The engines; set during a step (from a PyRunner), the new list is what this gives at
        once, and it runs from the next step on (Yade's O._nextEngines)."""
        running = self._running()
        return list(running if self._pending is None else self._pending)

    @engines.setter
    def engines(self, engines: Sequence[Engine]):
        if isinstance(engines, (Engine, str)) or not isinstance(engines, Iterable):
            raise TypeError(f"O.engines takes a list of engines, got {engines!r}")
        engines = collapseDispatchers(list(engines))
        for e in engines:
            if not isinstance(e, Engine):
                raise TypeError(f"O.engines takes engines, got {e!r}")
        check_engines(engines)
        self._cpp.engines = [e._cpp for e in engines]     # the C++ scene defers them inside a step
        if self._cpp.subStep >= 0:
            self._pending = engines
        else:
            self._engines, self._pending = engines, None
        _applyGeometrySettings(self._cpp, engines)   # the geometry functors' settings of the scene
        # As in Yade, a labelled engine, functor or sub-engine becomes a name of Python's
        # builtins, which the script and every module see (and which stays after O.reset()).
        for labelled in _labelled(engines):
            setattr(builtins, labelled.label, labelled)

    def _running(self) -> list[Engine]:
        """The engines the current step runs, once the C++ scene took those set during a step."""
        if self._pending is not None and self._cpp.nextEngines is None:
            self._engines, self._pending = self._pending, None
        return self._engines

    @property
    def _currEngines(self) -> list[Engine]:
        """The engines the current step runs (Yade's O._currEngines)."""
        return list(self._running())

    @property
    def _nextEngines(self) -> list[Engine]:
        """Engines set during a step, waiting for the next one (Yade's O._nextEngines); empty if none."""
        self._running()
        return list(self._pending or [])

    @property
    def subStep(self) -> int:
        """Yade's O.subStep: -1 between steps, 0 while a whole step runs; with ``subStepping``
        the sub-step the next O.step() runs (-1 the step's start, k engine k, len(engines) its end)."""
        return self._cpp.subStep

    @property
    def subStepping(self) -> bool:
        """Yade's O.subStepping: each O.step() runs one sub-step (see subStep); turned off
        mid-step, the next O.step() finishes the step."""
        return self._cpp.subStepping

    @subStepping.setter
    def subStepping(self, value: bool):
        self._cpp.subStepping = bool(value)

    def typedEngine(self, name: str) -> Engine:
        """The first engine of the class ``name`` in O.engines (Yade's utils.typedEngine)."""
        engines = self.engines
        for e in engines:
            if type(e).__name__ == name:
                return e
        raise ValueError(f"typedEngine: no {name} in O.engines ({', '.join(type(e).__name__ for e in engines)})")

    def step(self):
        """Run one time step."""
        self._openRunPending = False
        by_id.agree(by_id.STEP)     # under mpirun: every process is here (see talus.dem.split.by_id)
        distributed.attach(self)    # under mpirun: the scene is split when its first step starts
        check_time_step(self)
        try:
            self._cpp.step()
        finally:
            self._warn_of_overlaps()

    @property
    def running(self) -> bool:
        """An open-ended run (``O.run()`` without a step count) was started without waiting
        and has not run yet: it runs at ``O.wait()``."""
        return self._openRunPending

    def run(self, nSteps: int = -1, wait: bool = False):
        """Run ``nSteps`` steps, or with no count until ``O.pause()`` (from a PyRunner),
        ``O.stopAtIter`` or ``O.stopAtTime``.

        Yade runs in the background unless ``wait``. Talus runs a counted run to its end before
        returning (what a Yade script sees after ``O.wait()``). An open-ended run without
        ``wait`` is kept for ``O.wait()``; a script that ends with it still pending stops
        there, as under ``yade -x``."""
        if nSteps != int(nSteps):
            raise ValueError(f"O.run: nSteps must be a whole number of steps, got {nSteps}")
        nSteps = int(nSteps)
        if nSteps < -1:
            raise ValueError(f"O.run: nSteps must be >= 0 (or -1: until O.pause()), got {nSteps}")
        self._openRunPending = False
        if nSteps == -1 and not wait:
            self._openRunPending = True
            return
        self._run(nSteps)

    def wait(self):
        """Run the open-ended run started by ``O.run()`` (Yade: wait for the background run)."""
        if self._openRunPending:
            self._openRunPending = False
            self._run(-1)

    def __setattr__(self, name, value):
        super().__setattr__(name, value)
        # Set by an engine during a run (Yade scripts do so from a PyRunner): the run pauses
        # after this step and goes on to the new limits, as Yade checks them at every step.
        if name in ("stopAtIter", "stopAtTime") and self.__dict__.get("_runLimitsMoved") is False:
            self._runLimitsMoved = True
            self._cpp.pause()

    def _run(self, nSteps: int):
        self._runLimitsMoved = False
        try:
            self._runSteps(nSteps)
        finally:
            self._runLimitsMoved = None

    def _runSteps(self, nSteps: int):
        stopIter = self.stopAtIter if self.stopAtIter > self.iter else None
        stopTime = self.stopAtTime if self.stopAtTime > self.time else None
        if nSteps < 0 and stopIter is None and stopTime is None and \
                not any(type(e).__name__ == "PyRunner" or getattr(e, "doneHook", None) for e in self.engines):
            raise ValueError("O.run() without a step count runs until O.pause(), but no PyRunner or doneHook could "
                             "call it (or set O.stopAtIter / O.stopAtTime)")
        remaining = nSteps
        while True:
            limits = [remaining] if remaining >= 0 else []
            if stopIter is not None:
                limits.append(stopIter - self.iter)
            if stopTime is not None:
                # Whole steps to reach stopAtTime at the current dt; again if a time stepper
                # changed dt meanwhile.
                limits.append(max(1, math.ceil((stopTime - self.time) / self.dt - 1e-9)))
            steps = min(limits) if limits else -1
            before = self.iter
            by_id.agree(by_id.STEP)     # under mpirun: every process is here (see talus.dem.split.by_id)
            distributed.attach(self)    # under mpirun: the scene is split when its first step starts
            check_time_step(self)
            try:
                self._cpp.run(steps)
            finally:
                self._warn_of_overlaps()
            done = self.iter - before
            remaining = remaining - done if remaining >= 0 else -1
            if self._runLimitsMoved:
                self._runLimitsMoved = False
                stopIter = self.stopAtIter if self.stopAtIter >= self.iter else None
                stopTime = self.stopAtTime if self.stopAtTime >= self.time else None
            elif steps < 0 or done < steps:                    # paused
                return
            if remaining == 0 or (stopIter is not None and self.iter >= stopIter) or \
                    (stopTime is not None and self.time >= stopTime):
                return

    def pause(self):
        """Stop the current run after this step (call it from a PyRunner, as in Yade); a
        pending open-ended run is dropped."""
        self._openRunPending = False
        self._cpp.pause()

    # Array views of all bodies (index = body id): the particle exchange interface in Python.
    # Views stay valid until bodies are appended: an append that moves the arrays' storage
    # while an earlier view is alive warns (talus.dem.core.views).
    def positions(self):
        return self._views.track(self._cpp.pos())

    def velocities(self):
        return self._views.track(self._cpp.vel())

    def angular_velocities(self):
        return self._views.track(self._cpp.angVel())

    def torques(self):
        return self._views.track(self._cpp.torque())

    def persistent_forces(self):
        """Forces that stay applied until changed (Yade's permanent forces), by body id."""
        return self._views.track(self._cpp.extForce())

    def persistent_torques(self):
        return self._views.track(self._cpp.extTorque())

    def add_hook(self, where: str, function, period: int = 1):
        """Call ``function()`` every ``period`` steps at a point of the step: "before_forces"
        (after ForceResetter: add this step's forces to ``forces()``), "after_forces" (before
        NewtonIntegrator) or "after_step". Returns the hook engine (set ``dead`` to stop it)."""
        from talus.dem.step.engines import ForceResetter, NewtonIntegrator, PyRunner
        anchors = {"before_forces": (ForceResetter, 1), "after_forces": (NewtonIntegrator, 0),
                   "after_step": (NewtonIntegrator, 1)}
        if where not in anchors:
            raise ValueError(f"add_hook: where must be one of {sorted(anchors)}, got {where!r}")
        anchor, offset = anchors[where]
        engines = self.engines
        positions = [k for k, e in enumerate(engines) if isinstance(e, anchor)]
        if not positions:
            raise ValueError(f"add_hook: the engine list has no {anchor.__name__}")
        hook = PyRunner(function, iterPeriod=period, initRun=True)
        engines.insert(positions[0] + offset, hook)
        self.engines = engines
        return hook

    def radii(self):
        return self._views.track(self._cpp.radius())

    def sphere_ids(self) -> np.ndarray:
        """Ids of the live spheres (the particles couplings act on), ascending."""
        return _dem.live_ids(self._cpp, "Sphere")

    def masses(self):
        return self._views.track(self._cpp.mass())

    # The bodies' heat (Yade's ThermalState: temp, Cp, k, alpha), writable, NaN where not given:
    # what a heat engine and any other component read and change (talus.dem.core.heat).
    def temperatures(self):
        return self._views.track(self._cpp.temperature())

    def heat_capacities(self):
        return self._views.track(self._cpp.heatCapacity())

    def conductivities(self):
        return self._views.track(self._cpp.conductivity())

    def thermal_expansions(self):
        return self._views.track(self._cpp.thermalExpansion())

    def contacts(self) -> list[dict]:
        """A copy of the real contacts (ids, geometry, stiffness, forces), for inspection."""
        return self._cpp.contacts()


def contactTimeStep(scene: Scene | None = None) -> float:
    """Critical step of the stiffest current contact alone, 2 sqrt(m / kn) (under mpirun, the
    whole scene's: collective)."""
    scene = scene or default_scene()
    return distributed.smallest(scene._cpp.contactTimeStep(), scene)


def SpherePWaveTimeStep(radius: float, density: float, young: float) -> float:
    """The P-wave critical time step of one sphere, r / sqrt(E / rho) (Yade's utils)."""
    return radius / math.sqrt(young / density)


def PWaveTimeStep(scene: Scene | None = None) -> float:
    """Yade's P-wave critical step estimate: min over spheres of r sqrt(density / young) (under
    mpirun, the whole scene's: collective)."""
    scene = scene or default_scene()
    value = distributed.smallest(scene._cpp.pWaveTimeStep(), scene)
    if value == float("inf"):
        raise ValueError("PWaveTimeStep: the scene has no spheres")
    return value
