"""Yade's particle factories: ``BoxFactory`` and ``CircularFactory`` insert spheres at random
places of a region at a given mass flow rate (Yade's SpheresFactory family)::

    O.engines = [..., NewtonIntegrator(),
                 BoxFactory(center=(0, 0, 1), extents=(0.2, 0.2, 0.01), normal=(0, 0, -1),
                            massFlowRate=2.0, rMin=0.01, rMax=0.012, vMin=1, vMax=1.5,
                            maxParticles=-1, materialId=0, label='factory')]

Each step the goal mass grows by massFlowRate dt and spheres are inserted until the inserted
mass reaches it (or ``maxParticles`` / ``maxMass``). A sphere's radius is uniform in
[rMin, rMax], or follows the size distribution ``PSDsizes``/``PSDcum``; its place is drawn at
random in the region until its bounding box meets no other body's (grown by the collider's
skin, as Yade's bounds are) nor a sphere inserted in the same step, at most ``maxAttempt``
times (then, with ``stopIfFailed``, the factory stops). All spheres of a step get the same
velocity, along ``normalVel`` (or ``normal``) with a magnitude uniform in [vMin, vMax]; as in
Yade ``vAngle`` is kept but not used. ``mask`` > 0 is the spheres' group mask.

Yade draws from a generator seeded by the clock; Talus's factories are reproducible: ``seed``
(default: the factory's rank among the factories made so far) seeds each factory's own
generator, whose state checkpoints keep. The spheres placed differ from Yade's, the flow
(mass, number, sizes) is the same.
"""

from __future__ import annotations

import inspect
import itertools
import math
import warnings

import numpy as np

from talus import _dem
from talus.dem.core.bodies import sphere
from talus.dem.base.linalg import Quaternion, Vector3
from talus.dem.step.python_engines import PythonEngine, colliderSkin

_ranks = itertools.count()   # default seeds


def _vector(value, name: str, owner: str) -> np.ndarray:
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.shape != (3,):
        raise ValueError(f"{owner}.{name} takes 3 numbers, got {value!r}")
    return v


class SpheresFactory(PythonEngine):
    """Yade's SpheresFactory: the flow of spheres; its region is a derived engine's
    (BoxFactory, CircularFactory). See the module's docstring."""

    _VECTORS = ("normal", "normalVel", "color")

    def __init__(self, massFlowRate: float = math.nan, rMin: float = math.nan, rMax: float = math.nan,
                 vMin: float = math.nan, vMax: float = math.nan, vAngle: float = math.nan,
                 normal=(math.nan,) * 3, normalVel=(math.nan,) * 3, materialId: int = -1, mask: int = -1,
                 color=(-1.0, -1.0, -1.0), ids=(), totalMass: float = 0.0, totalVolume: float = 0.0,
                 goalMass: float = 0.0, maxParticles: int = 100, maxMass: float = -1.0, numParticles: int = 0,
                 maxAttempt: int = 5000, silent: bool = False, blockedDOFs: str = "", PSDsizes=(), PSDcum=(),
                 PSDcalculateMass: bool = True, stopIfFailed: bool = True, exactDiam: bool = True,
                 seed: int | None = None, label: str = "", dead: bool = False):
        super().__init__(label, dead)
        self.massFlowRate, self.rMin, self.rMax = float(massFlowRate), float(rMin), float(rMax)
        self.vMin, self.vMax, self.vAngle = float(vMin), float(vMax), float(vAngle)
        self.normal, self.normalVel, self.color = normal, normalVel, color
        self.materialId, self.mask = int(materialId), int(mask)
        self.ids = [int(i) for i in ids]
        self.totalMass, self.totalVolume, self.goalMass = float(totalMass), float(totalVolume), float(goalMass)
        self.maxParticles, self.maxMass, self.numParticles = int(maxParticles), float(maxMass), int(numParticles)
        self.maxAttempt, self.silent, self.blockedDOFs = int(maxAttempt), bool(silent), str(blockedDOFs)
        self.PSDsizes, self.PSDcum = [float(x) for x in PSDsizes], [float(x) for x in PSDcum]
        self.PSDcalculateMass, self.stopIfFailed, self.exactDiam = bool(PSDcalculateMass), bool(stopIfFailed), bool(exactDiam)
        self.seed = next(_ranks) if seed is None else int(seed)
        self._random = np.random.default_rng(self.seed)
        self._bins = None   # the size distribution's bins once checked: [needed, inserted] per bin

    def __setattr__(self, name, value):
        if name in self._VECTORS:
            value = Vector3(_vector(value, name, type(self).__name__))
        super().__setattr__(name, value)

    # -- the region (derived engines) ----------------------------------------------------------
    def _check_region(self):
        raise RuntimeError(f"{type(self).__name__} has no region: use BoxFactory or CircularFactory "
                           "(Yade's SpheresFactory cannot run either)")

    def _pick_position(self, radius: float) -> np.ndarray:
        raise NotImplementedError

    def _to_normal(self) -> np.ndarray:
        """The rotation taking the z axis to ``normal`` (the region's orientation)."""
        return np.asarray(Quaternion(Vector3(0, 0, 1), self.normal).toRotationMatrix())

    # -- one step ------------------------------------------------------------------------------
    def _require(self, *names):
        for name in names:
            value = np.asarray(getattr(self, name), dtype=float)
            if not np.all(np.isfinite(value)):
                raise ValueError(f"{type(self).__name__}.{name} must be set (got {getattr(self, name)!r})")

    def _action(self, scene):
        self._check_region()
        self._require("massFlowRate", "normal")
        if self.PSDcum and self._bins is None:
            self._bins = self._check_distribution()
        if not self.PSDcum:
            self._require("rMin", "rMax")
        self._require("vMin", "vMax")
        grow = colliderSkin(scene, type(self).__name__)
        self.goalMass += self.massFlowRate * scene.dt
        self.normal = np.asarray(self.normal) / np.linalg.norm(self.normal)
        if self.maxMass > 0 and self.maxParticles > 0:
            warnings.warn(f"{type(self).__name__}: both maxMass and maxParticles cannot be > 0; setting maxMass=-1",
                          RuntimeWarning, stacklevel=2)
            self.maxMass = -1.0
        direction = np.asarray(self.normalVel, dtype=float)
        direction = direction / np.linalg.norm(direction) if np.linalg.norm(direction) > 0 else np.asarray(self.normal)
        velocity = direction * (self.vMin + self._random.random() * (self.vMax - self.vMin))
        material = self.materialId if self.materialId >= 0 else len(scene.materials) + self.materialId
        if not 0 <= material < len(scene.materials):
            raise ValueError(f"{type(self).__name__}: invalid material id {self.materialId}")
        placed: list[tuple[np.ndarray, float]] = []   # this step's spheres, which have no bounds yet
        while (self.totalMass < self.goalMass and (self.maxParticles < 0 or self.numParticles < self.maxParticles)
               and (self.maxMass < 0 or self.totalMass < self.maxMass)):
            radius, bin = self._pick_radius()
            for _ in range(self.maxAttempt):
                center = self._pick_position(radius)
                if (not _dem.bodies_in_box(scene._cpp, center - radius, center + radius, grow)
                        and all(np.linalg.norm(c - center) >= r + radius for c, r in placed)):
                    break
            else:
                message = f"{type(self).__name__}: unable to place new sphere after {self.maxAttempt} attempts!"
                if not self.silent:
                    warnings.warn(message, RuntimeWarning, stacklevel=2)
                if self.stopIfFailed:
                    self.massFlowRate, self.goalMass = 0.0, self.totalMass
                return
            self._insert(scene, center, radius, velocity, material, bin)
            placed.append((center, radius))

    def _insert(self, scene, center, radius, velocity, material, bin):
        color = tuple(self.color) if min(self.color) >= 0 else None
        id = scene.bodies.append(sphere(center, radius, material=material, color=color))
        body = scene.bodies[id]
        body.state.vel = velocity
        if self.blockedDOFs:
            body.state.blockedDOFs = self.blockedDOFs
        if self.mask > 0:
            body.mask = self.mask
        self.ids.append(id)
        mass = body.state.mass
        self.totalMass += mass
        self.totalVolume += 4.0 / 3.0 * math.pi * radius ** 3
        self.numParticles += 1
        if bin is not None:
            self._bins[bin][1] += mass if self.PSDcalculateMass else 1

    # -- sizes ---------------------------------------------------------------------------------
    def _check_distribution(self) -> list[list[float]]:
        name, cum, sizes = type(self).__name__, self.PSDcum, self.PSDsizes
        if self.exactDiam and len(cum) != len(sizes):
            raise ValueError(f"{name}: PSDcum and PSDsizes should have an equal number of elements, if exactDiam=True.")
        if not self.exactDiam and len(cum) != len(sizes) - 1:
            raise ValueError(f"{name}: PSDsizes should have a number of elements on 1 more, than PSDcum, if exactDiam=False")
        if cum[0] <= 0 or any(b < a for a, b in zip(cum, cum[1:])):
            raise ValueError(f"{name}: PSDcum should have an ascending positive series of numbers (for example: 0.1, 0.3, 0.5, 1.0)")
        if sizes[0] <= 0 or any(b < a for a, b in zip(sizes, sizes[1:])):
            raise ValueError(f"{name}: PSDsizes should have an ascending positive series of numbers (for example: 15, 20, 50, 80)")
        # Normalised to end at 1 (Yade leaves out the first value, a slip that only matters
        # for a distribution not ending at 1).
        self.PSDcum = [c / cum[-1] for c in cum]
        return [[c - p, 0.0] for p, c in zip([0.0] + self.PSDcum, self.PSDcum)]

    def _pick_radius(self) -> tuple[float, int | None]:
        """A radius, and the bin of the size distribution it is in (None without one): the bin
        furthest below its share (the first on ties; the first if none is below)."""
        if self._bins is None:
            return self.rMin + self._random.random() * (self.rMax - self.rMin), None
        done = self.totalMass if self.PSDcalculateMass else self.numParticles
        bin, most = 0, 0.0
        for k, (need, have) in enumerate(self._bins):
            shortfall = need - (have / done if done else 0.0)
            if shortfall > most:
                bin, most = k, shortfall
        if self.exactDiam:
            return self.PSDsizes[bin] / 2, bin
        low, high = self.PSDsizes[bin] / 2, self.PSDsizes[bin + 1] / 2
        return low + self._random.random() * (high - low), bin

    # -- checkpoints ---------------------------------------------------------------------------
    def _io_params(self) -> dict:
        names = {name for cls in type(self).__mro__ if issubclass(cls, SpheresFactory)
                 for name in inspect.signature(cls.__init__).parameters if name not in ("self", "params")}
        return {name: getattr(self, name) for name in names}

    def _io_state(self):
        return {"random": self._random.bit_generator.state, "bins": self._bins}

    def _io_restore(self, state):
        self._random.bit_generator.state = state["random"]
        self._bins = state["bins"]


class BoxFactory(SpheresFactory):
    """Spheres in a box of half-sizes ``extents`` about ``center``, its z axis turned to
    ``normal`` (a line, a rectangle or a cuboid: some extents may be 0). See talus.dem.packing.factories."""

    _VECTORS = SpheresFactory._VECTORS + ("extents", "center")

    def __init__(self, extents=(math.nan,) * 3, center=(math.nan,) * 3, **params):
        super().__init__(**params)
        self.extents, self.center = extents, center

    def _check_region(self):
        self._require("extents", "center")

    def _pick_position(self, radius: float) -> np.ndarray:
        local = (self._random.random(3) - 0.5) * 2 * np.asarray(self.extents)
        return np.asarray(self.center) + self._to_normal() @ local


class CircularFactory(SpheresFactory):
    """Spheres in a disc of ``radius`` about ``center`` normal to ``normal``, or with
    ``length`` > 0 a cylinder along it. See talus.dem.packing.factories."""

    _VECTORS = SpheresFactory._VECTORS + ("center",)

    def __init__(self, radius: float = math.nan, length: float = 0.0, center=(math.nan,) * 3, **params):
        super().__init__(**params)
        self.radius, self.length, self.center = float(radius), float(length), center

    def _check_region(self):
        self._require("radius", "length", "center")

    def _pick_position(self, radius: float) -> np.ndarray:
        # A random polar point of the disc the sphere's centre may take, as Yade (uniform in
        # radius, so denser near the axis), then along the axis.
        angle, rr, along = self._random.random(3) * (2 * math.pi, self.radius - radius, 1.0)
        disc = np.array([math.cos(angle) * rr, math.sin(angle) * rr, 0.0])
        return np.asarray(self.center) + self._to_normal() @ disc + np.asarray(self.normal) * (along - 0.5) * self.length


__all__ = ["SpheresFactory", "BoxFactory", "CircularFactory"]
