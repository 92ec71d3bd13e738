"""Yade's HydroForceEngine: fluid forces on particles from a 1D vertical fluid velocity profile,
solid-phase averaging, and the 1D VANS fluid resolution, coupled to the DEM through the particle
exchange interface (``O.positions()``, ``O.velocities()``, ``O.radii()``, ``O.forces()``)::

    from talus.dem import *
    from talus.flow import HydroForceEngine, slope_gravity

    hydro = HydroForceEngine(densFluid=1000, viscoDyn=1e-3, zRef=0.0, gravity=slope_gravity(0.05),
                             deltaZ=dz, nCell=900, expoRZ=3.1, radiusPart=3e-3, ids=mobile,
                             vCell=length * width * dz, label="hydroEngine")
    O.engines = [ForceResetter(), ..., InteractionLoop(...), hydro, NewtonIntegrator(...)]
    hydro.averageProfile()                 # phiPart, vxPart, averageDrag from the particles
    hydro.fluidResolution(1e-2, 1e-5)      # vxFluid from the profiles

Names and defaults are Yade 2023.02a's. The forces are added every step to the particles of
``ids``; the fluid part (``fluidResolution``, its options and outputs) is a ``VansFluid``
(``hydro.fluid``) sharing the grid, fluid properties and profiles. Physics: ``docs/flow.md``.
"""

from __future__ import annotations

import math
import warnings
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from talus import _flow
from talus.dem.step.engines import Engine, PyRunner
from talus.flow.step_callback import step_of
from talus.flow.vans import VansFluid, core_parameter

__all__ = ["HydroForceEngine", "averageProfile"]

# Whether a particle of ids centred outside the grid is an error in a new engine (see
# HydroForceEngine's ignoreOutside). Yade gives it no fluid force: a run started as `yade -x`
# would start it sets False (yade_run_defaults below, called through yade.yade_run_defaults).
OUTSIDE_IS_ERROR = True


def yade_run_defaults() -> None:
    """Behave as Yade 2023.02a where Talus's defaults differ: particles leaving the grid (grains
    leaping out of the water) get no fluid force instead of stopping the run."""
    global OUTSIDE_IS_ERROR
    OUTSIDE_IS_ERROR = False


# Yade 2023.02a's attributes of HydroForceEngine that Talus lacks: setting one is an error, not
# a new Python attribute that changes nothing.
_YADE_UNIMPLEMENTED = frozenset((
    "twoSize", "radiusPart1", "radiusPart2", "phiPart1", "phiPart2", "vxPart1", "vxPart2", "vyPart1",
    "vyPart2", "vzPart1", "vzPart2", "averageDrag1", "averageDrag2", "pointParticleAverage", "lubrication",
    "roughnessPartScale", "convAccOption", "convAcc", "compatibilityOldVersion", "nbAverageT", "phiBed", "dtFluct",
    "fluctTime", "vFluctX", "vFluctY", "vFluctZ", "ompThreads"))

# The per-class profiles of averageProfile with enableMultiClassAverage: Yade's attribute name for
# each profile of the one-class average.
_CLASS_PROFILES = {"phiPart": "multiPhiPart", "vxPart": "multiVxPart", "vyPart": "multiVyPart",
                   "vzPart": "multiVzPart", "averageDrag": "multiDragPart"}

# Options of the fluid resolution that belong to the VansFluid alone.
_FLUID_ONLY = ("radiusPart", "iturbu", "ilm", "phiMax", "viscousSubLayer", "irheolf", "iusl", "uTop",
               "dpdx", "fluidWallFriction", "channelWidth", "fluidFrictionCoef")


def _shared_parameter(name: str, doc: str, convert=float):
    """A parameter of both the particle side and the fluid resolution (kept equal)."""
    particle = core_parameter(name, doc, convert)

    def set(self, value):
        setattr(self.fluid, name, value)          # validated there first
        particle.fset(self, value)
    return property(particle.fget, set, doc=doc)


def _fluid_parameter(name: str):
    return property(lambda self: getattr(self.fluid, name), lambda self, v: setattr(self.fluid, name, v),
                    doc=f"Fluid-resolution option ``{name}`` (see talus.flow.VansFluid).")


def _array(values: ArrayLike, name: str) -> np.ndarray:
    try:
        a = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"HydroForceEngine: {name} must be an array of numbers") from None
    if a.ndim != 1:
        raise ValueError(f"HydroForceEngine: {name} must be one-dimensional, got shape {a.shape}")
    return a


class HydroForceEngine(Engine):
    """Drag, buoyancy and optional lift on the spheres ``ids`` from the fluid velocity profile
    ``vxFluid`` and solid fraction ``phiPart`` on a grid of ``nCell`` layers of height ``deltaZ``
    from ``zRef`` (Yade's HydroForceEngine). Put it in ``O.engines`` after the InteractionLoop.

    Args (Yade's names and defaults; all are attributes too):
        nCell (or ndimz), deltaZ: the grid, nCell >= 1 layers [zRef, zRef + nCell deltaZ); the
            fluid resolution needs nCell >= 2 (its column is (nCell - 1) deltaZ high, so the top
            layer sees the surface velocity vxFluid[nCell], as in Yade).
        densFluid, viscoDyn: fluid density [kg/m^3] and dynamic viscosity [Pa s].
        gravity: gravity vector (buoyancy; |gravity[0]| drives the fluid resolution).
        expoRZ: Richardson-Zaki exponent of the hindrance (1 - phi)^-expoRZ.
        lift, Cl: lift force on/off and its coefficient.
        steadyFlow: no streamwise buoyancy (steady flow: the pressure gradient balances the fluid
            weight); False for a fluid at rest.
        ids: the particles receiving fluid forces.
        vCell: volume of a layer for averageProfile; 0 in a periodic cell means its horizontal
            area times deltaZ.
        enableMultiClassAverage: averageProfile also gives the profiles of each class of
            sphere radius (``radiusParts``, found by ``initialization`` or ``computeRadiusParts``):
            ``multiPhiPart``, ``multiVxPart``, ``multiVyPart``, ``multiVzPart``, ``multiDragPart``.
        velFluct: turbulent velocity fluctuations (discrete random walk on an eddy time scale
            0.33 kappa z / u*, u* = sqrt(ReynoldStresses / rho)), reproducible with ``seed``;
            bedElevation (above zRef) and unCorrelatedFluctuations as in Yade.
        ignoreOutside: particles of ids centred outside the grid [zRef, zRef + nCell deltaZ) get
            no fluid force (Yade's behaviour) instead of an error. Default: False, except in
            scripts run as Yade's (``talus run``, ``yadeimport``), where it is True.
        scene: the scene (default ``talus.dem.O``).
        Other keywords are the fluid resolution's (VansFluid): radiusPart, iturbu, ilm, kappa,
            phiMax, viscousSubLayer, irheolf, iusl, uTop, dpdx, fluidWallFriction, channelWidth,
            fluidFrictionCoef.
    """

    def __init__(self, *, deltaZ: float, nCell: int | None = None, ndimz: int | None = None,
                 zRef: float = 0.0, densFluid: float = 1000.0, viscoDyn: float = 1e-3,
                 gravity: Sequence[float] = (0.0, 0.0, -9.81), expoRZ: float = 3.1, lift: bool = False,
                 Cl: float = 0.2, steadyFlow: bool = True, ids: Sequence[int] = (), vCell: float = 0.0,
                 velFluct: bool = False, bedElevation: float = 0.0, unCorrelatedFluctuations: bool = False,
                 kappa: float = 0.41, seed: int = 0, ignoreOutside: bool | None = None,
                 enableMultiClassAverage: bool = False, scene=None,
                 label: str = "", dead: bool = False, **fluid_options):
        unknown = set(fluid_options) - set(_FLUID_ONLY)
        if unknown:
            raise TypeError(f"HydroForceEngine: unknown parameter(s) {sorted(unknown)}")
        self.fluid = VansFluid(nCell=nCell, ndimz=ndimz, deltaZ=deltaZ, densFluid=densFluid, viscoDyn=viscoDyn,
                               gravity=gravity, kappa=kappa, **fluid_options)
        p = _flow.HydroForceParameters()
        p.nCell, p.deltaZ, p.zRef = self.fluid.nCell, float(deltaZ), float(zRef)
        p.densFluid, p.viscoDyn, p.expoRZ = float(densFluid), float(viscoDyn), float(expoRZ)
        p.lift, p.Cl, p.steadyFlow = bool(lift), float(Cl), bool(steadyFlow)
        p.gravity = list(self.fluid.gravity)
        p.velFluct, p.bedElevation = bool(velFluct), float(bedElevation)
        p.unCorrelatedFluctuations, p.kappa = bool(unCorrelatedFluctuations), float(kappa)
        p.ignoreOutside = not OUTSIDE_IS_ERROR if ignoreOutside is None else bool(ignoreOutside)
        self._core = _flow.HydroForce(p)
        self._core.seed(int(seed))
        self._scene = scene
        self.vCell = vCell
        self.enableMultiClassAverage = bool(enableMultiClassAverage)
        self.radiusParts = []
        self._multi: dict[str, list[list[float]]] = {name: [] for name in _CLASS_PROFILES.values()}
        self.ids = ids
        self._vy = np.zeros(self.nCell)
        self._vz = np.zeros(self.nCell)
        self._cpp = PyRunner(step_of(self, "action"), iterPeriod=1, initRun=True)._cpp   # every step, the first one included
        self._cpp.resumable = False   # a failure leaves the step without its hydrodynamic forces
        self.label = label
        self.dead = dead

    def __setattr__(self, name: str, value) -> None:
        if not name.startswith("_") and name != "fluid" and not hasattr(type(self), name):
            if name in _YADE_UNIMPLEMENTED:
                raise AttributeError(f"HydroForceEngine.{name}: a Yade 2023.02a attribute that Talus does not implement")
            # Yade keeps such a name as a plain Python attribute (its examples set some that
            # HydroForceEngine no longer has, e.g. simplifiedReynoldStresses): so does Talus, saying so.
            warnings.warn(f"HydroForceEngine.{name} is not an attribute of HydroForceEngine (Yade 2023.02a's or "
                          "Talus's): kept as a plain Python attribute, it changes nothing", RuntimeWarning,
                          stacklevel=2)
        super().__setattr__(name, value)

    # -- the scene and its arrays (the particle exchange interface) -----------------------------
    @property
    def scene(self):
        if self._scene is None:
            from talus.dem import O
            return O
        return self._scene

    def _arrays(self):
        s = self.scene
        return s.positions(), s.velocities(), s.radii()

    def _sync_cell(self) -> None:
        """Period along z and default layer volume from a periodic cell."""
        s = self.scene
        p = self._core.parameters()
        period = 0.0
        if s.periodic:
            h = s.cell.hSize
            if h[2, 0] != 0 or h[2, 1] != 0:
                raise ValueError("HydroForceEngine: the periodic cell is tilted along z (hSize[2, 0:2] != 0); "
                                 "layers along z are not defined")
            period = float(h[2, 2])
        if p.periodZ != period:
            p.periodZ = period
            self._core.setParameters(p)

    def _layer_volume(self) -> float:
        v = self._vCell
        if v > 0:
            return v
        s = self.scene
        if s.periodic:
            h = s.cell.hSize
            return float(abs(np.linalg.det(h)) / h[2, 2] * self.deltaZ)
        raise ValueError("HydroForceEngine.averageProfile: vCell (volume of a layer) must be set "
                         "outside a periodic cell")

    # -- parameters ------------------------------------------------------------------------------
    @property
    def nCell(self) -> int:
        """Number of layers (``ndimz`` in Yade's scripts); changing it resets the profiles."""
        return self.fluid.nCell

    @nCell.setter
    def nCell(self, value: int):
        self.fluid.nCell = value
        p = self._core.parameters()
        p.nCell = self.fluid.nCell
        self._core.setParameters(p)
        self._vy, self._vz = np.zeros(self.nCell), np.zeros(self.nCell)

    ndimz = nCell
    deltaZ = _shared_parameter("deltaZ", "Layer height [m].")
    densFluid = _shared_parameter("densFluid", "Fluid density [kg/m^3].")
    viscoDyn = _shared_parameter("viscoDyn", "Fluid dynamic viscosity [Pa s].")
    kappa = _shared_parameter("kappa", "Von Karman constant (mixing length and eddy time scale).")
    zRef = core_parameter("zRef", "Elevation of the bottom of the grid [m].")
    expoRZ = core_parameter("expoRZ", "Richardson-Zaki exponent of the drag hindrance.")
    lift = core_parameter("lift", "Lift force on/off.", bool)
    Cl = core_parameter("Cl", "Lift coefficient.")
    steadyFlow = core_parameter("steadyFlow", "No streamwise buoyancy (steady flow).", bool)

    @property
    def vCell(self) -> float:
        """Volume of a layer [m^3] for averageProfile; 0 in a periodic cell: its horizontal area
        times deltaZ."""
        return self._vCell

    @vCell.setter
    def vCell(self, value: float):
        value = float(value)
        if not (value >= 0 and math.isfinite(value)):
            raise ValueError(f"HydroForceEngine: vCell must be finite and >= 0, got {value}")
        self._vCell = value

    velFluct = core_parameter("velFluct", "Turbulent velocity fluctuations on/off.", bool)
    bedElevation = core_parameter("bedElevation", "Elevation above zRef below which there are no "
                                                  "fluctuations [m].")
    unCorrelatedFluctuations = core_parameter("unCorrelatedFluctuations",
                                              "Streamwise and wall-normal fluctuations independent.", bool)
    ignoreOutside = core_parameter("ignoreOutside", "Particles centred below zRef or above the grid get no "
                                                    "fluid force (instead of an error).", bool)
    for _name in _FLUID_ONLY:
        locals()[_name] = _fluid_parameter(_name)
    del _name

    @property
    def gravity(self) -> tuple[float, float, float]:
        """Gravity vector (buoyancy; |gravity[0]| drives the fluid resolution)."""
        return self.fluid.gravity

    @gravity.setter
    def gravity(self, value: Sequence[float]):
        self.fluid.gravity = value
        p = self._core.parameters()
        p.gravity = list(self.fluid.gravity)
        self._core.setParameters(p)

    @property
    def ids(self) -> np.ndarray:
        """Ids of the particles receiving fluid forces."""
        return self._ids.copy()

    @ids.setter
    def ids(self, value: Sequence[int]):
        ids = np.asarray(list(value), dtype=np.int64).reshape(-1)
        self._ids = ids

    def seed(self, value: int) -> None:
        """Restart the random generator of the velocity fluctuations."""
        self._core.seed(int(value))

    # -- profiles ---------------------------------------------------------------------------------
    @property
    def vxFluid(self) -> np.ndarray:
        """Fluid velocity at the nCell + 1 velocity nodes (zFluid + zRef) [m/s]. Also settable
        with nCell values (as Yade's scripts impose profiles): the top node, the velocity of the
        top layer's particles and the fluid resolution's start at the surface, is then 0, which
        is what Yade 2023.02a reads past the end of such a profile (a RuntimeWarning says so)."""
        return self.fluid.vxFluid

    @vxFluid.setter
    def vxFluid(self, values: ArrayLike):
        a = _array(values, "vxFluid")
        if len(a) == self.nCell:
            warnings.warn(f"HydroForceEngine: vxFluid has nCell = {self.nCell} values; its top node vxFluid[nCell] "
                          "(the top layer's fluid velocity) is taken as 0, as Yade does", RuntimeWarning, stacklevel=2)
            a = np.append(a, 0.0)
        self.fluid.vxFluid = a
        self._core.setVxFluid(a)

    @property
    def phiPart(self) -> np.ndarray:
        """Solid volume fraction per layer (hindrance of the drag; input of the fluid resolution)."""
        return self.fluid.phiPart

    @phiPart.setter
    def phiPart(self, values: ArrayLike):
        a = _array(values, "phiPart")
        self.fluid.phiPart = a
        self._core.setPhiPart(a)

    vxPart = property(lambda self: self.fluid.vxPart, lambda self, v: setattr(self.fluid, "vxPart", v),
                      doc="Mean streamwise particle velocity per layer [m/s].")
    averageDrag = property(lambda self: self.fluid.averageDrag,
                           lambda self, v: setattr(self.fluid, "averageDrag", v),
                           doc="Mean streamwise drag per particle in each layer [N].")
    vyPart = property(lambda self: self._vy.copy(), doc="Mean spanwise particle velocity per layer [m/s].")
    vzPart = property(lambda self: self._vz.copy(), doc="Mean wall-normal particle velocity per layer [m/s].")

    @property
    def vPart(self) -> np.ndarray:
        """Mean particle velocity per layer, shape (nCell, 3) (Yade's vPart)."""
        return np.column_stack([self.vxPart, self._vy, self._vz])

    @property
    def ReynoldStresses(self) -> np.ndarray:
        """Reynolds shear stress per mesh node [Pa]: from the last fluid resolution, or set by the
        user (it scales the velocity fluctuations)."""
        return self._core.reynoldStresses()

    @ReynoldStresses.setter
    def ReynoldStresses(self, values: ArrayLike):
        self._core.setReynoldStresses(_array(values, "ReynoldStresses"))

    enableMultiClassAverage = False   # each engine sets its own in __init__

    @property
    def radiusParts(self) -> list[float]:
        """The radius classes of enableMultiClassAverage [m] (``computeRadiusParts`` finds them)."""
        return list(self._radiusParts)

    @radiusParts.setter
    def radiusParts(self, values: Sequence[float]):
        radii = [float(r) for r in values]
        if not all(r > 0 and math.isfinite(r) for r in radii):
            raise ValueError(f"HydroForceEngine.radiusParts: radii must be positive and finite, got {radii}")
        self._radiusParts = radii

    multiPhiPart = property(lambda self: self._multi["multiPhiPart"],
                            doc="Solid volume fraction per layer of each radius class (enableMultiClassAverage).")
    multiVxPart = property(lambda self: self._multi["multiVxPart"],
                           doc="Mean streamwise velocity per layer of each radius class [m/s].")
    multiVyPart = property(lambda self: self._multi["multiVyPart"],
                           doc="Mean spanwise velocity per layer of each radius class [m/s].")
    multiVzPart = property(lambda self: self._multi["multiVzPart"],
                           doc="Mean wall-normal velocity per layer of each radius class [m/s].")
    multiDragPart = property(lambda self: self._multi["multiDragPart"],
                             doc="Mean streamwise drag per particle in each layer of each radius class [N].")

    turbulentViscosity = property(lambda self: self.fluid.turbulentViscosity, doc="Eddy viscosity [m^2/s].")
    taufsi = property(lambda self: self.fluid.taufsi, doc="Drag exchange coefficient [1/s].")

    @property
    def vFluct(self) -> np.ndarray:
        """Current velocity fluctuation of each body, shape (bodies, 3) (Yade's vFluctX/Y/Z)."""
        return self._core.fluctuations().reshape(-1, 3)

    # -- operations -------------------------------------------------------------------------------
    def initialization(self) -> None:
        """Reset every profile to zeros and find the classes of sphere radius (Yade's
        ``initialization()``)."""
        self.fluid.initialization()
        n = self.nCell
        self._core.setVxFluid(np.zeros(n + 1))
        self._core.setPhiPart(np.zeros(n))
        self._core.setReynoldStresses(np.zeros(n))
        self._vy, self._vz = np.zeros(n), np.zeros(n)
        self.computeRadiusParts()

    def computeRadiusParts(self) -> None:
        """``radiusParts``: each distinct radius among the spheres of ``ids``, in their order (the
        classes of ``enableMultiClassAverage``; Yade 2023.02a takes them from ``ids`` too)."""
        spheres = self._ids[np.isin(self._ids, self.scene.sphere_ids())]
        self.radiusParts = [float(r) for r in dict.fromkeys(self.scene.radii()[spheres].tolist())]

    def action(self) -> None:
        """Add this step's fluid forces to the particles of ``ids`` (called every step as an engine)."""
        if self._core.parameters().periodZ == 0 and self.scene.periodic:
            self._sync_cell()
        s = self.scene
        self._core.action(s.positions(), s.velocities(), s.radii(), s.forces(), self._ids, s.dt)

    def force(self, id: int) -> np.ndarray:
        """The fluid force ``action`` applies to body ``id`` now (without advancing fluctuations)."""
        self._sync_cell()
        return np.asarray(self._core.force(*self._arrays(), int(id)))

    def measure(self, ids: Sequence[int] | None = None) -> dict:
        """The solid-phase profiles of ``averageProfile`` without storing them: a standalone
        measurement that leaves the coupling untouched. Returns a dict of nCell-long arrays
        ``phiPart``, ``vxPart``, ``vyPart``, ``vzPart``, ``averageDrag``."""
        self._sync_cell()
        p = self._core.parameters()
        p.vCell = self._layer_volume()
        self._core.setParameters(p)
        chosen = self.scene.sphere_ids() if ids is None else np.asarray(list(ids), dtype=np.int64)
        return self._core.averageProfile(*self._arrays(), chosen)

    def averageProfile(self, ids: Sequence[int] | None = None) -> dict:
        """Solid fraction ``phiPart``, mean velocity ``vxPart``/``vyPart``/``vzPart`` and mean
        streamwise drag ``averageDrag`` per layer, each sphere split between layers with the
        exact volume of its slices; over ``ids`` (default: every sphere, as Yade). Stores them
        (inputs of the next fluidResolution and of the hindrance) and returns them."""
        profile = self.measure(ids)
        if self.enableMultiClassAverage:      # before phiPart changes: the drag's hindrance reads it
            self._average_classes(ids)
        self.phiPart = profile["phiPart"]
        self.fluid.vxPart = profile["vxPart"]
        self.fluid.averageDrag = profile["averageDrag"]
        self._vy, self._vz = profile["vyPart"], profile["vzPart"]
        return profile

    def _average_classes(self, ids: Sequence[int] | None) -> None:
        """The profiles of each radius class: the one-class average over the spheres of that
        radius. Yade adds each slice's velocity to the layer of the sphere's centre instead of the
        slice's own layer (its per-class velocities differ from its total ones there); Talus
        weighs them layer by layer as the total, so the classes' volume-weighted mean velocity
        is ``vPart``."""
        chosen = self.scene.sphere_ids() if ids is None else np.asarray(list(ids), dtype=np.int64)
        radii = self.scene.radii()[chosen]
        classes = np.asarray(self.radiusParts, dtype=float)
        unknown = ~np.isin(radii, classes)
        # A sphere of no class is an error where it has volume in the grid, as in Yade.
        arrays = self._arrays()        # the grid and layer volume are set: averageProfile measured first
        if unknown.any() and self._core.averageProfile(*arrays, chosen[unknown])["phiPart"].any():
            body = int(chosen[np.argmax(unknown)])
            raise ValueError(f"HydroForceEngine.averageProfile: body {body}'s radius {radii[unknown][0]:g} is not in "
                             "radiusParts (enableMultiClassAverage): call initialization() or computeRadiusParts() "
                             "after adding spheres")
        per_class = [self._core.averageProfile(*arrays, chosen[radii == r]) for r in classes]
        self._multi = {multi: [c[name].tolist() for c in per_class] for name, multi in _CLASS_PROFILES.items()}

    def fluidResolution(self, tfin: float, dt: float) -> None:
        """Advance ``vxFluid`` over ``tfin`` seconds with steps ``dt`` from the stored solid
        profiles (Yade's fluidResolution; see VansFluid.fluidResolution)."""
        self.fluid.fluidResolution(tfin, dt)
        self._core.setVxFluid(self.fluid.vxFluid)
        self._core.setReynoldStresses(self.fluid.ReynoldStresses)

    def turbulentFluctuation(self) -> None:
        """Draw new velocity fluctuations for every particle of ``ids`` now."""
        self._sync_cell()
        self._core.turbulentFluctuation(*self._arrays(), self._ids)

    def transportRate(self, densPart: float, diameterPart: float) -> float:
        """Dimensionless transport rate from the stored profiles:
        sum(phiPart vxPart) deltaZ / sqrt((rho_p/rho_f - 1) |g_z| d^3) (per unit width)."""
        g = abs(self.gravity[2])
        q = float(np.sum(self.phiPart * self.vxPart) * self.deltaZ)
        return q / math.sqrt((densPart / self.densFluid - 1.0) * g * diameterPart ** 3)

    def shieldsNumber(self, densPart: float, diameterPart: float) -> float:
        """Shields number max(ReynoldStresses) / ((rho_p - rho_f) d |g_z|)."""
        return float(np.max(self.ReynoldStresses)) / ((densPart - self.densFluid) * diameterPart
                                                      * abs(self.gravity[2]))

    def __repr__(self):
        return f"HydroForceEngine(nCell={self.nCell}, deltaZ={self.deltaZ:g}, ids={len(self._ids)}, label={self.label!r})"


def averageProfile(*, nCell: int, deltaZ: float, zRef: float = 0.0, vCell: float = 0.0,
                   ids: Sequence[int] | None = None, scene=None, vxFluid: ArrayLike | None = None,
                   **options) -> dict:
    """Standalone solid-phase measurement: the profiles of ``HydroForceEngine.averageProfile``
    (solid fraction, mean velocity, mean drag in the fluid profile ``vxFluid`` if given) over
    the spheres ``ids`` (default all) of ``scene`` (default ``talus.dem.O``), on nCell layers of
    height deltaZ from zRef; ``vCell`` as for the engine. ``options`` are HydroForceEngine's
    (densFluid, viscoDyn, expoRZ, ...), for the drag."""
    engine = HydroForceEngine(nCell=nCell, deltaZ=deltaZ, zRef=zRef, vCell=vCell, scene=scene, dead=True, **options)
    if vxFluid is not None:
        engine.vxFluid = vxFluid
    return engine.measure(ids)
