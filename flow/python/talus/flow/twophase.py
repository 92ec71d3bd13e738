"""Quasi-static two-phase flow in the pore network (Yade's ``TwoPhaseFlowEngine``, the "2PFV"
model of Yuan & Chareyre 2017, CMAME 318).

Each pore of the FlowEngine network holds one phase: wetting (saturation 1) or non-wetting (0).
Boundary 2 (ymin) is the wetting reservoir, boundary 3 (ymax) the non-wetting one, both with an
imposed pressure (``bndCondIsPressure[2]`` and ``[3]``); the capillary pressure is
``bndCondValue[3] - bndCondValue[2]``. At each ``invasion()`` the non-wetting phase enters a
wetting pore through a throat when the pressure difference exceeds both the throat's entry
pressure ``surfaceTension / r_throat`` and the pore body's ``surfaceTension / r_body``
(drainage); with ``isImbibitionActivated`` the wetting phase comes back when it falls below both.
With ``isPhaseTrapped`` (default) a wetting cluster cut from its reservoir is trapped, at the
capillary pressure of that moment. The throat radius follows ``entryPressureMethod``: 1 MS-P
(Mayer-Stowe-Princen as Yuan & Chareyre compute it: the meniscus radius balancing the capillary
force on the non-wetting front and its pressure in the throat's plane; throats touching a
boundary take the inscribed circle), 2 the circle inscribed between the three spheres, 3 the
circle of the throat's fluid area. The body radius is the sphere inscribed between the pore's
four spheres. Names are Yade's::

    from talus.flow import TwoPhaseFlowEngine
    tp = TwoPhaseFlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], surfaceTension=10)
    tp.initialization()                  # the network of talus.dem.O, or tp.triangulate(pos, radii) first
    for pc in pcs:
        tp.bndCondValue = [0, 0, -pc, 0, 0, 0]
        tp.invasion()
        print(pc, tp.getSaturation(False))

See ``docs/twophase.md``.
"""

from __future__ import annotations

import math
import os
import warnings

import numpy as np

from talus import _flow
from talus.flow.phasecluster import PhaseCluster
from talus.flow.pore import FlowEngine

_OWNER = "TwoPhaseFlowEngine"
# the options of the C++ model (TwoPhaseParameters), Yade's names and defaults
_FLAGS = ("isPhaseTrapped", "isInvadeBoundary", "drainageFirst", "isDrainageActivated", "isImbibitionActivated",
          "recursiveInvasion", "isCellLabelActivated", "useFastInvasion")
# Yade's FlowEngine names of the boundary indices (wallIds[flow.ymin] ...)
_BOUNDARY_NAMES = ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")
# Yade's attributes kept for its scripts; no physics of this model depends on them (iniVoidVolumes:
# Talus always has the void volumes)
_STORED = {"bndCondIsWaterReservoir": [False] * 6, "computeForceActivated": True, "keepTriangulation": False,
           "iniVoidVolumes": False}

# Yade's dynamic two-phase flow (Sweijen et al.: actionTPF, pore units merged from tetrahedra,
# partial saturations), which Talus does not have: its names get an error saying so
_DYNAMIC = frozenset((
    "actionTPF", "primaryTPF", "actionMergingAlgorithm", "reTriangulateSpheres", "calculateResidualSaturation",
    "copyPoreDataToCells", "mergeCells", "entryMethodCorrection", "solvePressureSwitch", "firstDynTPF", "dtDynTPF",
    "iterationTPF", "deformation", "remesh", "swelling", "truncationPrecision", "deltaTimeTruncation",
    "waterBoundaryPressure", "maximumRatioPoreThroatoverPoreBody", "getCellMergedID", "getCellMergedVolume",
    "getCellEntrySaturation", "getCellThresholdSaturation", "setCellDeltaVolume", "imposeDeformationFluxTPF"))


def _dynamic(name: str) -> AttributeError:
    return AttributeError(f"{_OWNER}.{name} belongs to Yade's dynamic two-phase flow (actionTPF: pore units merged "
                          "from tetrahedra, partial saturations), which Talus does not have; the quasi-static model "
                          "(invasion) and the clusters are there (docs/twophase.md)")


def _pore_index(name: str, value, function: str = "clusterOutvadePore") -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{_OWNER}.{function}: {name} must be a pore index (int), got {value!r}")
    return int(value)


def _triplet(*values):
    """Three (position, radius) pairs as the C++ functions take them."""
    return [np.asarray(v, dtype=float) if k % 2 == 0 else float(v) for k, v in enumerate(values)]


class TwoPhaseFlowEngine(FlowEngine):
    """Quasi-static drainage and imbibition on the pore network (see the module docstring), with
    FlowEngine's attributes for the network and its boundaries and Yade's two-phase names:
    ``surfaceTension`` (0.0728), ``entryPressureMethod`` (1), ``isPhaseTrapped`` (True),
    ``isInvadeBoundary`` (True), ``drainageFirst`` (True), ``isDrainageActivated`` (True),
    ``isImbibitionActivated`` (False), ``recursiveInvasion`` (True); ``initialization``,
    ``invasion``, ``getSaturation``, ``getMinDrainagePc``, ``getMaxImbibitionPc``,
    ``computeCapillaryForce``, ``fluidForce``, ``savePhaseVtk`` and the per-pore getters
    (``getCellSaturation``, ``getCellIsWRes`` ...)."""

    def __init__(self, scene=None, **attrs):
        object.__setattr__(self, "_params", _flow.TwoPhaseParameters())
        object.__setattr__(self, "_tp", _flow.TwoPhaseFlow())
        object.__setattr__(self, "_stored", {k: (list(v) if isinstance(v, list) else v) for k, v in _STORED.items()})
        object.__setattr__(self, "_userNetwork", False)
        object.__setattr__(self, "_spheres", None)
        object.__setattr__(self, "_capillary", None)
        object.__setattr__(self, "_vtkCount", 0)
        object.__setattr__(self, "_barycentres", None)
        object.__setattr__(self, "_current", False)  # the model is of the network as it is
        super().__init__(scene, **attrs)

    # --- parameters ---------------------------------------------------------------------------
    def __setattr__(self, name, value):
        if name in _DYNAMIC:
            raise _dynamic(name)
        if name == "surfaceTension":
            gamma = float(value) if isinstance(value, (int, float, np.number)) else math.nan
            if not math.isfinite(gamma) or gamma < 0:
                raise ValueError(f"{_OWNER}.surfaceTension must be a finite number >= 0 (N/m), got {value!r}")
            self._params.surfaceTension = gamma
            return
        if name == "entryPressureMethod":
            if not isinstance(value, (int, np.integer)) or isinstance(value, bool) or value not in (1, 2, 3):
                raise ValueError(f"{_OWNER}.entryPressureMethod must be 1 (MS-P, Yuan & Chareyre 2017), 2 (inscribed "
                                 f"circle) or 3 (circle of the throat's fluid area), got {value!r}")
            self._params.entryPressureMethod = int(value)
            self._warn_if_initialized(name)
            return
        if name in _FLAGS:
            if not isinstance(value, (bool, int, np.integer, np.bool_)) or value not in (0, 1):
                raise TypeError(f"{_OWNER}.{name} must be True or False, got {value!r}")
            setattr(self._params, name, bool(value))
            if name in ("isInvadeBoundary", "drainageFirst"):
                self._warn_if_initialized(name)
            return
        if name == "meshUpdateInterval" and value == -1:
            value = 2 ** 31 - 1  # Yade's -1: never remesh
        if name in _STORED:
            if isinstance(_STORED[name], list):
                value = list(value)
                if len(value) != 6:
                    raise ValueError(f"{_OWNER}.{name} needs a list of 6 values (xmin, xmax, ymin, ymax, zmin, zmax), "
                                     f"got {value!r}")
            self._stored[name] = value
            return
        try:
            super().__setattr__(name, value)
        except (ValueError, TypeError, AttributeError) as error:
            # FlowEngine's messages name FlowEngine: name the engine the user has
            raise type(error)(str(error).replace("FlowEngine", _OWNER, 1)) from None

    def _warn_if_initialized(self, name):
        """Options read by initialization() only (as in Yade): say so when set after it."""
        if self._tp.initialized():
            warnings.warn(f"{_OWNER}.{name} acts at the next initialization() (the entry radii and the initial "
                          "phases are set there)", RuntimeWarning, stacklevel=3)

    def __getattr__(self, name):
        if name in _DYNAMIC:
            raise _dynamic(name)
        if name == "surfaceTension" or name == "entryPressureMethod" or name in _FLAGS:
            return getattr(self._params, name)
        if name in _STORED:
            value = self._stored[name]
            return list(value) if isinstance(value, list) else value
        if name in _BOUNDARY_NAMES:
            return _BOUNDARY_NAMES.index(name)
        return super().__getattr__(name)

    # --- network ------------------------------------------------------------------------------
    def triangulate(self, positions, radii, ids=None):
        """Build the network of given spheres (FlowEngine.triangulate); ``initialization`` then
        uses it instead of the scene's spheres."""
        super().triangulate(positions, radii, ids)
        ident = np.arange(len(radii)) if ids is None else np.asarray(ids)
        self._spheres = dict(zip((int(i) for i in ident), np.asarray(positions, dtype=float).reshape(-1, 3)))
        self._userNetwork = True
        self._current = False

    def initialization(self):
        """Build the network (from the scene's spheres, or the one of ``triangulate``), the entry
        radii of the throats, the pore bodies and the initial phases: all wetting with
        ``drainageFirst`` (else all non-wetting), the pores on boundary 2 wetting and those on
        boundary 3 non-wetting (Yade's initialization); with ``isCellLabelActivated`` the pores
        labelled by cluster (``getClusters``)."""
        if not (self.bndCondIsPressure[2] and (self.bndCondIsPressure[3] or self.isCellLabelActivated)):
            raise ValueError(f"{_OWNER}.bndCondIsPressure must impose the pressure on boundaries 2 (ymin, the wetting "
                             f"reservoir) and 3 (ymax, the non-wetting reservoir; optional with isCellLabelActivated), "
                             f"got {self.bndCondIsPressure}")
        if not self._userNetwork:
            from talus.dem import O
            scene = self._scene or O
            ids = scene.sphere_ids()
            everything = np.asarray(scene.positions())
            positions = everything[ids]
            # boundaries not at the packing's extremes are at their wall bodies, as in Yade
            walls, useMaxMin = self._wall_ids(scene), self.boundaryUseMaxMin
            self.wallPosition = [p if useMaxMin[k] or walls[k] < 0 else everything[walls[k]][k // 2]
                                 for k, p in enumerate(self.wallPosition)]
            self._current = False
            FlowEngine.triangulate(self, positions, np.asarray(scene.radii())[ids], ids)
            self._spheres = dict(zip((int(i) for i in ids), positions))
        self._tp.initialize(self._flow, self._params)
        self._capillary = None
        self._barycentres = None
        self._current = True

    def _step(self):
        """In an engine list the engine does nothing each step, as Yade's TwoPhaseFlowEngine (its
        action is empty): scripts call its functions."""

    def _model(self):
        """The C++ model with the options as they are now (Yade reads them at each call)."""
        model = self._state()
        model.setParameters(self._params)
        return model

    def _state(self):
        """The C++ model for the queries and cluster operations, which read no option (called
        per pore and per interface by injection scripts: kept light). Only triangulate() changes
        the network (the engine does nothing per step)."""
        if not self._current:
            if not self._tp.initialized():
                raise RuntimeError(f"{_OWNER}: call initialization() first")
            raise RuntimeError(f"{_OWNER}: the pore network was rebuilt since initialization() (triangulate): "
                               "call initialization() again")
        return self._tp

    # --- invasion -----------------------------------------------------------------------------
    def invasion(self):
        """Invade at the current ``bndCondValue`` (capillary pressure bndCondValue[3] -
        bndCondValue[2]): drainage and/or imbibition as activated, then the reservoirs and the
        trapped phases updated."""
        self._model().invasion(self.bndCondValue)

    def getSaturation(self, isSideBoundaryIncluded: bool = False) -> float:
        """Wetting saturation of the packing: wetting pore-body volume over pore-body volume,
        the pores on pressure boundaries left out and, unless ``isSideBoundaryIncluded``, the
        pores touching any boundary."""
        return self._model().saturation(bool(isSideBoundaryIncluded))

    def getMinDrainagePc(self) -> float:
        """The smallest capillary pressure at which one more pore drains (0: none can)."""
        return self._model().minDrainagePc()

    def getMaxImbibitionPc(self) -> float:
        """The largest capillary pressure at which one more pore imbibes (0: none can)."""
        return self._model().maxImbibitionPc()

    def getPcSwCurve(self, pcs, isSideBoundaryIncluded: bool = False) -> np.ndarray:
        """Talus: the saturation after invading at each capillary pressure of ``pcs`` in turn
        (the non-wetting reservoir kept at bndCondValue[3], the wetting one set to
        bndCondValue[3] - pc), as (pc, Sw) rows."""
        model = self._model()
        values = self.bndCondValue
        curve = []
        for pc in pcs:
            values[2] = values[3] - float(pc)
            model.invasion(values)
            curve.append((float(pc), model.saturation(bool(isSideBoundaryIncluded))))
        self.bndCondValue = values
        return np.array(curve)

    # --- per-pore getters (Yade's) ------------------------------------------------------------
    def getCellSaturation(self, cell: int) -> float:
        return float(self._model().saturations()[cell])

    def getCellIsWRes(self, cell: int) -> bool:
        return bool(self._model().flags("isWRes")[cell])

    def getCellIsNWRes(self, cell: int) -> bool:
        return bool(self._model().flags("isNWRes")[cell])

    def getCellIsTrapW(self, cell: int) -> bool:
        return bool(self._model().flags("isTrapW")[cell])

    def getCellIsTrapNW(self, cell: int) -> bool:
        return bool(self._model().flags("isTrapNW")[cell])

    def getCellPressure(self, cell: int) -> float:
        """The pressure of pore ``cell``'s phase (Yade keeps one pressure per pore, which the
        two-phase model sets); before initialization() FlowEngine's."""
        if not self._tp.initialized():
            return super().getCellPressure(cell)
        model = self._state()
        return float(model.pressures()[self._cell(cell, model)])

    def getCellVolume(self, cell) -> float:
        """Volume of pore ``cell`` (TwoPhaseFlowEngine takes a pore id, as Yade's); given a
        position, FlowEngine's: the volume of the pore containing it."""
        if np.ndim(cell) == 1:
            return super().getCellVolume(cell)
        model = self._state()
        return float(abs(self._flow.poreVolumes()[self._cell(cell, model)]))

    def getCellVoidVolume(self, cell: int) -> float:
        """Pore-body volume of pore ``cell`` (its volume minus the solid in it)."""
        model = self._state()
        return float(model.bodyVolumes()[self._cell(cell, model)])

    def getCellPorosity(self, cell: int) -> float:
        """Pore-body volume over volume of pore ``cell``."""
        return self.getCellVoidVolume(cell) / self.getCellVolume(cell)

    def getCellIsFictious(self, cell: int) -> bool:
        """Whether pore ``cell`` has a wall among its vertices."""
        model = self._state()
        return bool(min(self._flow.poreVertexIds()[self._cell(cell, model)]) < 6)

    def isCellNeighbor(self, cell1_ID: int, cell2_ID: int) -> bool:
        model = self._state()
        return self._cell(cell2_ID, model) in self.getNeighbors(self._cell(cell1_ID, model))

    def getPotentialPendularSpheresPair(self) -> list[tuple[int, int]]:
        """The pairs of vertices (body ids; walls by wallIds) whose edge of the network has only
        non-wetting pores around it: where a pendular bridge of the wetting phase may remain
        (the space outside the walls' fictitious spheres counts as dry, as in Yade)."""
        model = self._state()
        wet = model.saturations() == 1
        ring: dict[tuple[int, int], bool] = {}  # edge -> no wet pore around it so far
        for c, corners in enumerate(np.asarray(self._flow.poreVertexIds())):
            for i in range(4):
                for j in range(i + 1, 4):
                    edge = tuple(sorted((int(corners[i]), int(corners[j]))))
                    ring[edge] = ring.get(edge, True) and not wet[c]
        walls = self.wallIds
        body = lambda v: walls[v] if v < 6 else v  # noqa: E731
        return [(body(a), body(b)) for (a, b), dry in ring.items() if dry]

    def getCellInSphereRadius(self, cell: int) -> float:
        """Radius of the sphere inscribed in pore ``cell`` (its body radius)."""
        return float(self._model().bodyRadii()[cell])

    def getPoreThroatRadiusList(self, cell: int) -> list[float]:
        """Entry radii of the four throats of pore ``cell`` (0 across a facet with no pore)."""
        return [self.getPoreThroatRadius(cell, n) if n >= 0 else 0.0 for n in self.getNeighbors(cell)]

    def getPoreThroatRadius(self, cell1: int, cell2: int) -> float:
        """Entry radius of the throat between pores ``cell1`` and ``cell2``."""
        return float(self._model().throatRadii()[self._throat(cell1, cell2, "getPoreThroatRadius")])

    # --- per-pore setters (Yade's), for set-ups a script makes itself -------------------------
    # They change the state as given; no label or reservoir is recomputed (the next invasion()
    # floods the reservoirs again from boundaries 2 and 3; updatePressure() applies the pressures).
    def setCellSaturation(self, cell: int, saturation: float):
        model = self._model()
        model.setSaturation(self._cell(cell, model), float(saturation))

    def setCellIsWRes(self, cell: int, value: bool):
        model = self._model()
        model.setReservoir(self._cell(cell, model), True, bool(value))

    def setCellIsNWRes(self, cell: int, value: bool):
        model = self._model()
        model.setReservoir(self._cell(cell, model), False, bool(value))

    def setPoreBodyRadius(self, cell: int, radius: float):
        """The pore-body entry radius of pore ``cell`` (its entry pressure surfaceTension / radius)."""
        model = self._model()
        model.setBodyRadius(self._cell(cell, model), float(radius))

    def setPoreThroatRadius(self, cell1: int, cell2: int, radius: float):
        """The entry radius of the throat between pores ``cell1`` and ``cell2`` (negative: closed)."""
        self._model().setThroatRadius(self._throat(cell1, cell2, "setPoreThroatRadius"), float(radius))

    def updatePressure(self):
        """Each pore's pressure from ``bndCondValue`` and its reservoir and trapping flags (what
        ``invasion()`` starts with)."""
        self._model().updatePressure(self.bndCondValue)

    def _throat(self, cell1, cell2, function) -> int:
        pairs = self._flow.throatPores()
        hit = np.nonzero(((pairs[:, 0] == cell1) & (pairs[:, 1] == cell2)) | ((pairs[:, 0] == cell2) & (pairs[:, 1] == cell1)))[0]
        if len(hit) == 0:
            raise ValueError(f"{_OWNER}.{function}: pores {cell1} and {cell2} are not neighbours")
        return int(hit[0])

    def getMSPRcByPosRadius(self, position1, radius1, position2, radius2, position3, radius3) -> float:
        """The MS-P entry radius of the throat between three spheres (Yade's)."""
        return _flow.mspRadius(*_triplet(position1, radius1, position2, radius2, position3, radius3))

    def getEffRcByPosRadius(self, position1, radius1, position2, radius2, position3, radius3) -> float:
        """The radius of the circle inscribed between three spheres in their plane (Yade's)."""
        return _flow.inscribedRadius(*_triplet(position1, radius1, position2, radius2, position3, radius3))

    @property
    def cellSaturations(self) -> np.ndarray:
        """Talus: the saturation of every pore."""
        return self._model().saturations()

    @property
    def cellInSphereRadii(self) -> np.ndarray:
        """Talus: the body radius of every pore."""
        return self._model().bodyRadii()

    @property
    def throatEntryRadii(self) -> np.ndarray:
        """Talus: the entry radius of every throat (index as throatPores; -1: closed)."""
        return self._model().throatRadii()

    @property
    def phasePressures(self) -> np.ndarray:
        """Talus: the pressure of every pore's phase."""
        return self._model().pressures()

    # --- forces and output --------------------------------------------------------------------
    def computeCapillaryForce(self, addForces: bool = False, permanently: bool = False):
        """The forces of the phase pressures on the spheres and walls (Yade's scheme: each
        pore's pressure on the sphere sectors in its facets plus its share of the facet's fluid
        area); read them with ``fluidForce``. ``addForces`` adds them to the scene's bodies (the
        walls: ``wallIds``) for the next step (``permanently``: as permanent forces)."""
        forces = self._model().capillaryForces()
        ids = self._flow.vertexIds()
        # vertices 0..5 are the boundaries: their bodies are wallIds (Yade: bodies 0..5)
        self._capillary = {int(ids[k]): forces[k] for k in range(6, len(forces))}
        self._capillary.update({body: forces[k] for k, body in enumerate(self.wallIds) if body >= 0})
        if addForces:
            from talus.dem import O
            forcesOf = (self._scene or O).forces
            for body, f in self._capillary.items():
                (forcesOf.setPermF if permanently else forcesOf.addF)(body, tuple(f))

    def fluidForce(self, id: int):
        """Capillary force on body ``id`` (a sphere, or a wall of wallIds) from the last
        computeCapillaryForce (before any: FlowEngine's fluid force of the single-phase solve)."""
        if self._capillary is None:
            return super().fluidForce(id)
        if id not in self._capillary:
            return (0.0, 0.0, 0.0)  # a body out of the network, as Yade's zero force
        return tuple(self._capillary[id])

    def savePhaseVtk(self, folder: str = "./phaseVtk", withBoundaries: bool = True) -> str:
        """ParaView file ``<folder>/out_<n>.vtk`` (n counts the calls, as Yade): one tetrahedron
        per pore with cell data saturation, pressure, Pcondition; boundary pores (with
        ``withBoundaries``) drawn with their wall vertices at the projection of the pore's
        spheres on the wall. Returns the path."""
        model = self._model()
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, f"out_{self._vtkCount}.vtk")
        self._vtkCount += 1
        vertices = np.asarray(self._flow.poreVertexIds())
        real = vertices >= 6
        count = real.sum(axis=1)
        cells = np.nonzero((count == 4) | ((count > 0) & bool(withBoundaries)))[0]
        vertices, real, count = vertices[cells], real[cells], count[cells]
        ids = np.fromiter(self._spheres.keys(), dtype=int, count=len(self._spheres))
        table = np.zeros((max(ids.max(), 5) + 1, 3))  # position by body id
        table[ids] = np.asarray(list(self._spheres.values()))
        points = table[np.where(real, vertices, 0)]
        # a wall vertex: the centre of the pore's spheres projected on the wall
        centre = (points * real[..., None]).sum(axis=1) / count[:, None]
        cell, corner = np.nonzero(~real)
        wall = vertices[cell, corner]
        points[cell, corner] = centre[cell]
        points[cell, corner, wall // 2] = np.asarray(self.boundaryPositions())[wall]
        points = points.reshape(-1, 3)
        sat, pressure, imposed = model.saturations(), model.pressures(), model.flags("Pcondition")
        with open(path, "w") as out:
            out.write("# vtk DataFile Version 3.0\nTalus TwoPhaseFlowEngine phases\nASCII\nDATASET UNSTRUCTURED_GRID\n")
            out.write(f"POINTS {len(points)} double\n")
            out.writelines(f"{p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n" for p in points)
            out.write(f"CELLS {len(cells)} {5 * len(cells)}\n")
            out.writelines(f"4 {4 * k} {4 * k + 1} {4 * k + 2} {4 * k + 3}\n" for k in range(len(cells)))
            out.write(f"CELL_TYPES {len(cells)}\n" + "10\n" * len(cells))
            out.write(f"CELL_DATA {len(cells)}\n")
            for name, values in (("saturation", sat), ("pressure", pressure), ("Pcondition", imposed)):
                out.write(f"SCALARS {name} double 1\nLOOKUP_TABLE default\n")
                out.writelines(f"{values[c]:.9g}\n" for c in cells)
        return path

    # --- clusters (isCellLabelActivated; Yade's cell labels and PhaseCluster) ------------------
    def getClusters(self) -> list[PhaseCluster]:
        """The clusters, indexed by label: 0 the non-wetting pores, 1 the wetting reservoir, then
        the other wetting clusters (empty ones stay after a merge, as in Yade). Needs
        ``isCellLabelActivated`` at ``initialization()``."""
        model = self._model()
        if not self.isCellLabelActivated and model.clusterCount() == 0:
            raise RuntimeError(f"{_OWNER}.getClusters: set isCellLabelActivated = True before initialization()")
        return [PhaseCluster(self, k) for k in range(model.clusterCount())]

    def clusterOutvadePore(self, startingId: int, imbibedId: int, index: int = -1) -> list[int]:
        """Non-wetting pore ``imbibedId`` joins the wetting cluster of pore ``startingId``: it
        takes the cluster's label, its throats to non-wetting pores become interfaces of the
        cluster (volume 0), the cluster's interfaces onto it go, and the wetting clusters it
        touches merge into this one. Returns the label of the cluster and of those merged.
        ``index`` (the rank of the interface crossed) is accepted and unused, as in Yade."""
        return list(self._state().outvadePore(_pore_index("startingId", startingId),
                                              _pore_index("imbibedId", imbibedId)))

    def clusterInvadePore(self, cellId: int) -> list[int]:
        """Wetting pore ``cellId`` drains: it joins the non-wetting pores (label 0) and its
        cluster is found again from the pore's neighbours in turn, the first keeping the label,
        each other neighbour it no longer reaches starting a new cluster (the cluster split).
        The clusters rebuilt get their interfaces anew (volume and capillary pressure 0).
        Returns the cluster's label then the new labels; empty if the pore was its cluster's
        last. A pore not in a wetting cluster is an error (Yade warns and does nothing)."""
        return list(self._state().invadePore(_pore_index("cellId", cellId, "clusterInvadePore")))

    def clusterInvadePoreFast(self, cellId: int) -> list[int]:
        """Wetting pore ``cellId`` drains, its cluster kept in place: its interfaces go, its
        neighbours in the cluster get interfaces onto it (appended; the others keep their volumes),
        and the cluster is split only when those neighbours no longer meet around the pore's
        edges (then what its first pore, or the wetting reservoir's last imposed pore, no longer
        reaches becomes new clusters). The cluster's volume, interfacial area and entry radius are
        not updated, as in Yade. A pore on a pressure boundary is left as it is. Returns the
        cluster's label and the new ones. ``useFastInvasion`` makes ``invasion()`` call it on each
        pore it drains (instead of labelling every pore again after it)."""
        return list(self._state().invadePoreFast(_pore_index("cellId", cellId, "clusterInvadePoreFast")))

    def getCellHasInterface(self, cell: int) -> bool:
        """Whether pore ``cell`` is the inner side of a cluster interface (set when one is added,
        cleared when the pore drains)."""
        model = self._state()
        return bool(model.flags("hasInterface")[self._cell(cell, model)])

    def setCellHasInterface(self, cell: int, value: bool):
        model = self._state()
        model.setHasInterface(self._cell(cell, model), bool(value))

    def getCellLabel(self, id: int) -> int:
        """Cluster label of pore ``id`` (-1 without isCellLabelActivated)."""
        model = self._state()
        return model.label(self._cell(id, model))

    def getCellInvVoidVolume(self, id: int) -> float:
        """1 / pore-body volume of pore ``id`` (Yade's invVoidVolume with iniVoidVolumes)."""
        model = self._state()
        return 1.0 / float(model.bodyVolumes()[self._cell(id, model)])

    def getCellBarycenter(self, id: int):
        """Mean of the four vertices of pore ``id``, a wall's vertex being its fictitious sphere's
        far centre (Yade's cellBarycenter: far away for pores on a wall, mid-box across the
        other axes), unlike FlowEngine.getCellBarycenter's point inside the pore."""
        model = self._state()
        if self._barycentres is None:
            self._barycentres = model.barycentres()
        return tuple(self._barycentres[self._cell(id, model)])

    def getBoundaryFlux(self, boundary: int) -> float:
        """Flux the pores of ``boundary`` (its wall id, Yade's argument, or its index 0..5)
        receive from their neighbours at the phase pressures; negative where fluid enters."""
        walls = self.wallIds
        k = walls.index(boundary) if boundary in walls else boundary
        return self._model().boundaryFlux(k)

    def getCellFluxFromId(self, id: int) -> float:
        """Flux pore ``id`` sends to its neighbours at the phase pressures (sum of conductance
        times its pressure minus theirs; negative where fluid enters it)."""
        model = self._state()
        return model.poreFlux(self._cell(id, model))

    def _cell(self, id, model) -> int:
        n = model.poreCount()
        if isinstance(id, bool) or not isinstance(id, (int, np.integer)) or not 0 <= id < n:
            raise IndexError(f"{_OWNER}: cell id must be an integer in 0..{n - 1}, got {id!r}")
        return int(id)


class UnsaturatedEngine(TwoPhaseFlowEngine):
    """Yade's UnsaturatedEngine: the same quasi-static model as TwoPhaseFlowEngine, with its
    measures of parts of the packing (a pore belongs to a part by its centre, getCellCenter):
    getCuboidSubdomainSaturation, getCuboidSubdomainPorosity, getSphericalSubdomainSaturation,
    getInvadeDepth."""

    def _pores(self, isSideBoundaryIncluded: bool):
        """The pores the measures count (not on a pressure boundary; those touching a wall only
        with ``isSideBoundaryIncluded``), their centres and pore-body volumes."""
        model = self._model()
        keep = model.flags("Pcondition") == 0
        if not isSideBoundaryIncluded:
            keep &= np.asarray(self._flow.poreVertexIds()).min(axis=1) >= 6
        return keep, np.asarray(self._flow.poreCentres()), model.bodyVolumes()

    def _inCuboid(self, pos1, pos2, isSideBoundaryIncluded):
        keep, centres, volumes = self._pores(isSideBoundaryIncluded)
        a, b = np.asarray(pos1, dtype=float), np.asarray(pos2, dtype=float)
        inside = keep & np.all((a - centres) * (b - centres) < 0, axis=1)  # strictly between the corners
        if not inside.any():
            raise ValueError(f"{type(self).__name__}: no pore has its centre in the cuboid {tuple(a)} - {tuple(b)}")
        return inside, volumes

    def getCuboidSubdomainSaturation(self, pos1, pos2, isSideBoundaryIncluded: bool = False) -> float:
        """Wetting saturation of the pores whose centres are inside the box of corners ``pos1``,
        ``pos2``."""
        inside, volumes = self._inCuboid(pos1, pos2, isSideBoundaryIncluded)
        return float(np.sum(volumes[inside] * self._model().saturations()[inside]) / np.sum(volumes[inside]))

    def getCuboidSubdomainPorosity(self, pos1, pos2, isSideBoundaryIncluded: bool = False) -> float:
        """Pore-body volume over pore volume (solid included) of the pores whose centres are
        inside the box of corners ``pos1``, ``pos2``."""
        inside, volumes = self._inCuboid(pos1, pos2, isSideBoundaryIncluded)
        return float(np.sum(volumes[inside]) / np.sum(np.abs(self._flow.poreVolumes())[inside]))

    def getSphericalSubdomainSaturation(self, pos, radius: float) -> float:
        """Wetting saturation of the pores whose centres are within ``radius`` of ``pos``
        (pressure-boundary pores left out); the sphere must not reach a pore touching a wall (Yade
        returns -1 then)."""
        _, centres, volumes = self._pores(True)
        model = self._model()
        inside = np.linalg.norm(centres - np.asarray(pos, dtype=float), axis=1) <= radius
        if (inside & (np.asarray(self._flow.poreVertexIds()).min(axis=1) < 6)).any():
            raise ValueError(f"{type(self).__name__}.getSphericalSubdomainSaturation: the sphere of radius {radius} "
                             f"around {tuple(pos)} reaches pores touching a wall: make it smaller or move it inside")
        if not inside.any():
            raise ValueError(f"{type(self).__name__}.getSphericalSubdomainSaturation: no pore has its centre within "
                             f"radius {radius} of {tuple(pos)}")
        return float(np.sum(volumes[inside] * model.saturations()[inside]) / np.sum(volumes[inside]))

    def getInvadeDepth(self) -> float:
        """Extent along y of the pores of the non-wetting reservoir (from its boundary to the
        front of the invasion)."""
        y = np.asarray(self._flow.poreCentres())[self._model().flags("isNWRes") == 1, 1]
        return float(y.max() - y.min()) if len(y) else 0.0
