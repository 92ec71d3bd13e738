"""ParaView output: VTK XML unstructured grids (``.vtu``) and ``.pvd`` time series, written with
numpy alone (no VTK library), as Yade's ``VTKRecorder`` engine and ``export.VTKExporter``.

Files (arrays in brackets; vectors have 3 components):

- spheres: one point (with a vertex cell) per live sphere at its centre [radius, velocity,
  angVel, force, torque, id, materialId, mass, nonfinite]. Show them with ParaView's Glyph
  filter: glyph type Sphere, Scale Array ``radius``, scale factor 2 (the glyph's size is a
  diameter), Scale Mode scalar.
- facets: one triangle per live facet [id, materialId, normal, force, velocity].
- walls: one square of side ``wallSize`` per wall, centred on the spheres [id, materialId, axis,
  sense, force].
- periodic cell (Yade's ``pericell``): one hexahedron, the cell's corners ``hSize @ (i, j, k)`` in
  Yade's order (top face z=1 first).
- contacts (Yade's ``intrs``): one line per real contact, between the two sphere centres (the
  periodic image of the second sphere when across the cell) or, for walls and facets, from the
  contact point to the sphere centre [forceN (normal force magnitude), normalForce, shearForce,
  force (on body 2), penetration, id1, id2, kind (0 sphere-sphere, 1 wall, 2 facet), real].

Every file carries the simulated time as field data ``TimeValue``. Data are inline base64
(``format="binary"``, ``header_type="UInt64"``), which ParaView 5.x reads and XML parsers accept.
Files are written to a temporary name and renamed, so a reader never sees half a file. Non-finite
numbers are written as they are (IEEE NaN/inf, legal in VTK) and flagged: the point array
``nonfinite`` is 1 for the spheres concerned and a :class:`VTKWarning` names them.
"""

from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Iterable, Sequence
from xml.sax.saxutils import quoteattr

import numpy as np

from talus import _dem
from talus.atomic import write_atomically
from talus.dem.step.engines import PyRunner
from talus.dem.files.io import owner_scene
from talus.dem.core import heat
from talus.dem.base.linalg import Quaternion
from talus.dem.core.scenes import default_scene
from talus.dem.files import vtk_split
from talus.dem.files.vtu import vtu_bytes

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

__all__ = ["VTKWarning", "sphere_rows", "write_spheres", "write_facets", "write_walls", "write_boxes", "write_contacts", "PvdCollection",
           "write_periodic_cell", "VTKRecorder", "VTKExporter"]

# VTK cell types.
VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_QUAD, VTK_HEXAHEDRON = 1, 3, 5, 9, 12
# Corners of a box in VTK's hexahedron order, as signs of the extents.
_HEX_CORNERS = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                         (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], dtype=float)
# Corners of the periodic cell as fractions of its edges, in the order Yade's files list them.
_CELL_CORNERS = np.array([(0, 0, 1), (0, 1, 1), (1, 1, 1), (1, 0, 1),
                          (0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)], dtype=float)


class VTKWarning(UserWarning):
    """Something unusual was written to a VTK file (non-finite values)."""


def _cells(count: int, size: int, cell_type: int):
    """Connectivity, offsets and types of ``count`` cells of ``size`` consecutive points."""
    return (np.arange(count * size, dtype=np.int64), np.arange(1, count + 1, dtype=np.int64) * size,
            np.full(count, cell_type, dtype=np.uint8))


def _flag_nonfinite(what: str, ids: np.ndarray, arrays: Iterable[np.ndarray]) -> np.ndarray:
    bad = np.zeros(len(ids), dtype=bool)
    for a in arrays:
        a = np.asarray(a)
        if a.dtype.kind == "f" and len(a):
            bad |= ~np.isfinite(a.reshape(len(ids), -1)).all(axis=1)
    if bad.any():
        first = ", ".join(str(i) for i in ids[bad][:5])
        warnings.warn(f"VTK export: {int(bad.sum())} {what} with non-finite values (ids {first}"
                      f"{', ...' if bad.sum() > 5 else ''}); written as NaN/inf and flagged in 'nonfinite'",
                      VTKWarning, stacklevel=3)
    return bad.astype(np.uint8)


def sphere_rows(scene: "Scene") -> np.ndarray:
    """The rows of the spheres a sphere file holds: the live spheres; under mpirun, those this
    process owns (talus.dem.files.vtk_split)."""
    return vtk_split.owned(scene, scene.sphere_ids())


def write_spheres(scene: "Scene", path: str, extra: dict | None = None) -> int:
    """Write the live spheres of ``scene`` to ``path`` (.vtu); returns their number. ``extra``:
    more point arrays (name -> array over the spheres of :func:`sphere_rows`, in that order).
    Under mpirun every process calls it and process 0 writes every sphere (vtk_split)."""
    rows = sphere_rows(scene)
    ids = vtk_split.global_ids(scene, rows)
    cpp = scene._cpp
    data = {
        "position": cpp.pos()[rows],
        "radius": cpp.radius()[rows], "velocity": cpp.vel()[rows], "angVel": cpp.angVel()[rows],
        "force": cpp.force()[rows], "torque": cpp.torque()[rows], "id": ids.astype(np.int32),
        "materialId": cpp.materialIds()[rows].astype(np.int32), "mass": cpp.mass()[rows],
        "color": scene._appearance.of(ids, len(scene.bodies)),
    }
    data.update(extra or {})
    data = vtk_split.gather(scene, data, ("id",))
    if data is None:    # another process writes
        return vtk_split.total(scene, len(rows))
    positions = data.pop("position")
    data["nonfinite"] = _flag_nonfinite("spheres", data["id"], [positions, *data.values()])
    write_atomically(path, vtu_bytes(positions, *_cells(len(positions), 1, VTK_VERTEX), point_data=data,
                                     time=cpp.time))
    return vtk_split.total(scene, len(rows))


def write_facets(scene: "Scene", path: str) -> int:
    """Write the live facets of ``scene`` to ``path`` as triangles; returns their number."""
    f = _dem.facet_arrays(scene._cpp)
    rows = f["id"]
    ids = vtk_split.global_ids(scene, rows)     # every process holds every facet: process 0 writes them
    data = {"id": ids.astype(f["id"].dtype), "materialId": f["material"], "normal": f["normal"],
            "force": vtk_split.summed(scene, scene._cpp.force()[rows]), "velocity": scene._cpp.vel()[rows],
            "color": scene._appearance.of(ids, len(scene.bodies))}
    if vtk_split.writes(scene):
        write_atomically(path, vtu_bytes(f["vertices"].reshape(-1, 3), *_cells(len(ids), 3, VTK_TRIANGLE),
                                         cell_data=data, time=scene._cpp.time))
    return len(ids)


def write_boxes(scene: "Scene", path: str) -> int:
    """Write the live boxes of ``scene`` to ``path`` as hexahedra; returns their number."""
    rows = _dem.live_ids(scene._cpp, "Box")
    ids = vtk_split.global_ids(scene, rows)     # every process holds every box: process 0 writes them
    cpp = scene._cpp
    corners = [cpp.pos()[i] + (_HEX_CORNERS * _dem.box_extents(cpp, int(i))) @ Quaternion(*cpp.ori(int(i))).toRotationMatrix().T
               for i in rows]
    data = {"id": ids.astype(np.int32), "materialId": cpp.materialIds()[rows].astype(np.int32),
            "velocity": cpp.vel()[rows], "angVel": cpp.angVel()[rows],
            "force": vtk_split.summed(scene, cpp.force()[rows]), "color": scene._appearance.of(ids, len(scene.bodies))}
    if vtk_split.writes(scene):
        write_atomically(path, vtu_bytes(np.array(corners).reshape(-1, 3), *_cells(len(ids), 8, VTK_HEXAHEDRON),
                                         cell_data=data, time=cpp.time))
    return len(ids)


def _sphere_box(scene: "Scene"):
    rows = sphere_rows(scene)
    pos, r = scene._cpp.pos()[rows], scene._cpp.radius()[rows]
    finite = np.isfinite(pos).all(axis=1)
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    if finite.any():
        lo, hi = (pos[finite] - r[finite, None]).min(axis=0), (pos[finite] + r[finite, None]).max(axis=0)
    lo, hi = vtk_split.extremes(scene, lo, hi)    # every process's spheres
    return (lo, hi) if np.isfinite(lo).all() else (np.zeros(3), np.ones(3))


def write_walls(scene: "Scene", path: str, size: float | None = None) -> int:
    """Write the walls of ``scene`` to ``path`` as squares of side ``size`` (default: 1.5 times
    the largest extent of the spheres) centred on the spheres; returns their number."""
    w = _dem.wall_arrays(scene._cpp)
    lo, hi = _sphere_box(scene)
    centre = 0.5 * (lo + hi)
    half = 0.5 * (float(size) if size else 1.5 * max(float((hi - lo).max()), 1e-300))
    corners = []
    for axis, position in zip(w["axis"], w["position"]):
        u, v = [d for d in range(3) if d != axis]
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            p = centre.copy()
            p[axis], p[u], p[v] = position, centre[u] + su * half, centre[v] + sv * half
            corners.append(p)
    rows = w["id"]
    data = {"id": vtk_split.global_ids(scene, rows).astype(rows.dtype), "materialId": w["material"], "axis": w["axis"],
            "sense": w["sense"], "force": vtk_split.summed(scene, scene._cpp.force()[rows])}
    if vtk_split.writes(scene):
        write_atomically(path, vtu_bytes(np.array(corners).reshape(-1, 3), *_cells(len(rows), 4, VTK_QUAD),
                                         cell_data=data, time=scene._cpp.time))
    return len(rows)


def write_periodic_cell(scene: "Scene", path: str) -> int:
    """Write the periodic cell of ``scene`` to ``path`` as one hexahedron; returns 1."""
    if not scene.periodic:
        raise ValueError("write_periodic_cell: the scene is not periodic (O.periodic is False)")
    corners = _CELL_CORNERS @ np.asarray(scene.cell.hSize, dtype=float).T
    if vtk_split.writes(scene):     # every process holds the cell alike
        write_atomically(path, vtu_bytes(corners, *_cells(1, 8, VTK_HEXAHEDRON), time=scene._cpp.time))
    return 1


def write_contacts(scene: "Scene", path: str, real_only: bool = True) -> int:
    """Write the contact-force network of ``scene`` to ``path``: one line per contact (only the
    real ones unless ``real_only`` is false); returns the number of lines. Under mpirun every
    process calls it and process 0 writes every contact once (vtk_split)."""
    c = _dem.contact_arrays(scene._cpp, bool(real_only))
    counted = vtk_split.counted_contacts(scene, c["id1"], c["id2"])
    c = {name: np.asarray(a)[counted] for name, a in c.items()}
    pos = scene._cpp.pos()
    id1, id2 = c["id1"], c["id2"]
    sphere_pair = (c["kind"] == 0)[:, None]
    start = np.where(sphere_pair, pos[id1], c["contactPoint"])
    end = pos[id2] + np.where(sphere_pair, c["shift2"], 0.0)   # the periodic image of body 2
    data = {"start": start, "end": end, "forceN": np.linalg.norm(c["normalForce"], axis=1),
            "normalForce": c["normalForce"], "shearForce": c["shearForce"], "force": c["force"],
            "penetration": c["penetration"], "id1": vtk_split.global_ids(scene, id1).astype(id1.dtype),
            "id2": vtk_split.global_ids(scene, id2).astype(id2.dtype), "kind": c["kind"], "real": c["real"]}
    data = vtk_split.gather(scene, data, ("id1", "id2"))
    if data is not None:    # (None: another process writes)
        points = np.stack([data.pop("start"), data.pop("end")], axis=1).reshape(-1, 3)
        write_atomically(path, vtu_bytes(points, *_cells(len(data["id1"]), 2, VTK_LINE), cell_data=data,
                                         time=scene._cpp.time))
    return vtk_split.total(scene, len(id1))


class PvdCollection:
    """A ParaView time series (``.pvd``): one entry (time, file) per written step, rewritten
    atomically after each addition. Files are stored relative to the ``.pvd``'s folder."""

    def __init__(self, path: str, entries: Sequence[tuple[float, str]] = ()):
        self.path = path
        self.entries: list[tuple[float, str]] = [(float(t), str(f)) for t, f in entries]

    def add(self, time: float, file: str, write: bool = True) -> None:
        """List ``file`` at ``time`` and rewrite the ``.pvd`` (unless ``write`` is false: under
        mpirun every process lists it, process 0 writes)."""
        rel = os.path.relpath(os.path.abspath(file), os.path.dirname(os.path.abspath(self.path)))
        self.entries = [e for e in self.entries if e[1] != rel] + [(float(time), rel)]
        if write:
            self.write()

    def write(self) -> None:
        lines = ['<?xml version="1.0"?>\n', '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n',
                 "  <Collection>\n"]
        lines += [f'    <DataSet timestep="{t!r}" group="" part="0" file={quoteattr(f)}/>\n' for t, f in self.entries]
        lines += ["  </Collection>\n", "</VTKFile>\n"]
        write_atomically(self.path, "".join(lines).encode("utf-8"))


# ------------------------------------------------------------------------------------------------
# Yade's VTKRecorder engine and export.VTKExporter.

_WRITERS = {"spheres": write_spheres, "facets": write_facets, "walls": write_walls, "boxes": write_boxes,
            "intrs": write_contacts, "pericell": write_periodic_cell}
_RECORDERS = {"spheres": ("spheres",), "facets": ("facets",), "walls": ("walls",), "boxes": ("walls", "boxes"),
              "intr": ("intrs",), "pericell": ("pericell",), "all": ("spheres", "facets", "walls", "boxes", "intrs"),
              "thermal": ("spheres",)}
# Yade recorders whose data the sphere file always holds (colours: the facet and box files too).
_INCLUDED = {"velocity", "id", "ids", "materialId", "mass", "force", "color", "colors"}


class VTKRecorder(PyRunner):
    """Write ParaView files every ``iterPeriod`` steps (Yade's VTKRecorder).

    ``fileName`` is a prefix: files are ``{fileName}spheres.{iter}.vtu``, ``...facets...``,
    ``...walls...`` and ``...intrs...`` (the contact network), each series listed in
    ``{fileName}spheres.pvd`` etc. for ParaView. ``recorders``: any of ``spheres``, ``facets``,
    ``walls``, ``boxes`` (Box bodies as hexahedra, and walls as Yade's ``boxes`` does), ``intr``,
    ``pericell`` (the periodic cell; nothing in a scene that is not periodic), ``thermal`` (the
    sphere file gets the bodies' heat, ``temp``, ``k``, ``Cp``: the values given, or the
    ThermalEngine's defaults), or
    ``all`` (all but ``pericell``, as Yade's); Yade's ``velocity``, ``ids``, ``colors``,
    ``materialId``, ``mass``, ``force`` are accepted (the sphere file always has them).
    ``wallSize``: side of the squares drawn for walls (default: from the spheres' extent).
    Folders in ``fileName`` are created. Usable in ``O.engines`` and saved by ``O.save``.
    ``parallelMode`` (Yade's switch for its mpy module, which then writes a piece per process)
    changes nothing: under mpirun Talus writes the files above, from process 0.
    """

    def __init__(self, fileName: str = "", recorders: Sequence[str] = ("spheres", "facets", "intr"),
                 iterPeriod: int = 1, initRun: bool = False, wallSize: float | None = None,
                 parallelMode: bool = False, label: str = ""):
        if isinstance(recorders, str):
            recorders = [recorders]
        kinds: list[str] = []
        for r in recorders:
            if r in _RECORDERS:
                kinds += [k for k in _RECORDERS[r] if k not in kinds]
            elif r not in _INCLUDED:
                known = sorted(set(_RECORDERS) | _INCLUDED)
                raise ValueError(f"VTKRecorder: unknown recorder {r!r}; Talus knows {', '.join(known)}")
        super().__init__(command=self._record, iterPeriod=iterPeriod, initRun=initRun, label=label)
        self.fileName = str(fileName)
        self.recorders = list(recorders)
        self.wallSize = wallSize
        self.parallelMode = bool(parallelMode)
        self._kinds = kinds
        self._series: dict[str, PvdCollection] = {}

    def _collection(self, kind: str) -> PvdCollection:
        if kind not in self._series:
            self._series[kind] = PvdCollection(f"{self.fileName}{kind}.pvd")
        return self._series[kind]

    def _record(self):
        scene = self._scene()
        for kind in self._kinds:
            if kind == "pericell" and not scene.periodic:   # as Yade: no cell, no file
                continue
            path = f"{self.fileName}{kind}.{scene.iter}.vtu"
            if kind == "walls":
                write_walls(scene, path, self.wallSize)
            elif kind == "spheres" and "thermal" in self.recorders:
                if vtk_split.is_split(scene):   # which heat fields a file has is decided per process
                    from talus.dem import distributed
                    distributed.refuse("VTKRecorder's 'thermal' recorder")
                write_spheres(scene, path, heat.sphere_arrays(scene, sphere_rows(scene)))
            else:
                _WRITERS[kind](scene, path)
            self._collection(kind).add(scene.time, path, write=vtk_split.writes(scene))

    def _scene(self) -> "Scene":
        """The scene whose engine list holds this recorder; O for one called by hand outside any
        engine list (``VTKRecorder(...)()``, as in Yade)."""
        O = default_scene()
        if any(e is self for e in O.engines):
            return O
        try:
            return owner_scene(self)
        except RuntimeError:
            return O

    # Saved with the engine by O.save, so that the series go on after O.load.
    def _io_state(self):
        return {kind: [list(e) for e in c.entries] for kind, c in self._series.items()}

    def _io_restore(self, state):
        self._series = {kind: PvdCollection(f"{self.fileName}{kind}.pvd", [tuple(e) for e in entries])
                        for kind, entries in state.items()}


class VTKExporter:
    """Yade's ``export.VTKExporter``: write snapshots on demand, ``{baseName}-spheres-{n}.vtu``
    etc., each kind numbered from ``startSnap`` (or ``numLabel`` when given). ``what`` adds
    sphere arrays: a name and an expression of ``b`` (the Body) evaluated per sphere, e.g.
    ``{"speed": "np.linalg.norm(b.state.vel)"}``."""

    def __init__(self, baseName: str, startSnap: int = 0, scene: "Scene | None" = None):
        self.baseName = baseName
        self.startSnap = startSnap
        self._counts: dict[str, int] = {}
        self._scene = scene

    @property
    def scene(self) -> "Scene":
        if self._scene is None:
            O = default_scene()
            return O
        return self._scene

    def _path(self, kind: str, numLabel: int | None) -> str:
        if numLabel is None:
            numLabel = self._counts.get(kind, self.startSnap)
            self._counts[kind] = numLabel + 1
        return f"{self.baseName}-{kind}-{numLabel}.vtu"

    def exportSpheres(self, what: dict | None = None, numLabel: int | None = None) -> str:
        scene = self.scene
        path = self._path("spheres", numLabel)
        ids = vtk_split.global_ids(scene, sphere_rows(scene))
        write_spheres(scene, path, _evaluate(what, [scene.bodies._here(i) for i in ids]))
        return path

    def exportFacets(self, numLabel: int | None = None) -> str:
        path = self._path("facets", numLabel)
        write_facets(self.scene, path)
        return path

    def exportFacetsAsMesh(self, ids="all", connectivityTable=None, what: dict | None = None,
                           numLabel: int | None = None) -> str:
        """The facets (all, or those of ``ids``) as one mesh whose triangles share their nodes:
        ``connectivityTable`` gives the three node numbers of each facet, in the order of the
        facets (as ``ymport.unv(..., returnConnectivityTable=True)`` returns it). Cell arrays:
        ``id`` and the expressions of ``what`` (see :meth:`exportSpheres`)."""
        scene = self.scene
        facets = _dem.facet_arrays(scene._cpp)
        facets["id"] = vtk_split.global_ids(scene, facets["id"])    # (every process holds every facet)
        chosen = _chosen_ids(facets["id"], ids, "Facet")
        if connectivityTable is None:
            raise ValueError("exportFacetsAsMesh: connectivityTable is required (the node numbers of each facet)")
        table = np.asarray(connectivityTable, dtype=np.int64).reshape(-1, 3)
        if len(table) != len(chosen):
            raise ValueError(f"exportFacetsAsMesh: connectivityTable has {len(table)} rows for {len(chosen)} facets")
        if len(table) and table.min() < 0:
            raise ValueError("exportFacetsAsMesh: connectivityTable has a negative node number")
        # Each node takes the position of the last facet naming it, as in Yade.
        nodes = np.zeros((int(table.max()) + 1 if len(table) else 0, 3))
        row = {int(i): k for k, i in enumerate(facets["id"])}
        for triangle, i in zip(table, chosen):
            nodes[triangle] = facets["vertices"][row[int(i)]]
        data = {"id": chosen.astype(np.int32), **_evaluate(what, [scene.bodies[int(i)] for i in chosen])}
        path = self._path("facets", numLabel)
        if vtk_split.writes(scene):
            write_atomically(path, vtu_bytes(nodes, table.reshape(-1), 3 * np.arange(1, len(table) + 1),
                                             np.full(len(table), VTK_TRIANGLE, dtype=np.uint8), cell_data=data,
                                             time=scene._cpp.time))
        return path

    def exportPeriodicCell(self, numLabel: int | None = None) -> str | None:
        """The periodic cell as one hexahedron (``{baseName}-periCell-{n}.vtu``); a scene that
        is not periodic gives a warning and no file, as in Yade."""
        if not self.scene.periodic:
            warnings.warn("exportPeriodicCell: the scene is not periodic, nothing exported", VTKWarning, stacklevel=2)
            return None
        path = self._path("periCell", numLabel)
        write_periodic_cell(self.scene, path)
        return path

    def exportWalls(self, size: float | None = None, numLabel: int | None = None) -> str:
        path = self._path("walls", numLabel)
        write_walls(self.scene, path, size)
        return path

    def exportBoxes(self, numLabel: int | None = None) -> str:
        path = self._path("boxes", numLabel)
        write_boxes(self.scene, path)
        return path

    def exportInteractions(self, numLabel: int | None = None) -> str:
        path = self._path("intrs", numLabel)
        write_contacts(self.scene, path)
        return path


def _chosen_ids(available: np.ndarray, ids, kind: str) -> np.ndarray:
    """The ids of ``ids`` ("all": every one of ``available``), each checked to be a live ``kind``."""
    if isinstance(ids, str) and ids.lower() == "all":
        return np.asarray(available, dtype=np.int64)
    chosen = np.asarray(list(ids), dtype=np.int64)
    missing = np.setdiff1d(chosen, available)
    if len(missing):
        raise ValueError(f"body {int(missing[0])} is not a live {kind}")
    return chosen


def _evaluate(what: dict | None, bodies: list) -> dict:
    """Yade's ``what`` of the exporter: name -> expression of ``b`` (the Body), evaluated per body
    into a point or cell array (scalars, vectors or 3x3 matrices)."""
    return {name: np.array([np.asarray(eval(expression, {"np": np}, {"b": b}), dtype=float) for b in bodies],
                           dtype=float)
            for name, expression in (what or {}).items()}
