"""Pore-scale finite-volume flow in a sphere packing (Yade's ``FlowEngine``, the PFV scheme of
Chareyre et al. 2012 and Catalano et al. 2014).

The packing is triangulated (CGAL regular triangulation, weights r²) together with six huge
fictitious spheres standing for the sides of the box; pores are tetrahedra, throats the facets
between them. Each throat gets Yade's conductance

    k = permeabilityFactor * A_f * (2 R_h)² / (8 μ L)

(A_f fluid area of the facet, R_h hydraulic radius = void volume / solid surface of the region
between the facet and the two pore centres, L the distance between the pore centres), clamped to
[minKdivKmean, maxKdivKmean] × a global reference value when ``clampKValues``. The pore
pressures solve Σ_j k_ij (p_i − p_j) = 0 with imposed pressures on the boundaries whose
``bndCondIsPressure`` is set (no flux on the others; with none and an incompressible fluid the
net volume change must be zero and the mean pressure is ``pZero``), by CHOLMOD (``useSolver=3``, the factor is
kept until the mesh or the boundary types change), Gauss–Seidel (``useSolver=0``) or, a Talus
addition, conjugate gradients preconditioned by algebraic multigrid (``useSolver=4``, Talus's
aggregation multigrid, or ``useSolver=5``, hypre's BoomerAMG, faster: no factor, for large
networks remeshed often or too large for a factor).

Attribute and method names are Yade's. Boundaries are numbered as Yade's ``wallIds``: 0 xmin,
1 xmax, 2 ymin, 3 ymax, 4 zmin, 5 zmax. Sign convention of ``getBoundaryFlux`` as Yade: the sum of
the fluxes the boundary pores receive, negative where fluid enters. See ``docs/flow.md``,
section "Pore-scale flow".

    from talus.flow import FlowEngine
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0])
    flow.triangulate(positions, radii)      # or flow.triangulateScene(O)
    flow.solve()
    print(flow.getBoundaryFlux(2), flow.samplePermeability(2, 3))
"""

from __future__ import annotations

import math
import os
import warnings
from typing import Sequence

import numpy as np

from talus import _flow
from talus.dem.step.engines import Engine, PyRunner, asCallback
from talus.flow import stray_attributes
from talus.flow.step_callback import step_of

_BOUNDARY_LISTS = ("bndCondIsPressure", "bndCondValue", "boundaryUseMaxMin", "wallPosition")
# engine step counts and their smallest allowed values (None: any; meshUpdateInterval <= 0 never
# remeshes by count, as Yade)
_ENGINE_COUNTS = {"meshUpdateInterval": None, "backgroundSteps": 0}
# engine flags and their defaults: decoupleForces keeps the fluid forces off the bodies; debug
# (Yade's debug messages) and getCHOLMODPerfTimings (Yade prints its CHOLMOD timings; Talus's
# are in solverStats()) print nothing; permeabilityMap (Yade's per-pore permeability in
# the cell data) is not implemented, True is refused
_ENGINE_FLAGS = {"decoupleForces": False, "debug": False, "getCHOLMODPerfTimings": False, "permeabilityMap": False}
_SCALARS = ("permeabilityFactor", "viscosity", "clampKValues", "minKdivKmean", "maxKdivKmean",
            "slipBoundary", "useSolver", "tolerance", "multigridTolerance", "relax",
            "fluidBulkModulus", "yadeInsertionOrder",
            "concurrentTriangulation",
            "viscousShear", "shearLubrication", "normalLubrication", "eps", "stiffness", "pZero",
            "alphaBound", "alphaBoundValue")

# Yade's FlowEngine attributes of the thermal coupling (the pore temperatures ThermalEngine
# advances when its ``advection`` is on) and their defaults
_THERMAL_ATTRIBUTES = {"thermalEngine": False, "tZero": 0.0, "fluidRho": 1000.0, "fluidCp": 4181.3,
                       "bndCondIsTemperature": [False] * 6, "thermalBndCondValue": [0.0] * 6,
                       "thermalPorosity": 0.0, "tempDependentViscosity": False}

# the real numbers among them (the others are flags and the solver's number)
_REALS = ("permeabilityFactor", "viscosity", "minKdivKmean", "maxKdivKmean", "tolerance", "multigridTolerance",
          "relax", "fluidBulkModulus", "eps", "stiffness", "pZero", "alphaBound", "alphaBoundValue")


def _finite_number(name: str, value) -> float:
    """A real parameter: an infinite permeabilityFactor, say, would give NaN pressures."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number) or isinstance(value, (str, bytes)):
        raise ValueError(f"FlowEngine.{name} must be a finite number, got {value!r}")
    return number


def _boundary_list(name: str, value) -> list:
    """One of the six-boundary lists: finite numbers (bndCondValue, wallPosition) or flags
    (True/False or 1/0: a string such as 'abcdef' would read as six True)."""
    values = [value] if isinstance(value, (str, bytes)) else list(value)
    if len(values) != 6:
        raise ValueError(f"FlowEngine.{name} needs a list of 6 values (xmin, xmax, ymin, ymax, zmin, zmax), "
                         f"got {value!r}")
    if name in ("bndCondValue", "wallPosition"):
        numbers = [float(v) for v in values]
        if not all(math.isfinite(v) for v in numbers):
            raise ValueError(f"FlowEngine.{name} must be 6 finite numbers, got {value!r}")
        return numbers
    if not all(isinstance(v, (bool, int, np.integer, np.bool_)) and v in (0, 1) for v in values):
        raise TypeError(f"FlowEngine.{name} must be a list of 6 booleans (True/False or 1/0), got {value!r}")
    return [bool(v) for v in values]


def _thermal_value(name: str, value):
    """A thermal attribute checked as Yade's type and physics allow."""
    if name in ("bndCondIsTemperature", "thermalBndCondValue"):
        values = _boundary_list("bndCondValue" if name == "thermalBndCondValue" else "bndCondIsPressure", value)
        if name == "thermalBndCondValue" and min(values) < -273.15:
            raise ValueError(f"FlowEngine.thermalBndCondValue = {value!r}: below absolute zero (-273.15 °C, 0 K)")
        return values
    if name in ("thermalEngine", "tempDependentViscosity"):
        if not isinstance(value, (bool, int, np.integer, np.bool_)) or value not in (0, 1):
            raise TypeError(f"FlowEngine.{name} must be True or False, got {value!r}")
        if name == "tempDependentViscosity" and value:
            raise NotImplementedError("FlowEngine.tempDependentViscosity: a temperature-dependent viscosity is not "
                                      "implemented yet in Talus (planned, docs/thermal.md)")
        return bool(value)
    number = _finite_number(name, value)
    if name == "tZero" and number < -273.15:
        raise ValueError(f"FlowEngine.tZero = {number}: below absolute zero (-273.15 °C, 0 K)")
    if name in ("fluidRho", "fluidCp") and number <= 0:
        raise ValueError(f"FlowEngine.{name} must be > 0, got {number}")
    if name == "thermalPorosity" and not 0 <= number <= 1:
        raise ValueError(f"FlowEngine.thermalPorosity must be in [0, 1] (0: the pores' void volume), got {number}")
    return number


class HiddenSphereWarning(UserWarning):
    """Spheres the regular triangulation dropped (inside the power cells of their neighbours):
    they carry no pore and receive no fluid force."""


class FlowEngine(Engine):
    """Pore-scale flow model with Yade's FlowEngine names (see the module docstring).

    Used standalone (``triangulate`` + ``solve``) or, as in Yade, as an engine of ``O.engines``
    between the ForceResetter and the NewtonIntegrator: each step it reads the spheres of
    ``talus.dem.O`` through the particle exchange interface, re-triangulates every
    ``meshUpdateInterval`` steps (or when ``updateTriangulation`` is set), solves the pressures
    and adds the fluid forces to the bodies; ``wallIds[k]`` (default -1: none) names the wall
    body that receives the force of boundary k.

    Parameters (Yade's defaults): ``bndCondIsPressure`` [0]*6, ``bndCondValue`` [0]*6,
    ``boundaryUseMaxMin`` [1]*6 (boundary at the packing's extreme x±r; else at
    ``wallPosition[k]``), ``permeabilityFactor`` 1, ``viscosity`` 1, ``clampKValues`` True,
    ``minKdivKmean`` 1e-4, ``maxKdivKmean`` 100, ``slipBoundary`` True (no-flux walls are not
    solid surface in the hydraulic radius), ``useSolver`` 3 (Talus: 4 multigrid, 5 hypre's BoomerAMG), ``tolerance`` 1e-6 and ``relax`` 1.9 (Gauss–Seidel only),
    ``multigridTolerance`` 1e-8 (Talus: the relative residual at which ``useSolver`` 4 and 5 stop; pressures
    within 1e-6 of CHOLMOD's largest, boundary fluxes within 1e-7 of CHOLMOD's),
    ``fluidBulkModulus`` 0 (incompressible; > 0: transient storage V_void / (K_f dt)), ``yadeInsertionOrder``
    True (Talus: the spheres enter the triangulation one by one and each cell keeps CGAL's vertex order, as
    Yade's: the same numbers as Yade to round-off; False inserts them as one spatially sorted range, faster
    from about 30 000 spheres, and takes the vertices in a canonical order: the wall pores' centres then
    carry other round-off, the permeability up to 5e-4 from Yade's at 200 000 spheres),
    ``concurrentTriangulation`` False (Talus: True, with ``yadeInsertionOrder`` False, lets CGAL insert the spheres of a box network on
    the OpenMP threads when there are several; the results then differ from a one-thread run's by
    round-off; False gives the same bits at any thread count), and for the engine
    ``meshUpdateInterval`` 1000 (<= 0: never by count), ``decoupleForces`` False (True: the fluid forces are
    not added to the bodies), ``pZero`` 0 (pressure of the first network's pores: the initial pressure of
    a compressible fluid; the mean pressure of an incompressible one that no boundary drains), ``debug`` False (no effect), ``defTolerance`` 0 (off, as Yade; > 0: remesh when a pore's volume changed by more than this
    fraction since the mesh; an inverted pore always remeshes), ``blockHook`` (callable or command string run
    after each remesh, before the solve), ``multithread`` False (Yade's name: build due meshes and their
    CHOLMOD factor in a second thread while the old mesh keeps being used) with ``backgroundSteps`` 10 (Talus:
    the new mesh, of the positions when the remesh fell due, replaces the old one exactly this many steps
    later, waiting for the thread if needed, so results do not depend on thread timing; 0 gives the results of
    ``multithread`` False). Between remeshes the engine moves the network's spheres each step:
    the pores' volume changes drive the flow (consolidation), see ``moveVertices``.

    Viscous forces between neighbouring spheres (pairs joined by an edge of the triangulation),
    from their relative velocities, added by the engine after the solve (Yade's options, all off
    by default): ``viscousShear`` (tangential force μ Δv_t A / R_h, A the power-diagram face of
    the pair, R_h = gap + 0.45 min(r1, r2)), ``shearLubrication`` (tangential lubrication force
    (π μ / 2)(−2R + L ln(L/h)) Δv_t instead), ``normalLubrication`` (3π R² μ Δv_n / (2h), in
    series with a spring ``stiffness`` × R when ``stiffness`` > 0, default 10000), ``eps``
    1e-5 (roughness: h = max(gap, 0) + 2 eps R). Standalone: ``computeViscousForces``. See
    ``docs/flow.md``.
    """

    def __init__(self, scene=None, **attrs):
        """``scene``: the talus.dem scene the engine acts on when in its engine list (default
        ``talus.dem.O``); the other keywords set attributes."""
        self._scene = scene
        self._flow = _flow.PoreFlow()
        self._coupling = None
        self._wallIds = None        # Yade's default, bodies 0..5 (see _wall_ids)
        self._meshUpdateInterval = 1000
        self._defTolerance = 0.0
        self._blockHook = None
        self._multithread = False
        self._fixedAlpha = False
        self._backgroundSteps = 10
        self._rebuild = False
        self._flags = dict(_ENGINE_FLAGS)
        self._thermal = {k: (list(v) if isinstance(v, list) else v) for k, v in _THERMAL_ATTRIBUTES.items()}
        self._poreHeat = None       # the pore temperatures, attached by a ThermalEngine with advection
        self._cpp = PyRunner(step_of(self, "_step"), iterPeriod=1, initRun=True)._cpp  # from the first step on, as Yade's FlowEngine
        self._cpp.resumable = False   # a failed solve leaves the step without its fluid forces
        for name, value in attrs.items():
            setattr(self, name, value)
        self._constructed = True    # an unknown attribute from now on: see stray_attributes

    # --- parameters: plain attributes mirrored into the C++ parameters -------------------
    def __setattr__(self, name, value):
        if name.startswith("_") or isinstance(getattr(type(self), name, None), property):
            object.__setattr__(self, name, value)
            return
        if name == "wallIds":
            ids = [int(v) for v in value]
            if len(ids) != 6:
                raise ValueError("FlowEngine.wallIds needs 6 body ids (-1: none)")
            self._wallIds = ids
            return
        if name in _ENGINE_COUNTS:
            if _ENGINE_COUNTS[name] is not None and int(value) < _ENGINE_COUNTS[name]:
                raise ValueError(f"FlowEngine.{name} must be >= {_ENGINE_COUNTS[name]}")
            object.__setattr__(self, "_" + name, int(value))
            return
        if name in _ENGINE_FLAGS:
            if name == "permeabilityMap" and value:
                raise ValueError("FlowEngine.permeabilityMap = True (Yade's average permeability stored per pore) "
                                 "is not implemented in Talus")
            self._flags[name] = bool(value)
            return
        if name == "updateTriangulation":
            self._rebuild = bool(value)
            return
        if name == "defTolerance":
            self._defTolerance = float(value)
            return
        if name == "multithread":
            self._multithread = bool(value)
            return
        if name == "fixedAlpha":
            # Yade's other sizing of the alpha vertices (one size, over every boundary facet)
            if value:
                raise ValueError("FlowEngine.fixedAlpha = True (Yade's constant-size alpha vertices) is not implemented "
                                 "in Talus: its alpha vertices are those of fixedAlpha False (docs/flow.md)")
            self._fixedAlpha = False
            return
        if name == "blockHook":
            if value and not (callable(value) or isinstance(value, str)):
                raise ValueError("FlowEngine.blockHook must be a callable or a Python command string")
            self._blockHook = value
            return
        params = self._flow.params
        if name in _BOUNDARY_LISTS:
            setattr(params, name, _boundary_list(name, value))
        elif name in _SCALARS:
            if name == "useSolver" and int(value) not in (0, 3, 4, 5):
                raise ValueError("FlowEngine.useSolver must be 0 (Gauss-Seidel) or 3 (CHOLMOD), or Talus's 4 (multigrid) "
                                 "or 5 (hypre's BoomerAMG)")
            setattr(params, name, _finite_number(name, value) if name in _REALS else value)
        elif name in _THERMAL_ATTRIBUTES:
            self._thermal[name] = _thermal_value(name, value)
            return
        else:
            known = (*_BOUNDARY_LISTS, *_SCALARS, *_ENGINE_COUNTS, *_ENGINE_FLAGS, *_THERMAL_ATTRIBUTES, "wallIds",
                     "updateTriangulation", "defTolerance", "multithread", "blockHook", "fixedAlpha")
            stray_attributes.refuse_or_keep(self, "FlowEngine", name, value, known)
            return
        self._flow.params = params
        if name == "alphaBound":
            self._rebuild = True  # the alpha vertices are part of the mesh

    def __getattr__(self, name):
        if name == "wallIds":
            ids = object.__getattribute__(self, "_wallIds")
            return list(range(6)) if ids is None else list(ids)
        if name == "meshUpdateInterval":
            return self._meshUpdateInterval
        if name == "updateTriangulation":
            return self._rebuild
        if name in _ENGINE_FLAGS:
            return object.__getattribute__(self, "_flags")[name]
        if name in ("defTolerance", "blockHook", "multithread", "backgroundSteps", "fixedAlpha"):
            return object.__getattribute__(self, "_" + name)
        if name in _THERMAL_ATTRIBUTES:
            value = object.__getattribute__(self, "_thermal")[name]
            return list(value) if isinstance(value, list) else value
        if name in _BOUNDARY_LISTS or name in _SCALARS:
            value = getattr(self._flow.params, name)
            return list(value) if name in _BOUNDARY_LISTS else value
        raise AttributeError(f"FlowEngine has no attribute {name!r}")

    # --- building and solving -------------------------------------------------------------
    def triangulate(self, positions, radii, ids: Sequence[int] | None = None):
        """Build the pore network of spheres (positions (n, 3), radii (n,)); ``ids`` name them in
        messages and results (default 0..n-1). Warns (HiddenSphereWarning) with the body ids of
        spheres the triangulation dropped; raises ValueError for fewer than 4 spheres, NaN
        positions or a sphere centre outside the boundaries."""
        pos = np.asarray(positions, dtype=float)
        rad = np.asarray(radii, dtype=float).reshape(-1)
        if pos.ndim != 2 or pos.shape[1] != 3 or len(pos) != len(rad):
            raise ValueError(f"FlowEngine.triangulate: positions must be (n, 3) with one radius each, got positions "
                             f"of shape {pos.shape} and {len(rad)} radii")
        ident = np.arange(len(rad), dtype=np.int64) if ids is None else np.asarray(ids, dtype=np.int64)
        self._flow.build(pos, rad, ident)
        hidden = self._flow.hiddenSpheres()
        if hidden:
            warnings.warn(f"FlowEngine: the regular triangulation dropped hidden spheres (body ids {hidden}); "
                          "they get no pore and no fluid force", HiddenSphereWarning, stacklevel=2)

    def triangulateScene(self, scene):
        """Build the network of the live spheres of a talus.dem scene (ids = body ids)."""
        ids = scene.sphere_ids()
        pos = np.asarray(scene.positions())[ids]
        rad = np.asarray(scene.radii())[ids]
        self.triangulate(pos, rad, ids)

    def _wall_ids(self, scene) -> list[int]:
        """The wall bodies of the boundaries: those set, else Yade's default 0..5 (aabbWalls
        appended before the spheres) when bodies 0..5 are walls or boxes; otherwise none, with a
        warning: Yade would give the boundary forces to whatever bodies 0..5 are."""
        if self._wallIds is not None:
            return self._wallIds
        # looked up again only when bodies were added or erased (each step it cost as much as the solve)
        version = scene._cpp.bodiesVersion
        if getattr(self, "_defaultWalls", (None, None))[0] == version:
            return self._defaultWalls[1]
        kinds = [type(scene.bodies[i].shape).__name__ if i < len(scene.bodies) and scene.bodies[i] is not None
                 else None for i in range(6)]
        if all(kind in ("Wall", "Box") for kind in kinds):
            self._defaultWalls = (version, list(range(6)))
            return list(range(6))
        if not getattr(self, "_warnedNoWalls", False):
            self._warnedNoWalls = True
            warnings.warn("FlowEngine: bodies 0..5 are not six walls or boxes (" + ", ".join(map(str, kinds))
                          + "), as Yade's default wallIds assume: no body receives the boundary forces "
                          "(set FlowEngine.wallIds)", RuntimeWarning, stacklevel=2)
        self._defaultWalls = (version, [-1] * 6)
        return [-1] * 6

    def _step(self):
        """The engine's action: the C++ coupling on the running scene (talus.dem.O)."""
        from talus.dem import O
        if self._coupling is None:
            self._coupling = _flow.PoreFlowCoupling((self._scene or O)._cpp, self._flow)
            self._couplingSettings = None
        # given to the coupling when they changed (each step costs as much as a small solve)
        settings = (self._wall_ids(self._scene or O), self._meshUpdateInterval, self._defTolerance, self._multithread,
                    self._backgroundSteps, self._flags["decoupleForces"], self._blockHook)
        if settings != self._couplingSettings:
            c = self._coupling
            c.wallIds, c.meshUpdateInterval, c.defTolerance, c.multithread, c.backgroundSteps = settings[:5]
            c.decoupleForces = settings[5]
            c.blockHook = asCallback(self._blockHook, "blockHook")
            self._couplingSettings = settings
        if self._rebuild:
            self._coupling.requestRebuild()
            self._rebuild = False
        self._coupling.step()
        rebuilds = self._coupling.rebuilds()
        if rebuilds != getattr(self, "_warned", 0):
            self._warned = rebuilds
            hidden = self._flow.hiddenSpheres()
            if hidden:
                warnings.warn(f"FlowEngine: the regular triangulation dropped hidden spheres (body ids {hidden}); "
                              "they get no pore and no fluid force", HiddenSphereWarning, stacklevel=2)

    def _io_params(self):
        """What rebuilds the engine from a checkpoint: its label and parameters (the network is
        rebuilt at its next step)."""
        names = (*_BOUNDARY_LISTS, *_SCALARS, *_ENGINE_COUNTS, *_ENGINE_FLAGS, "defTolerance", "multithread",
                 *_THERMAL_ATTRIBUTES)
        params = {name: getattr(self, name) for name in names}
        if self._wallIds is not None:
            params["wallIds"] = list(self._wallIds)
        return {"label": self.label, **params}

    def emulateAction(self):
        """Run the engine's action once now (Yade's): triangulate (at the first call or when
        ``updateTriangulation`` is set), solve, add the fluid forces."""
        self._step()

    def moveVertices(self, positions, dt: float, boundaryPositions=None):
        """Move the spheres (same order as in ``triangulate``) and, optionally, the six
        boundary planes, over the time step ``dt`` without remeshing: pore volumes are
        recomputed and their rates of change drive the next solve (fluid expelled from shrinking
        pores), as Yade's FlowEngine does between remeshes. See ``maxVolumetricStrain``."""
        walls = self._flow.boundaryPositions() if boundaryPositions is None else [float(b) for b in boundaryPositions]
        self._flow.moveVertices(np.asarray(positions, dtype=float).reshape(-1, 3), walls, float(dt))

    def setTimeStep(self, dt: float):
        """Time step of the compressible (transient) solve when used standalone."""
        self._flow.setTimeStep(float(dt))

    def maxVolumetricStrain(self) -> float:
        """Largest relative change of a pore volume since the last triangulation (inf once a
        pore turned inside out); the engine remeshes when it exceeds ``defTolerance``."""
        return self._flow.maxVolumetricStrain()

    def boundaryPositions(self) -> list[float]:
        """Current positions of the six boundary planes (xmin .. zmax)."""
        return list(self._flow.boundaryPositions())

    def solverStats(self) -> dict:
        """Solver work so far: CHOLMOD's symbolic analyses, numeric factorisations and their
        seconds; the multigrid's (``useSolver=4`` or 5) set-ups, conjugate-gradient iterations and
        seconds."""
        c = self._flow.solverCounters()
        return dict(analyses=c.analyses, factorizations=c.factorizations,
                    analyseSeconds=c.analyseSeconds, factorizeSeconds=c.factorizeSeconds,
                    multigridSetups=c.multigridSetups, multigridIterations=c.multigridIterations,
                    multigridSeconds=c.multigridSeconds)

    def remeshCount(self) -> tuple[int, int]:
        """(all rebuilds, rebuilds triggered by defTolerance or an inverted pore) of the engine."""
        if self._coupling is None:
            return (0, 0)
        return (self._coupling.rebuilds(), self._coupling.strainRebuilds())

    def updateConductances(self):
        """Recompute conductances after changing permeabilityFactor, viscosity or the clamping."""
        self._flow.updateConductances()

    def solve(self):
        """Solve the pore pressures for the current boundary values. With no pressure imposed
        anywhere and an incompressible fluid the mean pressure is ``pZero``; raises ValueError
        when the pores' volume changes then sum to a net gain or loss (no solution)."""
        self._flow.solve()

    def imposePressure(self, pos, p: float) -> int:
        """Impose pressure ``p`` in the pore containing ``pos`` (located again at each
        triangulation, overriding boundary values); returns its index for setImposedPressure
        and getCellFlux."""
        return self._flow.imposePressure(np.asarray(pos, dtype=float), float(p))

    def setImposedPressure(self, cond: int, p: float):
        """Change the value of imposed point ``cond`` (the factorisation is kept)."""
        self._flow.setImposedPressure(cond, float(p))

    def clearImposedPressure(self):
        self._flow.clearImposedPressure()

    def imposeFlux(self, pos, q: float) -> int:
        """Impose the flux ``q`` in the pore containing ``pos`` (a source term; as Yade:
        outflux positive, influx negative), located again at each triangulation."""
        return self._flow.imposeFlux(np.asarray(pos, dtype=float), float(q))

    def clearImposedFlux(self):
        self._flow.clearImposedFlux()

    def saveVtk(self, base: str = "pores", withBoundaries: bool = True) -> list[str]:
        """ParaView output (legacy VTK): ``<base>.pores.vtk``, the pores as tetrahedra with
        pressure, volume, voidVolume and velocity per pore (and temperature, with a ThermalEngine's
        pore temperatures), radius and fluidForce per sphere (boundary pores drawn with their wall
        vertices projected on the wall), and ``<base>.throats.vtk``, one line per throat between
        the pore centres with flux, conductance, fluidArea, hydraulicRadius. Returns the two paths.
        ``withBoundaries`` False leaves the pores with a wall vertex out of the pores' file (Yade's
        option, whose default there is False). A ``base`` ending with '/' is a folder, as Yade's
        ``saveVtk(folder)``: it is created and the files are ``<folder>/pores_<iteration>.*``."""
        base = str(base)
        if base.endswith(("/", os.sep)):
            from talus.dem import O
            os.makedirs(base, exist_ok=True)
            base = os.path.join(base, f"pores_{(self._scene or O).iter}")
        fields = [] if self._poreHeat is None else [("temperature", list(self._poreHeat.temperatures()))]
        if self.alphaBound >= 0:
            fields.append(("alpha", [float(e) for e in self.alphaShape()[1]]))
        return list(self._flow.saveVtk(base, fields, bool(withBoundaries)))

    @property
    def poreVelocities(self) -> np.ndarray:
        """Darcy velocity of each pore, (nCells, 3)."""
        return self._flow.poreVelocities()

    def getCellFlux(self, cond: int) -> float:
        """Flux injected into the network by imposed point ``cond`` (positive out of its pore)."""
        return self._flow.getCellFlux(cond)

    # --- pore temperatures (ThermalEngine with advection) -------------------------------------
    def _heat(self):
        if self._poreHeat is None:
            raise RuntimeError("FlowEngine: no pore temperatures yet: they belong to a ThermalEngine with advection=True, "
                               "made at its first step")
        return self._poreHeat

    def getPoreTemperature(self, pos) -> float:
        """Temperature of the pore containing ``pos`` (Yade's)."""
        return self._heat().temperatureAt(np.asarray(pos, dtype=float))

    def getCellTemperature(self, cell: int) -> float:
        """Temperature of pore ``cell`` (Yade's)."""
        return float(self._heat().temperatures()[cell])

    def setCellTemperature(self, cell: int, temperature: float):
        """Set the temperature of pore ``cell`` (Yade's)."""
        t = _finite_number("setCellTemperature", temperature)
        if t < -273.15:
            raise ValueError(f"FlowEngine.setCellTemperature: {t} is below absolute zero (-273.15 °C, 0 K)")
        self._heat().setTemperature(int(cell), t)

    @property
    def cellTemperatures(self) -> np.ndarray:
        """Temperature of each pore (Talus)."""
        return self._heat().temperatures()

    # --- Yade's queries -------------------------------------------------------------------
    def nCells(self) -> int:
        return self._flow.nCells()

    def getBoundaryFlux(self, boundary: int) -> float:
        return self._flow.boundaryFlux(boundary)

    def getPorePressure(self, pos) -> float:
        return self._flow.porePressure(np.asarray(pos, dtype=float))

    def getCell(self, pos) -> int:
        return self._flow.locate(np.asarray(pos, dtype=float))

    def getCellPressure(self, cell: int) -> float:
        return float(self._flow.pressures()[cell])

    def getCellCenter(self, cell: int):
        return tuple(self._flow.poreCentres()[cell])

    def getCellBarycenter(self, cell: int):
        """A point inside pore ``cell``: the centroid of its vertices (a boundary vertex taken as
        the projection of the others' centroid on its plane); the place to impose a point
        condition on that pore."""
        return tuple(self._flow.poreBarycentre(cell))

    def getCellVolume(self, pos) -> float:
        """Volume of the pore containing ``pos`` (Yade's signature)."""
        return float(self._flow.poreVolumes()[self.getCell(pos)])

    def alphaShape(self) -> tuple[float, np.ndarray, list[int]]:
        """The alpha-shape boundary of the current network (``alphaBound`` >= 0): the alpha used
        (``alphaBound``, or CGAL's optimal one when 0), whether each pore lies outside the
        packing (an alpha or a box vertex: its pressure is then ``alphaBoundValue``), the body
        ids of the spheres in a pore with an alpha vertex."""
        alpha, exterior, onShape = self._flow.alphaShape()
        return float(alpha), np.asarray(exterior, dtype=bool), [int(i) for i in onShape]

    def printVertices(self, path: str = "vertices.txt"):
        """Yade's printVertices: ``vertices.txt`` with a line ``id x y z r alpha fictious`` per
        sphere of the network, then per alpha vertex (ids -1, -2, ... where Yade numbers them
        after the bodies) with ``alpha`` 1; ``fictious`` is 0 (as Yade's)."""
        ids = self._flow.vertexIds()
        spheres = self._flow.vertexSpheres()
        with open(path, "w") as out:
            out.write("id x y z r alpha fictious\n")
            for k in range(6, len(spheres)):
                x, y, z, r = spheres[k]
                alpha = k >= len(ids)
                out.write(f"{int(ids[k]) if not alpha else len(ids) - 1 - k} {x:g} {y:g} {z:g} {r:g} {int(alpha)} 0\n")

    def getVertices(self, cell: int) -> list[int]:
        """Vertex ids of a pore: boundaries 0..5, spheres by body id."""
        return [int(v) for v in self._flow.poreVertexIds()[cell]]

    def getNeighbors(self, cell: int) -> list[int]:
        return [int(v) for v in self._flow.poreNeighbours()[cell]]

    def fluidForce(self, id: int):
        """Fluid force on sphere ``id`` (body id) from the last solve: pressure on its sectors in
        the facets plus its share of the viscous drag (Yade's fluidForce). Boundaries: use
        ``boundaryForce``."""
        ids = self._vertex_index()
        if id not in ids:
            raise KeyError(f"fluidForce: body {id} is not a sphere of the pore network")
        return tuple(self._flow.vertexForces()[ids[id]])

    def boundaryForce(self, boundary: int):
        """Fluid force on boundary 0..5 (xmin .. zmax)."""
        if not 0 <= boundary < 6:
            raise IndexError("boundary index must be 0..5")
        return tuple(self._flow.vertexForces()[boundary])

    def computeViscousForces(self, velocities, angularVelocities, dt: float = 0.0):
        """Viscous forces between neighbouring spheres for their velocities and angular
        velocities ((n, 3), same order as in ``triangulate``) over the step ``dt`` (needed by the
        normal lubrication spring); read them with shearLubForce, shearLubTorque, normalLubForce.
        The engine calls it each step with the bodies' velocities."""
        self._flow.computeViscousForces(np.asarray(velocities, dtype=float).reshape(-1, 3),
                                        np.asarray(angularVelocities, dtype=float).reshape(-1, 3), float(dt))

    def shearLubForce(self, id: int):
        """Tangential viscous force on sphere ``id`` (body id; viscousShear or shearLubrication)."""
        return tuple(self._flow.shearLubForces()[self._sphere_index(id)])

    def shearLubTorque(self, id: int):
        """Torque of the tangential viscous forces on sphere ``id`` (body id)."""
        return tuple(self._flow.shearLubTorques()[self._sphere_index(id)])

    def normalLubForce(self, id: int):
        """Normal lubrication force on sphere ``id`` (body id)."""
        return tuple(self._flow.normalLubForces()[self._sphere_index(id)])

    def _sphere_index(self, id: int) -> int:
        ids = self._vertex_index()
        if id not in ids:
            raise KeyError(f"body {id} is not a sphere of the pore network")
        return ids[id] - 6

    def _vertex_index(self):
        return {int(v): k for k, v in enumerate(self._flow.vertexIds()) if k >= 6}

    def averageVelocity(self):
        """Volume-averaged Darcy velocity over all pores (Yade's averageVelocity)."""
        return tuple(self._flow.averageVelocity())

    def samplePermeability(self, lo: int, hi: int) -> float:
        """Darcy permeability K = Q μ L / (A ΔP) between the opposite pressure boundaries lo, hi."""
        return self._flow.samplePermeability(lo, hi)

    # --- whole-network arrays (Talus additions) -------------------------------------------
    @property
    def pressures(self) -> np.ndarray:
        return self._flow.pressures()

    @property
    def cellVolumes(self) -> np.ndarray:
        return self._flow.poreVolumes()

    @property
    def cellVoidVolumes(self) -> np.ndarray:
        return self._flow.poreVoidVolumes()

    @property
    def cellCenters(self) -> np.ndarray:
        return self._flow.poreCentres()

    @property
    def cellVertexIds(self) -> np.ndarray:
        return self._flow.poreVertexIds()

    @property
    def throatPores(self) -> np.ndarray:
        return self._flow.throatPores()

    @property
    def throatConductances(self) -> np.ndarray:
        return self._flow.throatConductances()

    @property
    def throatFluidAreas(self) -> np.ndarray:
        return self._flow.throatFluidAreas()

    @property
    def throatHydraulicRadii(self) -> np.ndarray:
        return self._flow.throatHydraulicRadii()

    @property
    def throatLengths(self) -> np.ndarray:
        return self._flow.throatLengths()

    @property
    def hiddenSpheres(self) -> list[int]:
        return list(self._flow.hiddenSpheres())
