"""Heat transfer in a sphere packing (Yade's ``ThermalEngine``; Caulk, Scholtès, Krzaczek &
Chareyre 2020, "A pore-scale thermo-hydro-mechanical model for particulate systems", CMAME).

Available now: conduction between particles in contact, one temperature per sphere, explicit in
time::

    C_i dT_i/dt = sum_j G_ij (T_j - T_i),   C_i = m_i particleCp,
    G_ij = 2 (k_i + k_j) r_i r_j / d_ij     (d_ij the distance between the centres)

or, with ``useKernMethod``, ``G_ij = 2 (k_i + k_j) rc² / d_ij`` with rc the radius of the circle
where the two spheres intersect. ``m_i`` is the body's mass, or ``particleDensity`` x volume
when ``particleDensity`` > 0. Temperature boundaries (``bndCondIsTemperature``,
``thermalBndCondValue``, numbered as Yade's ``wallIds``: xmin, xmax, ymin, ymax, zmin, zmax)
hold the spheres that share a pore with that boundary in the triangulation of the scene's
``FlowEngine``, as Yade does; without boundaries no FlowEngine is needed (DEM-only conduction).
On a side that is not a temperature boundary a non-zero ``thermalBndCondValue`` is a heat flux
(W/m² into the packing; Talus's addition, Yade leaves the side insulated) given to the same spheres.

With ``advection`` (and ``fluidConduction``), as Yade: one temperature per pore of the FlowEngine
network (starting at its ``tZero``), advected upwind by the pore fluxes, exchanging heat with the
spheres that bound it (h A (T_pore - T_sphere), h = Nu fluidK / 2r, A the sphere's spherical
triangle in the pore) and conducted between neighbouring pores (fluidK x throat fluid area /
distance). Nu = 2 + 0.6 Re^0.5 Pr^0.33333 with Re = ``uniformReynolds`` in every pore or, with
``uniformReynolds`` = -1 (Yade's default), from each pore's own Reynolds number (its Darcy
velocity and size) by Yade's correlations, which use the packing's porosity (spheres' volume in
their bounding box); as Yade, these are computed at the first step and after each remesh.

Thermal expansion (``thermoMech``, on by default as in Yade): after each thermal run the free
spheres' radii grow by ``state.alpha`` r dT (``particleAlpha`` at the first step); with a
FlowEngine the pores' fluid volume changes by V ``fluidBeta`` dT (``fluidThermoMech``, pore
temperatures from ``advection``) and by the spheres' growth (``solidThermoMech``), which the
FlowEngine's next solves turn into pore pressure (stored by a compressible fluid,
``FlowEngine.fluidBulkModulus`` > 0). See ``docs/thermal.md``.

    thermal = ThermalEngine(label="thermal", advection=False, fluidConduction=False, thermoMech=False,
                            solidThermoMech=False, fluidThermoMech=False, particleT0=400, particleK=2,
                            particleCp=710, particleDensity=2600, tsSafetyFactor=0,
                            bndCondIsTemperature=[1, 1, 0, 0, 0, 0])
    ...
    print(O.bodies[10].state.temp, thermal.thermalBndFlux)
"""

from __future__ import annotations

import base64
import math
import warnings

import numpy as np

from talus import _flow
from talus.dem.core import heat as body_heat
from talus.dem.step.engines import Engine, PyRunner
from talus.flow import stray_attributes
from talus.flow.step_callback import step_of

# Yade 2023.02a's parameters of ThermalEngine and their defaults, by how Talus treats them.
_IMPLEMENTED = {
    "conduction": True, "tsSafetyFactor": 0.8, "particleT0": 0.0, "particleK": 3.0, "particleCp": 750.0,
    "particleDensity": 0.0, "bndCondIsTemperature": [False] * 6, "thermalBndCondValue": [0.0] * 6,
    "useKernMethod": False, "boundarySet": False, "delT": 0.0, "debug": False,
    "advection": True, "fluidConduction": True, "fluidK": 0.58, "fluidConductionAreaFactor": 1.0,
    "minimumFluidCondDist": 0.0, "uniformReynolds": -1.0, "ignoreFictiousConduction": False,
    "thermoMech": True, "solidThermoMech": True, "fluidThermoMech": True,
    "fluidBeta": 2e-4, "particleAlpha": 1.16e-5, "porosityFactor": 0.0,
}
# Switches of the planned physics, with what they switch on.
_PLANNED_SWITCHES = {
    "useHertzMethod": (False, "the Hertzian contact area for the conductance"),
    "letThermalRunFlowForceUpdates": (False, "fluid force updates after thermal pressure changes"),
    "tempDependentFluidBeta": (False, "a temperature-dependent fluid expansion coefficient"),
}
# Accepted (and checked) so that scripts setting them run: Yade 2023.02a reads none of them either
# (the fluid's bulk modulus that acts is FlowEngine.fluidBulkModulus). minimumThermalCondDist is
# not even one of its attributes: its thermoHydroMechanical_coupling example sets it, and Yade
# keeps it as a plain Python attribute that nothing reads.
_PLANNED_NUMBERS = {"fluidBulkModulus": 0.0, "minimumThermalCondDist": 0.0}
_PLANNED_FLAGS = {"unboundCavityBodies": True, "flowTempBoundarySet": True}
_NONNEGATIVE = ("particleK", "particleDensity", "fluidK", "fluidBulkModulus", "porosityFactor",
                "fluidConductionAreaFactor", "minimumFluidCondDist", "particleAlpha", "fluidBeta",
                "minimumThermalCondDist")
_BOUNDARY_NAMES = "xmin, xmax, ymin, ymax, zmin, zmax"


def _defaults() -> dict:
    return {**_IMPLEMENTED, **{k: v for k, (v, _) in _PLANNED_SWITCHES.items()}, **_PLANNED_NUMBERS, **_PLANNED_FLAGS}


def _number(name: str, value) -> float:
    if isinstance(value, (str, bytes, bool)):
        raise TypeError(f"ThermalEngine.{name} must be a number, got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"ThermalEngine.{name} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"ThermalEngine.{name} must be finite, got {value!r}")
    return number


def _temperature(name: str, value) -> float:
    t = _number(name, value)
    error = body_heat.below_absolute_zero(name, t)
    if error is not None:
        raise error
    return t


def _six(name: str, value) -> list:
    values = [value] if isinstance(value, (str, bytes)) else list(np.ravel(value))
    if len(values) != 6:
        raise ValueError(f"ThermalEngine.{name} needs 6 values ({_BOUNDARY_NAMES}), got {value!r}")
    return values


def _check(name: str, value):
    """The value ``name`` takes, or the error that names it."""
    if name == "bndCondIsTemperature":
        flags = _six(name, value)
        if not all(isinstance(v, (bool, int, np.integer, np.bool_)) and v in (0, 1) for v in flags):
            raise TypeError(f"ThermalEngine.{name} must be 6 booleans (True/False or 1/0), got {value!r}")
        return [bool(v) for v in flags]
    if name == "thermalBndCondValue":   # temperatures or heat fluxes: see _check_sides
        return [_number(f"{name}[{k}]", v) for k, v in enumerate(_six(name, value))]
    if name == "particleT0":
        return _temperature("ThermalEngine.particleT0", value)
    if name in _PLANNED_SWITCHES or name in _PLANNED_FLAGS or isinstance(_IMPLEMENTED.get(name), bool):
        if not isinstance(value, (bool, int, np.integer, np.bool_)) or value not in (0, 1):
            raise TypeError(f"ThermalEngine.{name} must be True or False, got {value!r}")
        return bool(value)
    number = _number(name, value)
    if name == "particleCp" and number <= 0:
        raise ValueError(f"ThermalEngine.particleCp must be > 0 (J/(kg K)), got {number}")
    if name in _NONNEGATIVE and number < 0:
        raise ValueError(f"ThermalEngine.{name} must be >= 0, got {number}")
    if name == "uniformReynolds" and number < 0 and number != -1:
        raise ValueError(f"ThermalEngine.uniformReynolds must be >= 0, or -1 for each pore's own, got {number}")
    if name == "tsSafetyFactor" and number > 1:
        raise ValueError(f"ThermalEngine.tsSafetyFactor = {number}: above 1 the explicit conduction step overshoots "
                         "the stable one; use (0, 1], or <= 0 for a thermal step equal to O.dt")
    return number


def _check_sides(bndCondIsTemperature, thermalBndCondValue):
    """A temperature side's value is a temperature; another side's is a heat flux (W/m², any
    finite value: _check has seen to that)."""
    for k, (held, value) in enumerate(zip(bndCondIsTemperature, thermalBndCondValue)):
        if held:
            _temperature(f"ThermalEngine.thermalBndCondValue[{k}]", value)


def _porosity(scene) -> float:
    """Porosity of the spheres in their bounding box (Yade's Shop::getPorosityAlt, which its
    per-pore Nusselt correlation uses)."""
    ids = np.asarray(scene.sphere_ids(), dtype=int)
    pos, radius = np.asarray(scene._cpp.pos())[ids], np.asarray(scene._cpp.radius())[ids]
    size = (pos + radius[:, None]).max(axis=0) - (pos - radius[:, None]).min(axis=0)
    return float(1 - (4 / 3 * np.pi * radius ** 3).sum() / np.prod(size))


def _planned(name: str) -> NotImplementedError:
    return NotImplementedError(f"ThermalEngine.{name}: {_PLANNED_SWITCHES[name][1]} is not implemented yet in Talus "
                               f"(planned, docs/thermal.md); set ThermalEngine.{name} = False")


def _encode(array) -> str:
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f8").tobytes()).decode("ascii")


def _decode(text: str) -> np.ndarray:
    return np.frombuffer(base64.b64decode(text), dtype="<f8").copy()


class ThermalEngine(Engine):
    """Heat conduction between particles with Yade's ThermalEngine names (see the module
    docstring). Placed in ``O.engines`` after the FlowEngine (Yade's order) and before the
    NewtonIntegrator; every body of the scene whose ``state.temp``, ``state.k``, ``state.Cp``,
    ``state.alpha`` (Yade's ThermalState: per-body fields of the DEM core, which other components
    read and change too) are not given gets ``particleT0``, ``particleK``, ``particleCp``,
    ``particleAlpha`` at its steps; ``state.Tcondition`` (read only) says a sphere is held by a
    boundary.

    Time step (``tsSafetyFactor``): <= 0, conduction each step with O.dt, and a run whose O.dt is
    above the stable conduction step stops with a message; in (0, 1] (default 0.8, as Yade),
    conduction every ``getConductionIterPeriod()`` steps over the time elapsed, the period chosen
    so that this stays below tsSafetyFactor x the stable step, and in sub-steps of that size when
    it is below O.dt (where Yade would run one unstable step). The stable step is
    min_i C_i / sum_j G_ij (``getMaxTimeStep()``).

    Outputs: ``thermalBndFlux`` (W into each boundary's particles during the last conduction
    step, positive when the packing is hotter; Yade's), ``thermalBndHeat`` (J received by each
    boundary since the start; Talus), VTKRecorder's ``thermal`` recorder (``temp``, ``k``, ``Cp``
    in the sphere file), checkpoints (O.save keeps the temperatures)."""

    def __init__(self, scene=None, **attrs):
        """``scene``: the talus.dem scene the engine acts on (default ``talus.dem.O``); the other
        keywords set Yade's attributes."""
        self._scene = scene
        self._params = _defaults()
        self._conduction = None      # the C++ state, made on first use (it needs the scene)
        self._expansion = None       # the thermal expansion's per-body state, made with it
        self._schedule = _flow.ConductionSchedule()
        self._started = False
        self._marked = False         # the expansion's reference temperatures are taken
        self._pendingState = None    # a checkpoint's state, applied once the scene is known
        self._poreHeat = None        # (FlowEngine, its pore temperatures) with advection
        self._pendingPores = None    # a checkpoint's pore centres and temperatures
        # each step reads many parameters: they go to the C++ state only when they changed since
        self._version = 0            # changes of the attributes so far
        self._pushed = -1            # the version the C++ state has
        self._fluidKey = None        # what the pore fluid's parameters were made of
        # every refusal comes before any temperature changes: a failed step can be resumed
        self._cpp = PyRunner(step_of(self, "_step"), iterPeriod=1, initRun=True)._cpp
        for name, value in attrs.items():
            setattr(self, name, value)
        self._constructed = True    # an unknown attribute from now on: see stray_attributes

    # --- Yade's attributes ----------------------------------------------------------------
    def __setattr__(self, name, value):
        if name.startswith("_") or isinstance(getattr(type(self), name, None), property):
            object.__setattr__(self, name, value)
            return
        if name not in self._params:
            stray_attributes.refuse_or_keep(self, "ThermalEngine", name, value, self._params)
            return
        value = _check(name, value)
        if name in _PLANNED_SWITCHES and value:
            raise _planned(name)
        if name in ("bndCondIsTemperature", "thermalBndCondValue"):
            _check_sides(**{**{n: self._params[n] for n in ("bndCondIsTemperature", "thermalBndCondValue")},
                            name: value})
        self._params[name] = value
        object.__setattr__(self, "_version", self._version + 1)

    def __getattr__(self, name):
        params = object.__getattribute__(self, "_params")
        if name in params:
            value = params[name]
            return list(value) if isinstance(value, list) else value
        raise AttributeError(f"ThermalEngine has no attribute {name!r}")

    @property
    def thermalBndFlux(self) -> list[float]:
        """Heat rate (W) into each boundary's particles during the last conduction step."""
        return [0.0] * 6 if self._conduction is None else list(self._conduction.boundaryFlux())

    @property
    def thermalBndHeat(self) -> list[float]:
        """Heat (J) received by each boundary's particles since the start (Talus)."""
        return [0.0] * 6 if self._conduction is None else list(self._conduction.boundaryHeat())

    @property
    def lenBodies(self) -> int:
        """Bodies the per-body arrays cover (Yade's)."""
        return 0 if self._conduction is None else len(self._conduction.boundaries())

    def getThermalDT(self) -> float:
        """Time covered by the last conduction run (Yade's)."""
        return self._schedule.thermalDT()

    def getMaxTimeStep(self) -> float:
        """Stable conduction step at the last run: min_i C_i / sum_j G_ij (Yade's)."""
        return self._schedule.maxTimeStep()

    def getConductionIterPeriod(self) -> int:
        """DEM steps between conduction runs (Yade's)."""
        return self._schedule.conductionIterPeriod()

    def checkThermal(self) -> bool:
        """Yade's: whether every body has a thermal state. Always True in Talus: every body has
        the DEM's heat fields."""
        return True

    def makeThermal(self) -> None:
        """Yade's: give bodies thermal states. Nothing to do in Talus (see checkThermal)."""

    def setReynoldsNumbers(self) -> None:
        """Yade's: with ``uniformReynolds`` = -1, compute the pores' Reynolds and Nusselt numbers
        again (from the current velocities) at the next step; otherwise nothing to do (the
        uniform number is applied at each step)."""
        if self._poreHeat is not None:
            self._poreHeat[1].resetPoreNusselt()

    # --- the engine's action --------------------------------------------------------------
    def _scene_(self):
        from talus.dem import O
        return self._scene or O

    def _state(self):
        """The C++ per-body state, made on first use with the current defaults."""
        if self._conduction is None:
            self._conduction = _flow.ParticleConduction(self._scene_()._cpp)
            self._expansion = _flow.ThermalExpansion(self._conduction, self._scene_()._cpp)
            self._push_parameters()
            if self._pendingState is not None:
                self._restore(self._pendingState)
                self._pendingState = None
        return self._conduction

    def _push_parameters(self):
        self._pushed = self._version
        p, c = self._params, self._conduction
        c.initialTemperature = p["particleT0"]
        c.defaultConductivity = p["particleK"]
        c.defaultHeatCapacity = p["particleCp"]
        c.particleDensity = p["particleDensity"]
        c.conductance = _flow.ContactConductance.Kern if p["useKernMethod"] else _flow.ContactConductance.Radii
        self._schedule.tsSafetyFactor = p["tsSafetyFactor"]
        e = self._expansion
        e.defaultAlpha = p["particleAlpha"]
        expansion = e.params
        expansion.particles = p["thermoMech"]
        expansion.solidVolume, expansion.fluid = p["solidThermoMech"], p["fluidThermoMech"]
        expansion.fluidBeta, expansion.porosityFactor = p["fluidBeta"], p["porosityFactor"]
        e.params = expansion

    def _start(self, scene):
        """First step: refuse the planned physics left on, and give every body Yade's initial
        values (particleT0, particleK, particleCp, particleAlpha) where its fields are not given
        (Yade overwrites them all; Talus keeps values set by hand or by another component)."""
        on = [name for name in _PLANNED_SWITCHES if self._params[name]]
        if on:
            raise NotImplementedError(
                "ThermalEngine: " + "; ".join(f"{n} ({_PLANNED_SWITCHES[n][1]})" for n in on) + " not implemented yet "
                "in Talus (planned, docs/thermal.md). Yade's defaults switch them on: set "
                + ", ".join(f"{n}=False" for n in on))
        if self._params["fluidConduction"] and not self._params["advection"]:
            raise ValueError("ThermalEngine.fluidConduction needs advection=True: conduction through the fluid acts on "
                             "the pore temperatures, which exist with advection (Yade does nothing then); set "
                             "fluidConduction=False, or advection=True")
        if self._params["advection"]:
            if self._params["fluidK"] <= 0:
                raise ValueError(f"ThermalEngine.fluidK = {self._params['fluidK']}: the fluid's conductivity must be > 0 "
                                 "with advection (its Prandtl number divides by it)")
            self._flow_engine(scene, "ThermalEngine.advection")
        self._state()
        self._expansion.resize()
        if self._params["thermoMech"]:
            self._warn_expansion_without_pores(scene)
        self._started = True

    def _warn_expansion_without_pores(self, scene):
        """thermoMech acts on the pores only where they exist: say which part has nothing to act on."""
        from talus.flow.pore import FlowEngine
        p = self._params
        if p["fluidThermoMech"] and p["fluidBeta"] > 0 and not p["advection"]:
            warnings.warn("ThermalEngine.fluidThermoMech: the pore fluid has no temperature without advection=True, so "
                          "it does not expand (as in Yade); set fluidThermoMech=False to silence this", RuntimeWarning,
                          stacklevel=3)
        if p["solidThermoMech"] and p["particleAlpha"] > 0 and not any(isinstance(e, FlowEngine) for e in scene.engines):
            warnings.warn("ThermalEngine.solidThermoMech: O.engines has no FlowEngine, so the particles grow but no pore "
                          "volume changes; set solidThermoMech=False to silence this", RuntimeWarning, stacklevel=3)

    def _set_boundaries(self, scene):
        """Hold the spheres of each temperature boundary (Yade's setConductionBoundary), and give
        the heat flux of the others with a non-zero value (Talus's addition: Yade leaves them
        insulated) to the same spheres, shared in proportion to their cross-sections pi r²: side
        k receives thermalBndCondValue[k] x its area, that of the FlowEngine's box face."""
        c = self._state()
        c.clearBoundaries()
        held, values = self._params["bndCondIsTemperature"], self._params["thermalBndCondValue"]
        wanted = [k for k in range(6) if held[k] or values[k] != 0]
        if wanted:
            flow = self._flow_engine(scene)
            for k in wanted:
                ids = flow._flow.boundarySphereIds(k)
                if held[k]:
                    c.imposeTemperature(k, ids, values[k])
                else:
                    c.imposeHeatFlux(k, ids, self._flux_rates(scene, flow, k, ids))
        self._params["boundarySet"] = True

    _warned_flux = False   # the flux boundary's warning is printed once per session

    def _flux_rates(self, scene, flow, k, ids) -> np.ndarray:
        if not ThermalEngine._warned_flux:
            ThermalEngine._warned_flux = True
            warnings.warn("ThermalEngine.thermalBndCondValue on a side with bndCondIsTemperature False is applied as a "
                          "heat flux, W/m² into the packing (Talus's addition: Yade ignores it)", RuntimeWarning,
                          stacklevel=4)
        position = np.asarray(flow._flow.boundaryPositions())
        others = [a for a in range(3) if a != k // 2]
        area = np.prod([position[2 * a + 1] - position[2 * a] for a in others])
        weight = np.asarray(scene._cpp.radius())[np.asarray(ids, dtype=int)] ** 2
        return self._params["thermalBndCondValue"][k] * area * weight / weight.sum()

    @staticmethod
    def _has_flow(scene) -> bool:
        from talus.flow.pore import FlowEngine
        return any(isinstance(e, FlowEngine) and e.nCells() > 0 for e in scene.engines)

    @staticmethod
    def _flow_engine(scene, what="ThermalEngine.bndCondIsTemperature"):
        from talus.flow.pore import FlowEngine
        flows = [e for e in scene.engines if isinstance(e, FlowEngine)]
        if not flows:
            raise ValueError(f"{what}: temperature boundaries and pore temperatures live on the triangulation of a "
                             "FlowEngine, and O.engines has no FlowEngine (add one, dead after flow.emulateAction() if "
                             "no flow is wanted, as in Yade's examples)")
        if flows[0].nCells() == 0:
            raise ValueError(f"{what}: the FlowEngine has not triangulated the packing yet: put it before the "
                             "ThermalEngine in O.engines or call flow.emulateAction() first")
        return flows[0]

    def _model(self, scene):
        """What the schedule advances: the spheres alone, or with the pore fluid (advection)."""
        c = self._state()
        if not self._params["advection"]:
            return c
        flow = self._flow_engine(scene, "ThermalEngine.advection")
        if self._poreHeat is None or self._poreHeat[0] is not flow:
            heat = _flow.PoreHeat(c, flow._flow)
            heat.initialTemperature = flow.tZero
            self._poreHeat = (flow, heat)
            self._fluidKey = None
            flow._poreHeat = heat
            if self._pendingPores is not None:
                self._restore_pores(flow, heat, *self._pendingPores)
                self._pendingPores = None
        heat, p = self._poreHeat[1], self._params
        fluidAttributes = flow._thermal   # FlowEngine's own values (its attributes return copies)
        held, values = fluidAttributes["bndCondIsTemperature"], fluidAttributes["thermalBndCondValue"]
        key = (self._version, flow.viscosity, fluidAttributes["fluidCp"], fluidAttributes["fluidRho"],
               fluidAttributes["thermalPorosity"], *held, *values)
        for k in range(6):   # in this order at every step: a pore of two sides follows the later one
            heat.setBoundary(k, held[k], values[k])
        if key == self._fluidKey and p["uniformReynolds"] >= 0:
            return heat
        self._fluidKey = key
        fluid = heat.params
        fluid.fluidK, fluid.fluidCp, fluid.fluidRho = p["fluidK"], flow.fluidCp, flow.fluidRho
        prandtl = flow.fluidCp * flow.viscosity / p["fluidK"]
        fluid.poreReynolds = p["uniformReynolds"] < 0
        if fluid.poreReynolds:
            fluid.porosity = _porosity(scene)
        else:
            # Yade's Nusselt number for uniformReynolds (Ranz-Marshall, with its exponent 0.33333)
            fluid.nusseltK = (2 + 0.6 * p["uniformReynolds"] ** 0.5 * prandtl ** 0.33333) * p["fluidK"]
        fluid.advection, fluid.fluidConduction = True, p["fluidConduction"]
        fluid.ignoreFictitious = p["ignoreFictiousConduction"]
        fluid.areaFactor, fluid.minimumDistance = p["fluidConductionAreaFactor"], p["minimumFluidCondDist"]
        fluid.thermalPorosity = flow.thermalPorosity
        heat.params = fluid
        return heat

    def _step(self):
        scene = self._scene_()
        c = self._state()
        if self._pushed != self._version:
            self._push_parameters()
        if not self._started:
            self._start(scene)
        self._expansion.resize()   # the bodies added since the last step get the defaults
        if not self._params["boundarySet"]:
            self._set_boundaries(scene)
        model = self._model(scene) if self._params["conduction"] else None
        fluid = self._poreHeat[1] if self._poreHeat is not None and model is self._poreHeat[1] else None
        expand = self._params["thermoMech"] and model is not None
        if expand and not self._marked:
            if fluid is not None:
                fluid.sync()
            self._expansion.mark(fluid)
            self._marked = True
        runs = self._schedule.counters().runs
        if model is not None:
            self._schedule.step(model, scene.dt)
        if self._params["delT"] != 0:   # once, to the free spheres, after conduction (Yade's delT)
            free = np.flatnonzero(np.asarray(c.boundaries()) < 0)
            scene._cpp.temperature()[free] += self._params["delT"]
            self._params["delT"] = 0.0
        if expand and self._schedule.counters().runs != runs:
            # after the temperatures and delT of this run, as Yade's thermalExpansion
            flow = self._flow_engine(scene, "ThermalEngine.solidThermoMech") if fluid is not None or (
                self._params["solidThermoMech"] and self._has_flow(scene)) else None
            self._expansion.apply(self._schedule.thermalDT(), fluid, flow._flow if flow is not None else None)

    # --- per-body fields ------------------------------------------------------------------
    def _heatDefaults(self) -> dict:
        """What a body whose heat field is not given has (talus.dem.core.heat): the values this
        engine gives at its steps."""
        p = self._params
        return {"temp": p["particleT0"], "k": p["particleK"], "Cp": p["particleCp"], "alpha": p["particleAlpha"]}

    def _bodyFields(self):
        def refuse(i, value):
            raise AttributeError("state.Tcondition is set by ThermalEngine.bndCondIsTemperature, not per body")

        c = self._state()

        def held(i):
            self._scene_()._cpp.checkBody(i)
            return c.boundaryAt(i) >= 0
        return {"Tcondition": (held, refuse)}

    # --- checkpoints ------------------------------------------------------------------------
    def _io_params(self):
        # what differs from Yade's defaults (those of the planned switches are refused when given)
        defaults = _defaults()
        return {"label": self.label, **{name: value for name, value in self._params.items()
                                        if name not in ("boundarySet", "delT") and value != defaults[name]}}

    def _io_state(self):
        if self._conduction is None:
            return {}
        # the temperatures, k, Cp and alpha are the DEM's, kept by its checkpoint
        c, n = self._conduction, self._schedule.counters()
        return {"boundary": [int(b) for b in c.boundaries()], "heat": list(c.boundaryHeat()),
                "heatFlux": [[[int(i), float(q)] for i, q in c.heatFlux(k)] for k in range(6)],
                "started": self._started, "boundarySet": self._params["boundarySet"],
                "values": list(self._params["thermalBndCondValue"]),
                "counters": [n.runs, n.sinceRun, n.period, n.timeSinceRun, n.thermalDT, n.maxTimeStep],
                "marks": _encode(self._expansion.marks()),
                "marked": self._marked, **self._io_pores()}

    def _io_pores(self) -> dict:
        """The pore temperatures with a point inside each pore: the FlowEngine rebuilds its network
        after a load, and each new pore takes the temperature of the saved pore whose point is
        nearest to its own (the same pore when the spheres are where they were saved; not the
        pores' circumcentres, which cospherical spheres share)."""
        if self._poreHeat is None:
            return {}
        flow, heat = self._poreHeat
        return {"poreTemp": _encode(heat.temperatures()), "poreCentre": _encode(np.ravel(self._pore_points(flow)))}

    @staticmethod
    def _pore_points(flow) -> np.ndarray:
        return np.array([flow._flow.poreBarycentre(i) for i in range(flow.nCells())])

    @staticmethod
    def _restore_pores(flow, heat, centres, temps):
        from scipy.spatial import cKDTree
        heat.sync()
        nearest = cKDTree(centres).query(ThermalEngine._pore_points(flow))[1]
        for i, j in enumerate(nearest):
            heat.setTemperature(i, float(temps[j]))

    def _io_restore(self, state):
        if state:
            self._pendingState = state
            self._conduction = None

    def _restore(self, state):
        c, cpp = self._conduction, self._scene_()._cpp
        # checkpoints written when the engine held the bodies' heat have it here
        for key in ("temp", "k", "Cp", "alpha"):
            if key in state:
                saved, field = _decode(state[key]), getattr(cpp, body_heat.FIELDS[key])()
                if len(saved) != len(field):
                    raise ValueError(f"ThermalEngine: the checkpoint holds {key} for {len(saved)} bodies, the scene "
                                     f"has {len(field)}")
                field[:] = saved
        c.resize()
        n = len(c.boundaries())
        boundary = np.asarray(state["boundary"])
        for k in range(6):
            ids = [int(i) for i in np.flatnonzero(boundary == k)]
            if ids:
                c.imposeTemperature(k, ids, state["values"][k])
        for k, flux in enumerate(state.get("heatFlux", [])):
            if flux:
                c.imposeHeatFlux(k, [int(i) for i, _ in flux], [q for _, q in flux])
        c.setBoundaryHeat(state["heat"])
        counters = _flow.ConductionCounters()
        (counters.runs, counters.sinceRun, counters.period, counters.timeSinceRun, counters.thermalDT,
         counters.maxTimeStep) = state["counters"]
        self._schedule.setCounters(counters)
        self._started = state["started"]
        self._params["boundarySet"] = state["boundarySet"]
        e = self._expansion
        e.resize()
        saved = _decode(state["marks"])
        if len(saved) != n:
            raise ValueError(f"ThermalEngine: the checkpoint holds marks for {len(saved)} bodies, the scene has {n}")
        e.setMarks(saved)
        if "poreTemp" in state:
            self._pendingPores = (_decode(state["poreCentre"]).reshape(-1, 3), _decode(state["poreTemp"]))
        # the pores' reference temperatures are not kept: the first run after a load marks them anew
        self._marked = state["marked"] and not self._params["fluidThermoMech"]
