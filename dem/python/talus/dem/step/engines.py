"""Engines of a time step, with Yade's names and parameters.

A Yade engine list ports as it is::

    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                        [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack()]),
        NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2),
        PyRunner(command="checkUnbalanced()", iterPeriod=100),
    ]

Bounding-volume (Bo1) and geometry (Ig2) functors are accepted for compatibility: Talus picks
the geometry from the shapes. Physics (Ip2) and law (Law2) functors choose the contact model;
each Law2 needs its Ip2 in the list, as in Yade.
"""

from __future__ import annotations

import functools
import inspect
import sys
from typing import Callable, Sequence

import numpy as np

from talus import _dem
from talus.dem.base.linalg import Vector3
from talus.dem.core.masks import group_mask
from talus.dem.core.scenes import default_scene


class Functor:
    """A Yade functor named in an engine's functor list. Functors with parameters list them in
    ``_parameters``; only those given (not None) are stored and passed on."""

    _parameters: tuple = ()

    def __init__(self, label: str = "", **params):
        self.label = label
        unknown = set(params) - set(self._parameters)
        if unknown:
            raise TypeError(f"{type(self).__name__} has no parameter(s) {', '.join(sorted(unknown))}"
                            + (f"; known: {', '.join(self._parameters)}" if self._parameters else ""))
        for name in self._parameters:
            setattr(self, name, params.get(name))

    def __setattr__(self, name, value):
        super().__setattr__(name, value)
        # A parameter set after the InteractionLoop was made (Yade scripts set them on labelled
        # functors) reaches the laws that took the functor's parameters.
        if name in self._parameters and value is not None and not isinstance(getattr(type(self), name, None), property):
            for law in self.__dict__.get("_configuredLaws", ()):
                law._set(name, value)

    def _io_params(self) -> dict:
        """The parameters that were given, to rebuild the functor (checkpoints)."""
        return {name: getattr(self, name) for name in self._parameters if getattr(self, name) is not None}

    def __repr__(self):
        args = ", ".join(f"{k}={v!r}" for k, v in self._io_params().items())
        return f"{type(self).__name__}({args})"


class MatchMaker:
    """Yade's MatchMaker: a contact parameter per pair of materials. ``matches``: (id1, id2,
    value) items for pairs of material ids (either order); any other pair by ``algo``: 'val'
    (``val``), 'zero', or from the two materials' own values 'avg' (Yade's default), 'min',
    'max', 'harmAvg'. Where a MatchMaker is accepted a number is too (one value for all pairs)."""

    _FALLBACKS = {
        "val": None, "zero": None,
        "avg": lambda a, b: (a + b) / 2.0, "min": min, "max": max,
        "harmAvg": lambda a, b: 2 * a * b / (a + b),
    }

    def __init__(self, algo: str = "avg", val: float = float("nan"), matches=()):
        if algo not in self._FALLBACKS:
            raise ValueError(f"MatchMaker: algo {algo!r} not recognized (possible values: {', '.join(self._FALLBACKS)})")
        self.algo, self.val = algo, float(val)
        self._matches = {}
        for item in matches:
            if len(item) != 3:
                raise ValueError(f"MatchMaker: each of matches is (id1, id2, value), got {item!r}")
            id1, id2, value = int(item[0]), int(item[1]), float(item[2])
            self._matches[(min(id1, id2), max(id1, id2))] = value

    @property
    def matches(self) -> list:
        """The (id1, id2, value) items, as Yade's Vector3 list."""
        return [Vector3(a, b, v) for (a, b), v in self._matches.items()]

    def computeFallback(self, val1: float, val2: float) -> float:
        """The value of a pair without a match, from the materials' values by ``algo``."""
        if self.algo == "val":
            return self.val
        if self.algo == "zero":
            return 0.0
        return float(self._FALLBACKS[self.algo](float(val1), float(val2)))

    def __call__(self, id1: int, id2: int, val1: float = float("nan"), val2: float = float("nan")) -> float:
        key = (min(int(id1), int(id2)), max(int(id1), int(id2)))
        if key in self._matches:
            return self._matches[key]
        if self.algo not in ("val", "zero") and (val1 != val1 or val2 != val2):
            raise ValueError(f"MatchMaker: no match for ({id1},{id2}), and values required for algo computation "
                             f"'{self.algo}' not specified.")
        return self.computeFallback(val1, val2)

    def pairTable(self) -> tuple[list, float | None]:
        """The matches as (id1, id2, value) and the value of any other pair, for a functor that
        does not pass the materials' values (None: such a pair is an error)."""
        fallback = self.val if self.algo == "val" else 0.0 if self.algo == "zero" else None
        return [(a, b, v) for (a, b), v in self._matches.items()], fallback

    def __float__(self):
        if self._matches or self.algo not in ("val", "zero"):
            raise TypeError(f"{self!r} gives a value per pair of materials; this parameter takes one value for all "
                            "pairs (a number, or MatchMaker(algo='val', val=x))")
        return self.val if self.algo == "val" else 0.0

    def __repr__(self):
        return f"MatchMaker(algo={self.algo!r}, val={self.val!r}, matches={list(self._matches.items())!r})"


def finite_vector(value, what: str) -> list[float]:
    """`value` as 3 floats; a ValueError naming `what` if it is not 3 finite numbers."""
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{what} must be 3 finite numbers, got {value!r}")
    return v.tolist()


def _number(functor: Functor, name: str, value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{type(functor).__name__}.{name} must be a number (or MatchMaker), got {value!r}") from None


def _functor(name: str, doc: str) -> type:
    return type(name, (Functor,), {"__doc__": doc})


def _neutral_only(name: str, doc: str, parameter: str, neutral, meaning: str) -> type:
    """A functor class taking Yade's `parameter` only at the values that change nothing
    (``neutral(value)``), and naming it with what it would do (`meaning`) otherwise."""
    def __init__(self, label: str = "", **params):
        value = params.get(parameter)
        if value is not None and not (isinstance(value, (int, float)) and not isinstance(value, bool) and neutral(value)):
            raise ValueError(f"{name}.{parameter} = {value!r}: {meaning} is not implemented in Talus; "
                             "leave it at Yade's default")
        Functor.__init__(self, label, **params)

    return type(name, (Functor,), {"__doc__": doc, "_parameters": (parameter,), "__init__": __init__})


Bo1_Sphere_Aabb = _neutral_only(
    "Bo1_Sphere_Aabb", "Bounding box of spheres (accepted; Talus bounds shapes itself). ``aabbEnlargeFactor``: "
    "only the values that enlarge nothing (negative, Yade's default, or 1).",
    "aabbEnlargeFactor", lambda f: f <= 0 or f == 1, "enlarging the bounding boxes (contacts at a distance)")
Bo1_Wall_Aabb = _functor("Bo1_Wall_Aabb", "Bounding box of walls (accepted; Talus bounds shapes itself).")
Bo1_Facet_Aabb = _functor("Bo1_Facet_Aabb", "Bounding box of facets (accepted; Talus bounds shapes itself).")
Bo1_Box_Aabb = _functor("Bo1_Box_Aabb", "Bounding box of boxes (accepted; Talus bounds shapes itself).")
Ig2_Box_Sphere_ScGeom = _functor("Ig2_Box_Sphere_ScGeom", "Box-sphere contact geometry (face, edge, corner).")
Ig2_Sphere_Sphere_ScGeom = _neutral_only(
    "Ig2_Sphere_Sphere_ScGeom", "Sphere-sphere contact geometry. ``interactionDetectionFactor``: only 1, Yade's default.",
    "interactionDetectionFactor", lambda f: f == 1, "detecting contacts at a distance")
Ig2_Facet_Sphere_ScGeom = _functor("Ig2_Facet_Sphere_ScGeom", "Facet-sphere contact geometry (face, edge, vertex).")
Ig2_Wall_Sphere_ScGeom = _functor("Ig2_Wall_Sphere_ScGeom", "Wall-sphere contact geometry.")
Ig2_Sphere_Sphere_ScGeom6D = _neutral_only(
    "Ig2_Sphere_Sphere_ScGeom6D", "Sphere-sphere contact geometry with relative rotations (the law asks for "
    "them). ``interactionDetectionFactor``: only 1, Yade's default.",
    "interactionDetectionFactor", lambda f: f == 1, "detecting contacts at a distance")
Ig2_Wall_Sphere_ScGeom6D = _functor("Ig2_Wall_Sphere_ScGeom6D", "Wall-sphere contact geometry with relative rotations.")
Ig2_Box_Sphere_ScGeom6D = _functor("Ig2_Box_Sphere_ScGeom6D", "Box-sphere contact geometry with relative rotations.")
Ip2_FrictMat_FrictMat_FrictPhys = _functor(
    "Ip2_FrictMat_FrictMat_FrictPhys", "Stiffness and friction of linear contacts from FrictMat parameters.")


class Ip2_ViscElMat_ViscElMat_ViscElPhys(Functor):
    """Spring-dashpot parameters from ViscElMat (tc, en, et; kn, cn, ks, cs; or young, poisson
    with en or cn, cs). ``tc``, ``en``, ``et``, ``frictAngle``: per pair of materials (a
    MatchMaker, or a number for all pairs) instead of the materials' means (frictAngle: their
    smaller angle); tc, en, et given together select the tc form for every pair."""
    _parameters = ("tc", "en", "et", "frictAngle")


class Ip2_FrictMat_FrictMat_MindlinPhys(Functor):
    """Hertz-Mindlin physics from FrictMat (young, poisson, frictionAngle): kno = 4/3 E* sqrt(R*),
    kso = 8 G* sqrt(R*). Damping from the restitution coefficients ``en``, ``es`` (Thornton's
    fit, as Yade; one alone stands for both) or directly the damping ratios ``betan``,
    ``betas``; none: elastic. Each a number or a MatchMaker (per pair of materials; a pair
    without a match takes ``val`` with algo 'val' and is an error with the averaging algos, as
    in Yade, whose functor passes no material values). Yade's krot, ktwist, eta and gamma are
    not supported."""
    _parameters = ("en", "es", "betan", "betas")


class LawFunctor(Functor):
    """Base of the contact laws (Yade's LawFunctor): the C++ law registered as ``_cpp_name``,
    its parameters set from the functor's."""
    _cpp_name = ""

    def __init__(self, label: str = "", **params):
        super().__init__(label, **params)
        self._cpp = _dem.make_contact_law(self._cpp_name)
        for name, value in self._io_params().items():
            self._set(name, value)

    def _set(self, name: str, value):
        _dem.law_set_parameter(self._cpp, name, _number(self, name, value))

    def _configure(self, phys: Functor):
        """Take the parameters of the physics functor that goes with this law, now and when they
        are set later."""
        for name, value in phys._io_params().items():
            self._set(name, value)
        phys.__dict__.setdefault("_configuredLaws", []).append(self)


class Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(Functor):
    """Cohesive-frictional physics from CohFrictMat: linear stiffnesses as FrictPhys, rolling and
    twisting stiffnesses and limits. ``setCohesionOnNewContacts``: new contacts between cohesive
    materials are bonded; ``setCohesionNow``: every existing contact is bonded at the next step
    (then the flag goes back to False, as in Yade)."""
    _parameters = ("setCohesionNow", "setCohesionOnNewContacts")

    def __init__(self, label: str = "", **params):
        self._laws = []
        self._now = None
        super().__init__(label, **params)

    @property
    def setCohesionNow(self):
        """Reads back False once the law has bonded the contacts (as in Yade)."""
        if self._laws:
            return bool(_dem.law_parameter(self._laws[0]._cpp, "setCohesionNow"))
        return self._now

    @setCohesionNow.setter
    def setCohesionNow(self, value):   # Yade scripts set it on the functor mid-run
        self._now = value
        for law in self._laws:
            law._set("setCohesionNow", bool(value))


class Law2_ScGeom6D_CohFrictPhys_CohesionMoment(LawFunctor):
    """Cohesive bonds (normal and shear strengths, fragile or plastic), Coulomb friction, and
    with momentRotationLaw rolling and twisting moments (``useIncrementalForm``: from
    incremental rotations, needed for exact plastic limits; ``always_use_moment_law``: keep
    them after the bond broke)."""
    _cpp_name = "Law2_ScGeom6D_CohFrictPhys_CohesionMoment"
    _parameters = ("useIncrementalForm", "always_use_moment_law")

    def _configure(self, phys: Functor):
        super()._configure(phys)
        phys._laws.append(self)

    # Yade's elastic energies of the springs of O's cohesive-frictional contacts (those between
    # two CohFrictMat bodies), each a sum of |F|^2 / (2 k) over the real contacts.
    def normElastEnergy(self) -> float:
        return self._elasticEnergy("normalForce", "kn")

    def shearElastEnergy(self) -> float:
        return self._elasticEnergy("shearForce", "ks")

    def bendingElastEnergy(self) -> float:
        return self._elasticEnergy("moment_bending", "kr")

    def twistElastEnergy(self) -> float:
        return self._elasticEnergy("moment_twist", "ktw")

    def _elasticEnergy(self, force: str, stiffness: str) -> float:
        O = default_scene()
        from talus.dem.core.materials import CohFrictMat
        cohesive = np.array([isinstance(m, CohFrictMat) for m in O.materials], dtype=bool)
        material = O._cpp.materialIds()
        energy = 0.0
        for contact, extra in zip(O._cpp.contacts(True), _dem.contact_extra(O._cpp)):
            if cohesive[material[contact["id1"]]] and cohesive[material[contact["id2"]]]:
                values = {**contact, **extra}
                energy += 0.5 * float(np.dot(values[force], values[force])) / values[stiffness]
        return energy


class Law2_ScGeom_MindlinPhys_Mindlin(LawFunctor):
    """Hertz normal force kno u^1.5, incremental Mindlin shear stiffness kso u^0.5 with Coulomb
    friction, viscous damping from Ip2_FrictMat_FrictMat_MindlinPhys (never attractive).
    ``neverErase`` only at Yade's default False: a contact ends when its bodies part."""
    _cpp_name = "Law2_ScGeom_MindlinPhys_Mindlin"
    _parameters = ("neverErase",)

    def _set(self, name: str, value):
        if isinstance(value, MatchMaker):   # a value per pair of materials
            _dem.law_set_pair_parameter(self._cpp, name, *value.pairTable())
        elif name != "neverErase":
            super()._set(name, value)
        elif value:
            raise ValueError("Law2_ScGeom_MindlinPhys_Mindlin: neverErase=True is not supported "
                             "(Talus ends a contact when its bodies part)")


class Law2_ScGeom_FrictPhys_CundallStrack(LawFunctor):
    """Linear elastic normal force and incremental shear force with Coulomb friction."""
    _cpp_name = "Law2_ScGeom_FrictPhys_CundallStrack"


class Law2_ScGeom_ViscElPhys_Basic(LawFunctor):
    """Linear spring-dashpot normal and shear forces (never attractive) with Coulomb friction,
    and rolling resistance for materials with ``mR`` > 0."""
    _cpp_name = "Law2_ScGeom_ViscElPhys_Basic"

    def _configure(self, phys: Functor):
        for name, value in phys._io_params().items():
            if not isinstance(value, MatchMaker):
                value = MatchMaker(algo="val", val=_number(phys, name, value))
            _dem.law_set_pair_parameter(self._cpp, name, *value.pairTable())


class TimingDeltas:
    """Time per labelled stage inside one engine (Yade's TimingDeltas)."""

    def __init__(self, cpp_engine):
        self._cpp = cpp_engine

    @property
    def data(self) -> list[tuple[str, int, int]]:
        return list(self._cpp.timingDeltasData)

    def reset(self):
        self._cpp.resetTimingDeltas()


class Engine:
    """Base of the engines: holds the C++ engine and forwards its parameters. Every engine takes
    Yade's ``dead=`` (a dead engine is skipped by the step, and by a CombinedKinematicEngine)."""

    _cpp: object

    def __init_subclass__(cls, **kwargs):
        # Yade's ``dead`` is an attribute of every engine: each constructor that does not name it
        # takes it as a keyword (its signature, which checkpoints read, stays the constructor's).
        super().__init_subclass__(**kwargs)
        init = cls.__dict__.get("__init__")
        if init is None or "dead" in inspect.signature(init).parameters:
            return

        @functools.wraps(init)
        def __init__(self, *args, dead: bool = False, **kw):
            init(self, *args, **kw)
            if dead:
                self.dead = True
        cls.__init__ = __init__

    @property
    def label(self) -> str:
        return self._cpp.label

    @label.setter
    def label(self, value: str):
        self._cpp.label = value

    @property
    def dead(self) -> bool:
        return self._cpp.dead

    @dead.setter
    def dead(self, value: bool):
        self._cpp.dead = value

    # Timing (O.timingEnabled), as Yade's Engine.execTime / execCount / timingDeltas.
    @property
    def execTime(self) -> int:
        """Nanoseconds spent in this engine while O.timingEnabled was on."""
        return self._cpp.execTime

    @execTime.setter
    def execTime(self, value: int):
        self._cpp.execTime = int(value)

    @property
    def execCount(self) -> int:
        """Timed calls of this engine."""
        return self._cpp.execCount

    @execCount.setter
    def execCount(self, value: int):
        self._cpp.execCount = int(value)

    @property
    def timingDeltas(self) -> "TimingDeltas":
        """The engine's labelled stages: ``.data`` is [(label, nanoseconds, count), ...]."""
        return TimingDeltas(self._cpp)

    def __repr__(self):
        return f"{type(self).__name__}(label={self.label!r})"


class ForceResetter(Engine):
    """Sets every body's force and torque to its persistent external force and torque."""

    def __init__(self, label: str = ""):
        self._cpp = _dem.ForceResetter()
        self.label = label


class ParallelEngine(Engine):
    """Yade's ParallelEngine: ``slaves``, each an engine or a list of engines run in order. Yade
    runs the slaves side by side; Talus runs them one after the other in the order given (they
    must not touch the same data in Yade either, so the order cannot change the result)."""

    def __init__(self, slaves: Sequence = (), label: str = ""):
        self._cpp = _dem.ParallelEngine()
        self.label = label
        self.slaves = slaves

    @property
    def slaves(self) -> list:
        return [list(group) if isinstance(group, list) else group for group in self._slaves]

    @slaves.setter
    def slaves(self, slaves: Sequence):
        groups = []
        for slave in slaves:
            group = list(slave) if isinstance(slave, (list, tuple)) else [slave]
            for engine in group:
                if not isinstance(engine, Engine):
                    raise TypeError(f"ParallelEngine.slaves takes engines or lists of engines, got {engine!r}")
            groups.append(group if isinstance(slave, (list, tuple)) else slave)
        self._slaves = groups
        self._cpp.slaves = [[e._cpp for e in (g if isinstance(g, list) else [g])] for g in groups]


class Dispatcher:
    """Yade's functor dispatchers (``BoundDispatcher``, ``IGeomDispatcher``, ``IPhysDispatcher``,
    ``LawDispatcher``): a list of functors, as engines hold them (``loop.lawDispatcher.functors``)
    and as old scripts list them in O.engines (three in a row stand for one InteractionLoop)."""

    _arity = 2   # a functor serves a pair of classes (Bo1 functors: one)
    _prefix: str | tuple = ""  # the functors' kind, from Yade's names: Bo1_, Ig2_, Ip2_, Law2_

    def __init__(self, functors: Sequence[Functor] = (), label: str = ""):
        # As in Yade: a functor of another kind is refused, and one of the same class as an
        # earlier one replaces it (each pair of classes has one functor).
        kept: dict[type, Functor] = {}
        for functor in functors:
            if not type(functor).__name__.startswith(self._prefix):
                raise TypeError(f"{type(self).__name__} takes {'/'.join(self._prefix) if isinstance(self._prefix, tuple) else self._prefix}* functors, got "
                                f"{type(functor).__name__}")
            kept.pop(type(functor), None)
            kept[type(functor)] = functor
        self.functors = list(kept.values())
        self.label = label

    def __repr__(self):
        return f"{type(self).__name__}({self.functors!r})"

    def dispMatrix(self, names: bool = True) -> dict:
        """Which functor serves which classes, as Yade's ``dispMatrix()``: {('Sphere', 'Facet'):
        'Ig2_Facet_Sphere_ScGeom', ...} (both orders of a pair), {('ScGeom', 'FrictPhys'):
        'Law2_...'}, {'Sphere': 'Bo1_Sphere_Aabb'} for bounds. The classes are read from the
        functors' names; Yade's class indices (``names=False``) do not exist in Talus."""
        if not names:
            raise ValueError(f"{type(self).__name__}.dispMatrix(names=False): Yade's class indices do not exist "
                             "in Talus; use dispMatrix() (class names)")
        matrix = {}
        for functor in self.functors:
            name = type(functor).__name__
            classes = name.split("_")[1:1 + self._arity]
            if self._arity == 1:
                matrix[classes[0]] = name
                continue
            matrix[tuple(classes)] = name
            if isinstance(self, IGeomDispatcher | IPhysDispatcher):   # Yade dispatches these symmetrically
                matrix[tuple(reversed(classes))] = name
        return matrix


class BoundDispatcher(Dispatcher, Engine):
    """The bound functors of a collider; also an engine of O.engines by itself, as Yade allows.
    There it does nothing: Talus's collider bounds the bodies itself (``b.bound`` reads its
    bounds)."""
    _arity = 1
    _prefix = ("Bo1_", "Potential")   # PotentialBlock2AABB, PotentialParticle2AABB are Yade's too

    def __init__(self, functors: Sequence[Functor] = (), label: str = ""):
        self._cpp = _dem.CallbackEngine()    # without a callback: a step through it does nothing
        super().__init__(functors, label)


class IGeomDispatcher(Dispatcher):
    _prefix = "Ig2_"


class IPhysDispatcher(Dispatcher):
    _prefix = "Ip2_"


class LawDispatcher(Dispatcher):
    _prefix = "Law2_"


def _functors(given) -> list:
    return list(given.functors) if isinstance(given, Dispatcher) else list(given)


def _verlet_dist(value) -> float:
    """The collider's skin: a NaN one would size the contact grid from NaN bounds."""
    try:
        skin = float(value)
    except (TypeError, ValueError):
        skin = float("nan")
    if skin != skin or isinstance(value, (str, bytes)):
        raise ValueError(f"InsertionSortCollider.verletDist must be a number (a length, or negative: that "
                         f"fraction of the smallest radius), got {value!r}")
    return skin


class InsertionSortCollider(Engine):
    """Contact detection with a Verlet skin ``verletDist`` (negative: a fraction of the smallest
    radius, Yade's default -0.5). Implemented with linked cells; Yade's name is kept.

    ``allowBiggerThanPeriod``: in a periodic cell, a facet or box spanning more than half the
    cell (a floor across it) meets the spheres where they are along that axis, as in Yade;
    without it such a body is an error.

    Yade's settings of its sweep-and-prune (``nBins``,
    ``sweepLength``, ``binCoeff``, ``targetInterv``, ``updatingDispFactor``, ``sortThenCollide``,
    ``keepListsShort``, ``doSort``, ``ompThreads``, ``fastestBodyMaxDist``) tune its speed, not the
    contacts it finds: they are accepted and kept, and Talus's linked cells do not need them."""

    _SPEED_SETTINGS = ("nBins", "sweepLength", "binCoeff", "targetInterv",
                       "updatingDispFactor", "sortThenCollide", "keepListsShort", "doSort", "ompThreads",
                       "fastestBodyMaxDist", "minSweepDistFactor", "periodic", "dumpBounds")

    def __init__(self, boundDispatcher=(), verletDist: float = -0.5, label: str = "",
                 allowBiggerThanPeriod: bool = False, avoidSelfInteractionMask: int = 0, **settings):
        unknown = set(settings) - set(self._SPEED_SETTINGS)
        if unknown:
            raise TypeError(f"InsertionSortCollider has no parameter(s) {', '.join(sorted(unknown))}")
        self._cpp = _dem.Collider()
        self.verletDist = verletDist
        self._cpp.allowBiggerThanPeriod = bool(allowBiggerThanPeriod)
        self.avoidSelfInteractionMask = avoidSelfInteractionMask
        self.label = label
        self.boundDispatcher = BoundDispatcher(_functors(boundDispatcher))
        self.settings = settings

    verletDist = property(lambda self: self._cpp.verletDist,
                          lambda self, v: setattr(self._cpp, "verletDist", _verlet_dist(v)))
    allowBiggerThanPeriod = property(lambda self: self._cpp.allowBiggerThanPeriod,
                                     lambda self, v: setattr(self._cpp, "allowBiggerThanPeriod", bool(v)))
    avoidSelfInteractionMask = property(
        lambda self: self._cpp.avoidSelfInteractionMask,
        lambda self, v: setattr(self._cpp, "avoidSelfInteractionMask",
                                group_mask(v, "InsertionSortCollider.avoidSelfInteractionMask")),
        doc="bodies of one mask sharing a bit with it never touch each other (Yade's; 0: none)")
    rebuilds = property(lambda self: self._cpp.rebuilds, doc="number of re-detections so far")


class FlatGridCollider(InsertionSortCollider):
    """Yade's FlatGridCollider: contact detection for spheres on a regular grid of cells of size
    ``step`` spanning ``aabbMin``..``aabbMax`` (spheres outside it fall into its border cells), with
    skin ``verletDist`` (Yade's default 0: re-detection at every step). The grid only tunes Yade's
    search: the contacts found are those of any exact detection with the same skin, so Talus
    runs its own collider with that skin; ``step`` and the box are checked as Yade checks them."""

    def __init__(self, step: float = 0.0, aabbMin=(0.0, 0.0, 0.0), aabbMax=(0.0, 0.0, 0.0),
                 verletDist: float = 0.0, label: str = ""):
        if not step > 0:
            raise ValueError(f"FlatGridCollider: step must be positive, got {step}")
        size = np.asarray(aabbMax, dtype=float) - np.asarray(aabbMin, dtype=float)
        if size.shape != (3,) or not np.all(size > 0):
            raise ValueError(f"FlatGridCollider: aabbMin {aabbMin} and aabbMax {aabbMax} must give a positive volume")
        if verletDist < 0:
            raise ValueError(f"FlatGridCollider: verletDist must be >= 0 (an absolute length), got {verletDist}")
        super().__init__(verletDist=verletDist, label=label)
        self.step, self.aabbMin, self.aabbMax = float(step), Vector3(aabbMin), Vector3(aabbMax)


class InteractionLoop(Engine):
    """Contact geometry, physics and forces of every contact."""

    def __init__(self, geomFunctors: Sequence[Functor] = (), physFunctors: Sequence[Functor] = (),
                 lawFunctors: Sequence[Functor] = (), label: str = ""):
        geomFunctors, physFunctors, lawFunctors = (_functors(f) for f in (geomFunctors, physFunctors, lawFunctors))
        laws = [f for f in lawFunctors if isinstance(f, LawFunctor)]
        unknown = [f for f in lawFunctors if not isinstance(f, LawFunctor)]
        if unknown:
            raise TypeError(f"InteractionLoop: not contact laws: {unknown}")
        if not laws:
            raise ValueError("InteractionLoop needs at least one Law2 functor, e.g. "
                             "Law2_ScGeom_FrictPhys_CundallStrack()")
        phys = {type(f).__name__: f for f in physFunctors}
        for law in laws:
            if law._cpp.physicsName not in phys:
                raise ValueError(f"InteractionLoop: {type(law).__name__} needs "
                                 f"{law._cpp.physicsName}() in the physics functors")
            law._configure(phys[law._cpp.physicsName])
            if hasattr(law, "_configureGeometry"):   # laws with geometry parameters (Ig2_PB_PB_ScGeom)
                law._configureGeometry(geomFunctors)
        self._cpp = _dem.InteractionLoop()
        self._cpp.laws = [law._cpp for law in laws]
        self.geomFunctors, self.physFunctors, self.lawFunctors = list(geomFunctors), list(physFunctors), laws
        self.label = label

    @property
    def callbacks(self) -> list:
        """Yade's InteractionLoop.callbacks (e.g. ``[SumIntrForcesCb()]``), told of every step's
        contacts; an InteractionLoop with callbacks is not run fused with the other engines."""
        return list(getattr(self, "_callbacks", []))

    @callbacks.setter
    def callbacks(self, callbacks):
        callbacks = list(callbacks)
        for c in callbacks:
            if not isinstance(getattr(c, "_cpp", None), _dem.IntrCallback):
                raise TypeError(f"InteractionLoop.callbacks takes interaction callbacks (SumIntrForcesCb()), got {c!r}")
        _dem.set_loop_callbacks(self._cpp, [c._cpp for c in callbacks])
        self._callbacks = callbacks

    # Yade's names for the three functor lists.
    geomDispatcher = property(lambda self: IGeomDispatcher(self.geomFunctors))
    physDispatcher = property(lambda self: IPhysDispatcher(self.physFunctors))
    lawDispatcher = property(lambda self: LawDispatcher(self.lawFunctors))


class NewtonIntegrator(Engine):
    """Leap-frog integration with ``gravity`` and Cundall's non-viscous ``damping``.

    Aspherical bodies (clumps, boxes) always rotate by Yade's exact scheme
    (``exactAsphericalRot=True``, Yade's default); ``kinSplit``: O.energy gives the kinetic
    energy as its translational and rotational parts (``kinTrans``, ``kinRot``), as Yade's;
    ``dampGravity=False``: the damping acts on the other forces only, gravity is added after it
    (Yade's); ``warnNoForceReset`` is accepted and changes nothing. Bodies with
    ``state.isDamped = False`` are not damped."""

    def __init__(self, gravity=(0.0, 0.0, 0.0), damping: float = 0.2, label: str = "",
                 exactAsphericalRot: bool = True, kinSplit: bool = False, warnNoForceReset: bool = True, mask: int = -1,
                 dampGravity: bool = True):
        if not exactAsphericalRot:
            raise ValueError("NewtonIntegrator: exactAsphericalRot=False (Yade's approximate rotation of aspherical "
                             "bodies) is not implemented; Talus always integrates their rotation exactly")
        self.exactAsphericalRot, self.kinSplit, self.warnNoForceReset = True, bool(kinSplit), bool(warnNoForceReset)
        self._cpp = _dem.NewtonIntegrator()
        self.gravity = gravity
        self.damping = damping
        self.dampGravity = dampGravity
        self.mask = mask
        self.label = label

    gravity = property(lambda self: Vector3(self._cpp.gravity),
                       lambda self, g: setattr(self._cpp, "gravity", finite_vector(g, "NewtonIntegrator.gravity")))

    @property
    def damping(self) -> float:
        return self._cpp.damping

    @damping.setter
    def damping(self, d: float):
        # Cundall's damping scales a force by 1 -+ damping: outside [0, 1] it adds energy (< 0)
        # or turns forces against themselves (> 1). Yade accepts it; it is never meant.
        d = float(d)
        if not 0 <= d <= 1:
            raise ValueError(f"NewtonIntegrator.damping must be in [0, 1] (usually 0 to 0.4), got {d}")
        self._cpp.damping = d

    dampGravity = property(lambda self: self._cpp.dampGravity,
                           lambda self, d: setattr(self._cpp, "dampGravity", bool(d)))
    mask = property(lambda self: self._cpp.mask,
                    lambda self, m: setattr(self._cpp, "mask", group_mask(m, "NewtonIntegrator.mask")),
                    doc="positive: only bodies whose mask shares a bit with it move (Yade's; -1: all)")


def asCallback(command: str | Callable[[], None] | None, what: str = "command") -> Callable[[], None] | None:
    """A command as a Python callable (None for none): a callable as it is, a string run in the
    script's namespace, as Yade runs its PyRunner commands and hooks."""
    if not command:
        return None
    if callable(command):
        return command
    from talus.dem.files import trust
    held = trust.held(command, what)      # a command of an untrusted checkpoint
    if held is not None:
        return held
    code = compile(command, f"<{what} {command!r}>", "exec")
    # The script's namespace is looked up at each call: `talus run` runs the script as a fresh
    # __main__ module, which is not the one this module saw when it was imported.
    return lambda: exec(code, vars(sys.modules["__main__"]))


def _yade_command(command: str) -> Callable[[], None]:
    """A PyRunner's command string as a callable that runs it in the script's namespace and
    reports an error in it as Yade does: a RuntimeError whose text is "PyRunner error.", the
    command, the error and the command's own traceback."""
    from talus.dem.files import trust
    held = trust.held(command, "PyRunner")      # a command of an untrusted checkpoint
    if held is not None:
        return held
    code = compile(command, "<string>", "exec")

    def run():
        try:
            exec(code, vars(sys.modules["__main__"]))
        except Exception as e:
            import traceback
            # The traceback from the command's own frame on (this function's is not Yade's).
            trace = traceback.format_exception(type(e), e, e.__traceback__.tb_next)
            raise RuntimeError(f"PyRunner error.\n\nCOMMAND: {command!r}\n\nERROR:\n{e}\n\nSTACK TRACE:\n"
                               + "\n".join(trace)) from e
    return run


class PyRunner(Engine):
    """Runs ``command`` every ``iterPeriod`` steps, ``virtPeriod`` seconds of simulated time
    and/or ``realPeriod`` seconds of wall time: a string executed in the script's namespace (as
    in Yade) or a Python callable; at most ``nDo`` times (-1: no limit). ``firstIterRun`` > 0:
    first called at that step, then every ``iterPeriod`` (Yade's; it disables ``initRun``)."""

    def __init__(self, command: str | Callable[[], None] = "", iterPeriod: int = 0, realPeriod: float = 0,
                 initRun: bool = False, label: str = "", dead: bool = False, virtPeriod: float = 0, nDo: int = -1,
                 firstIterRun: int = 0):
        if min(iterPeriod, realPeriod, virtPeriod) < 0:
            raise ValueError(f"PyRunner: iterPeriod, realPeriod and virtPeriod must be >= 0, got {iterPeriod}, "
                             f"{realPeriod}, {virtPeriod}")
        if iterPeriod == 0 and realPeriod == 0 and virtPeriod == 0:
            iterPeriod = 1          # Yade's default: every step
        self._cpp = _dem.CallbackEngine()
        self._cpp.resumable = True    # its error leaves the scene whole: the step can be finished
        self._cpp.iterPeriod = iterPeriod
        self._cpp.realPeriod = float(realPeriod)
        self._cpp.virtPeriod = float(virtPeriod)
        self._cpp.initRun = initRun
        self._cpp.nDo = int(nDo)
        self._firstIterRun = int(firstIterRun)
        if firstIterRun > 0:
            if self._cpp.iterPeriod <= 0:
                raise ValueError("PyRunner: firstIterRun needs an iterPeriod (Talus schedules it by steps)")
            self._cpp.initRun = False
            self._cpp.iterLast = int(firstIterRun) - self._cpp.iterPeriod
        self.command = command
        self.label = label
        self.dead = dead

    @property
    def command(self):
        return self._command

    @command.setter
    def command(self, command):
        self._command = command
        from talus.dem.split import by_id
        if isinstance(command, str) and command:
            callback = _yade_command(command)
        else:
            callback = asCallback(command, "PyRunner") or (lambda: None)
        self._cpp.callback = by_id.agreeing(callback, self._cpp)     # under mpirun: every process at its end

    def __call__(self):
        """Run the command once, now: Yade's ``engine()`` (whatever the periods, even when dead)."""
        self._cpp.callback()

    iterPeriod = property(lambda self: self._cpp.iterPeriod, lambda self, v: setattr(self._cpp, "iterPeriod", v))
    virtPeriod = property(lambda self: self._cpp.virtPeriod, lambda self, v: setattr(self._cpp, "virtPeriod", float(v)))
    nDone = property(lambda self: self._cpp.nDone)
    firstIterRun = property(lambda self: self._firstIterRun, doc="the step of the first call (0: by the periods)")
    nDo = property(lambda self: self._cpp.nDo, lambda self, v: setattr(self._cpp, "nDo", int(v)),
                   doc="calls after which it is not called any more (-1: no limit)")


__all__ = [
    "Functor", "Engine", "collapseDispatchers", "Dispatcher", "BoundDispatcher", "IGeomDispatcher", "IPhysDispatcher", "LawDispatcher", "ForceResetter", "InsertionSortCollider", "InteractionLoop", "NewtonIntegrator",
    "PyRunner", "ParallelEngine", "asCallback", "FlatGridCollider", "Ig2_Box_Sphere_ScGeom6D", "Bo1_Sphere_Aabb", "Bo1_Wall_Aabb", "Bo1_Facet_Aabb", "Bo1_Box_Aabb", "Ig2_Sphere_Sphere_ScGeom",
    "Ig2_Box_Sphere_ScGeom",
    "Ig2_Wall_Sphere_ScGeom", "Ig2_Facet_Sphere_ScGeom",
    "Ip2_FrictMat_FrictMat_FrictPhys", "Ip2_ViscElMat_ViscElMat_ViscElPhys",
    "Law2_ScGeom_FrictPhys_CundallStrack", "Law2_ScGeom_ViscElPhys_Basic",
    "Ip2_FrictMat_FrictMat_MindlinPhys", "Law2_ScGeom_MindlinPhys_Mindlin", "MatchMaker",
    "Ip2_CohFrictMat_CohFrictMat_CohFrictPhys", "Law2_ScGeom6D_CohFrictPhys_CohesionMoment", "Ig2_Sphere_Sphere_ScGeom6D",
    "Ig2_Wall_Sphere_ScGeom6D",
]


def collapseDispatchers(engines: Sequence) -> list:
    """An engine list with each IGeomDispatcher, IPhysDispatcher, LawDispatcher triple (Yade's
    older spelling of an InteractionLoop) replaced by the InteractionLoop it stands for. The law
    (a LawDispatcher, or Yade's ElasticContactLaw) may come after other engines, which then run
    after the loop: the forces come from the geometry of the loop's place."""
    out, k = [], 0
    while k < len(engines):
        if [type(e) for e in engines[k:k + 2]] == [IGeomDispatcher, IPhysDispatcher]:
            law = next((j for j in range(k + 2, len(engines))
                        if isinstance(engines[j], Dispatcher) and not isinstance(engines[j], Engine)), None)
            if law is not None and isinstance(engines[law], LawDispatcher):
                out.append(InteractionLoop(engines[k], engines[k + 1], engines[law], label=engines[law].label))
                out.extend(engines[k + 2:law])
                k = law + 1
                continue
        if isinstance(engines[k], Dispatcher) and not isinstance(engines[k], Engine):
            raise TypeError(f"O.engines: {type(engines[k]).__name__} must come as IGeomDispatcher, IPhysDispatcher, "
                            "LawDispatcher in a row (or use InteractionLoop)")
        out.append(engines[k])
        k += 1
    return out
