"""Triangulated surfaces with the interface of PyGTS (the ``gts`` module Yade ships, bindings to
the GNU Triangulated Surface library), in Python and numpy: the part Yade's scripts use to
build boundaries and to fill closed surfaces with spheres.

    import gts
    s = gts.read(open("horse.gts"))            # or built: Vertex -> Edge -> Face -> Surface
    s.is_closed(), s.volume(), s.area()
    gts.Point(0, 0, 0).is_inside(s)

What is here: ``Point``, ``Vertex``, ``Segment``/``Edge``, ``Triangle``/``Face`` (built from three
edges, as GTS, or from three vertices), ``Surface`` (``add``, ``faces``, ``vertices``, ``edges``,
``is_closed``, ``is_manifold``, ``is_orientable``, ``volume``, ``area``, ``center_of_mass``,
``cleanup``, ``translate``, ``scale``, ``rotate``, ``copy``, ``write``), ``read`` (GTS files) and
``Point.is_inside``. Boolean operations between surfaces, coarsening and refinement are not.

Topology is by vertex identity: two faces share an edge when they share its two vertices, as
GTS's faces built on shared ``Vertex`` objects do. A face keeps the vertex order GTS gives it
(``gts_triangle_vertices``: from its first two edges), so facets made from a surface have the
vertices in the order Yade's have. The inside test is the winding number of the surface about
the point (exact for a closed surface, whatever its orientation).
"""

from __future__ import annotations

import math
from typing import Iterable

import numpy as np

__all__ = ["Point", "Vertex", "Segment", "Edge", "Triangle", "Face", "Surface", "read"]


class Point:
    """A point in space."""

    def __init__(self, x: float = 0.0, y: float = 0.0, z: float = 0.0):
        self.x, self.y, self.z = float(x), float(y), float(z)

    def coords(self) -> tuple:
        return (self.x, self.y, self.z)

    def set(self, x: float = 0.0, y: float = 0.0, z: float = 0.0):
        self.x, self.y, self.z = float(x), float(y), float(z)

    def distance(self, other) -> float:
        return math.dist(self.coords(), other.coords())

    def is_inside(self, surface: "Surface") -> bool:
        """Whether the point is inside the closed ``surface``."""
        if not surface.is_closed():
            raise ValueError("Point.is_inside: the surface is not closed")
        w = winding_numbers(np.array([self.coords()]), surface._triangles())[0]
        return bool(abs(w) > .5)

    def __repr__(self):
        return f"{type(self).__name__}({self.x:g}, {self.y:g}, {self.z:g})"


class Vertex(Point):
    """A point that edges and faces are made of (shared by identity)."""


class Segment:
    """The segment between two vertices ``v1`` and ``v2``."""

    def __init__(self, v1: Vertex, v2: Vertex):
        if not (isinstance(v1, Vertex) and isinstance(v2, Vertex)):
            raise TypeError(f"{type(self).__name__}: v1 and v2 must be gts.Vertex, got {v1!r}, {v2!r}")
        if v1 is v2:
            raise ValueError(f"{type(self).__name__}: v1 and v2 must be different vertices")
        self.v1, self.v2 = v1, v2

    def vertices(self) -> tuple:
        return (self.v1, self.v2)

    def __repr__(self):
        return f"{type(self).__name__}({self.v1!r}, {self.v2!r})"


class Edge(Segment):
    """An edge of faces."""


def _triangle_vertices(e1: Segment, e2: Segment) -> tuple:
    """The vertex order GTS gives a triangle of edges e1, e2, ...: e1's vertices, the one shared
    with e2 second, then e2's other vertex."""
    if e1.v2 is e2.v1:
        return e1.v1, e1.v2, e2.v2
    if e1.v2 is e2.v2:
        return e1.v1, e1.v2, e2.v1
    if e1.v1 is e2.v1:
        return e1.v2, e1.v1, e2.v2
    return e1.v2, e1.v1, e2.v1


class Triangle:
    """A triangle, from three edges forming a loop (as GTS) or from three vertices."""

    def __init__(self, a, b, c):
        items = (a, b, c)
        if all(isinstance(x, Segment) for x in items):
            ends = [{id(e.v1), id(e.v2)} for e in items]
            if not all(len(ends[i] & ends[(i + 1) % 3]) == 1 for i in range(3)) or len(set().union(*ends)) != 3:
                raise ValueError(f"{type(self).__name__}: the three edges do not form a triangle")
            self._v = _triangle_vertices(a, b)
        elif all(isinstance(x, Vertex) for x in items):
            if len({id(x) for x in items}) != 3:
                raise ValueError(f"{type(self).__name__}: the three vertices must be different")
            self._v = items
        else:
            raise TypeError(f"{type(self).__name__}: give three gts.Edge or three gts.Vertex, got {items!r}")

    def vertices(self) -> tuple:
        return self._v

    def revert(self):
        """Turn the face over (its normal flips)."""
        self._v = (self._v[0], self._v[2], self._v[1])

    def _coords(self) -> np.ndarray:
        return np.array([v.coords() for v in self._v])

    def normal(self) -> tuple:
        a, b, c = self._coords()
        return tuple(np.cross(b - a, c - a))

    def area(self) -> float:
        return float(np.linalg.norm(self.normal()) / 2)

    def __repr__(self):
        return f"{type(self).__name__}{self._v!r}"


class Face(Triangle):
    """A triangle of a surface."""


class Surface:
    """Faces sharing vertices (and so edges)."""

    def __init__(self):
        self._faces: list[Face] = []
        self._ids: set[int] = set()

    # -- content ---------------------------------------------------------------------------------
    def add(self, item):
        """Add a face, or every face of another surface."""
        if isinstance(item, Surface):
            for f in item._faces:
                self.add(f)
            return
        if not isinstance(item, Face):
            raise TypeError(f"Surface.add: a gts.Face or gts.Surface, got {item!r}")
        if id(item) not in self._ids:
            self._ids.add(id(item))
            self._faces.append(item)

    def remove(self, face: Face):
        if id(face) not in self._ids:
            raise ValueError("Surface.remove: the face is not in the surface")
        self._ids.discard(id(face))
        self._faces = [f for f in self._faces if f is not face]

    def faces(self) -> list:
        return list(self._faces)

    def __iter__(self):
        return iter(list(self._faces))

    def vertices(self) -> list:
        seen, out = set(), []
        for f in self._faces:
            for v in f.vertices():
                if id(v) not in seen:
                    seen.add(id(v))
                    out.append(v)
        return out

    def _edge_faces(self) -> dict:
        """Per edge (its two vertices' ids), the faces using it, each with its direction (+1 if
        the face runs the edge from the lower id to the higher)."""
        edges: dict = {}
        for f in self._faces:
            v = f.vertices()
            for i in range(3):
                a, b = id(v[i]), id(v[(i + 1) % 3])
                key = (min(a, b), max(a, b))
                edges.setdefault(key, (v[i], v[(i + 1) % 3], []))[2].append(1 if a < b else -1)
        return edges

    def edges(self) -> list:
        return [Edge(a, b) for a, b, _ in self._edge_faces().values()]

    @property
    def Nvertices(self) -> int:
        return len(self.vertices())

    @property
    def Nedges(self) -> int:
        return len(self._edge_faces())

    @property
    def Nfaces(self) -> int:
        return len(self._faces)

    def _triangles(self) -> np.ndarray:
        """The faces as an (n, 3, 3) array of vertex coordinates."""
        return np.array([f._coords() for f in self._faces]).reshape(-1, 3, 3)

    # -- topology and measures -------------------------------------------------------------------
    def is_manifold(self) -> bool:
        """Every edge has at most two faces."""
        return all(len(d) <= 2 for _, _, d in self._edge_faces().values())

    def is_closed(self) -> bool:
        """Every edge has exactly two faces (a watertight surface)."""
        edges = self._edge_faces()
        return bool(edges) and all(len(d) == 2 for _, _, d in edges.values())

    def is_orientable(self) -> bool:
        """The two faces of every shared edge run it in opposite directions."""
        return all(len(d) < 2 or (len(d) == 2 and d[0] != d[1]) for _, _, d in self._edge_faces().values())

    def area(self) -> float:
        t = self._triangles()
        return float(np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1).sum() / 2)

    def volume(self) -> float:
        """Signed volume enclosed (positive when the faces' normals point outwards)."""
        t = self._triangles()
        return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6)

    def center_of_mass(self) -> tuple:
        t = self._triangles()
        v = np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])) / 6
        if not v.sum() != 0:
            raise ValueError("Surface.center_of_mass: the surface encloses no volume")
        return tuple((v[:, None] * t.sum(axis=1) / 4).sum(axis=0) / v.sum())

    def boundary(self) -> list:
        """The edges with one face only."""
        return [Edge(a, b) for a, b, d in self._edge_faces().values() if len(d) == 1]

    # -- changes ---------------------------------------------------------------------------------
    def cleanup(self, threshold: float = 0.0):
        """Merge vertices closer than ``threshold``, then drop the faces that became degenerate
        and faces repeated on the same three vertices (GTS's surface cleanup)."""
        vertices = self.vertices()
        if threshold > 0 and vertices:
            xyz = np.array([v.coords() for v in vertices])
            keep: list[int] = []          # representatives, in order of first appearance
            merged: dict[int, Vertex] = {}
            for k, v in enumerate(vertices):
                if keep:
                    d = np.linalg.norm(xyz[keep] - xyz[k], axis=1)
                    near = int(np.argmin(d))
                    if d[near] < threshold:
                        merged[id(v)] = vertices[keep[near]]
                        continue
                keep.append(k)
            for f in self._faces:
                f._v = tuple(merged.get(id(v), v) for v in f._v)
        faces, seen = [], set()
        for f in self._faces:
            key = frozenset(id(v) for v in f._v)
            if len(key) == 3 and key not in seen:
                seen.add(key)
                faces.append(f)
        self._faces, self._ids = faces, {id(f) for f in faces}

    def _apply(self, transform):
        for v in self.vertices():
            v.set(*transform(np.array(v.coords())))

    def translate(self, dx: float = 0.0, dy: float = 0.0, dz: float = 0.0):
        self._apply(lambda p: p + (dx, dy, dz))

    def scale(self, dx: float = 1.0, dy: float = 1.0, dz: float = 1.0):
        self._apply(lambda p: p * (dx, dy, dz))

    def rotate(self, dx: float = 0.0, dy: float = 0.0, dz: float = 0.0, a: float = 0.0):
        """Rotate by angle ``a`` about the axis (dx, dy, dz) through the origin."""
        axis = np.array([dx, dy, dz], dtype=float)
        if not np.linalg.norm(axis) > 0:
            raise ValueError("Surface.rotate: the axis (dx, dy, dz) must be non-zero")
        k = axis / np.linalg.norm(axis)
        self._apply(lambda p: p * math.cos(a) + np.cross(k, p) * math.sin(a) + k * np.dot(k, p) * (1 - math.cos(a)))

    def copy(self, other: "Surface" | None = None) -> "Surface":
        """A deep copy (new vertices and faces); with ``other``, this surface becomes its copy."""
        source = self if other is None else other
        new = {id(v): Vertex(*v.coords()) for v in source.vertices()}
        target = Surface() if other is None else self
        target._faces, target._ids = [], set()
        for f in source._faces:
            target.add(Face(*(new[id(v)] for v in f.vertices())))
        return target

    def write(self, file):
        """Write the surface in the GTS file format (to an open text file)."""
        vertices = self.vertices()
        index = {id(v): k + 1 for k, v in enumerate(vertices)}
        edges = list(self._edge_faces())
        edge_index = {e: k + 1 for k, e in enumerate(edges)}
        file.write(f"{len(vertices)} {len(edges)} {len(self._faces)} GtsSurface GtsFace GtsEdge GtsVertex\n")
        for v in vertices:
            file.write(f"{v.x!r} {v.y!r} {v.z!r}\n")
        for a, b in edges:
            file.write(f"{index[a]} {index[b]}\n")
        for f in self._faces:
            v = f.vertices()
            ids = [(min(id(v[i]), id(v[(i + 1) % 3])), max(id(v[i]), id(v[(i + 1) % 3]))) for i in range(3)]
            file.write(" ".join(str(edge_index[e]) for e in ids) + "\n")


def read(file) -> Surface:
    """A surface from a GTS file (an open file or a path): a line ``nv ne nf``, the vertices'
    coordinates, the edges as pairs of vertex numbers, the faces as triples of edge numbers
    (numbered from 1; ``#`` starts a comment)."""
    name = getattr(file, "name", str(file))
    if isinstance(file, (str, bytes)) or hasattr(file, "__fspath__"):
        with open(file) as f:
            return read(f)
    rows: list[tuple[int, list[str]]] = []
    for n, line in enumerate(file, 1):
        items = line.split("#", 1)[0].split()
        if items:
            rows.append((n, items))
    if not rows:
        raise ValueError(f"{name}: empty GTS file")

    def numbers(k, count, kind):
        line, items = rows[k]
        try:
            return [kind(x) for x in items[:count]]
        except (ValueError, IndexError):
            raise ValueError(f"{name}:{line}: expected {count} numbers, got {' '.join(items)!r}") from None

    nv, ne, nf = numbers(0, 3, int)
    if len(rows) < 1 + nv + ne + nf:
        raise ValueError(f"{name}: the header announces {nv} vertices, {ne} edges, {nf} faces; the file is shorter")
    vertices = [Vertex(*numbers(1 + k, 3, float)) for k in range(nv)]
    edges = []
    for k in range(ne):
        a, b = numbers(1 + nv + k, 2, int)
        if not (1 <= a <= nv and 1 <= b <= nv):
            raise ValueError(f"{name}:{rows[1 + nv + k][0]}: vertex number out of 1..{nv}")
        edges.append(Edge(vertices[a - 1], vertices[b - 1]))
    surface = Surface()
    for k in range(nf):
        ids = numbers(1 + nv + ne + k, 3, int)
        if not all(1 <= e <= ne for e in ids):
            raise ValueError(f"{name}:{rows[1 + nv + ne + k][0]}: edge number out of 1..{ne}")
        surface.add(Face(*(edges[e - 1] for e in ids)))
    return surface


def winding_numbers(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Per point, the winding number of the triangles about it: the sum of the signed solid
    angles of the triangles seen from the point over 4 pi (Van Oosterom and Strackee's formula)."""
    out = np.empty(len(points))
    for k, p in enumerate(points):
        r = triangles - p                                   # (n, 3, 3)
        n = np.linalg.norm(r, axis=2)
        a, b, c = r[:, 0], r[:, 1], r[:, 2]
        det = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (n[:, 0] * n[:, 1] * n[:, 2] + np.einsum("ij,ij->i", a, b) * n[:, 2]
               + np.einsum("ij,ij->i", a, c) * n[:, 1] + np.einsum("ij,ij->i", b, c) * n[:, 0])
        out[k] = 2 * np.arctan2(det, den).sum() / (4 * math.pi)
    return out
