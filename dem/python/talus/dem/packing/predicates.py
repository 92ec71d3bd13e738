"""Solids as predicates (Yade's ``pack`` predicates): ``pred(point, pad)`` says whether a sphere
of radius ``pad`` centred at ``point`` lies inside the solid (``pad`` 0: the point itself);
``pred.aabb()`` bounds the solid, ``dim()`` and ``center()`` follow from it.

Predicates combine as in Yade: ``a | b`` (PredicateUnion), ``a & b`` (PredicateIntersection),
``a - b`` (PredicateDifference: in ``a``, and ``b`` grown by the pad does not reach the
sphere), ``a ^ b`` (PredicateSymmetricDifference). A user class derived from :class:`Predicate`
that defines ``__call__`` and ``aabb`` combines as well.

The formulas, padding included, are Yade's (checked point by point against Yade 2023.02a), so
a packing clipped by a predicate keeps the same spheres; where Yade's padding is approximate
(inHyperboloid pads across the axis, inEllipsoid shrinks the semi-axes, inGtsSurface tests six
points at the pad's distance) Talus is approximate in the same way.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

__all__ = ["Predicate", "PredicateBoolean", "PredicateUnion", "PredicateIntersection", "PredicateDifference",
           "PredicateSymmetricDifference", "inSphere", "inAlignedBox", "inParallelepiped", "inCylinder",
           "inHyperboloid", "inEllipsoid", "notInNotch", "inSpace", "inHalfSpace", "inConvexPolyhedron", "inGtsSurface"]

_INF = float("inf")


def _vec(value, what: str) -> np.ndarray:
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{what} must be 3 finite numbers, got {value!r}")
    return v


def _vector3(v):
    from talus.dem.base.linalg import Vector3
    return Vector3(*(float(x) for x in v))


class Predicate:
    """A solid: subclasses define ``__call__(point, pad=0)`` and ``aabb()`` (a pair of corners)."""

    def __call__(self, point, pad: float = 0.0) -> bool:
        raise NotImplementedError(f"{type(self).__name__} defines no __call__(point, pad)")

    def aabb(self):
        raise NotImplementedError(f"{type(self).__name__} defines no aabb()")

    def dim(self):
        """Sizes of the bounding box."""
        lo, hi = self.aabb()
        return _vector3(np.asarray(hi, float) - np.asarray(lo, float))

    def center(self):
        """Centre of the bounding box."""
        lo, hi = self.aabb()
        return _vector3(.5 * (np.asarray(hi, float) + np.asarray(lo, float)))

    def __or__(self, other):
        return PredicateUnion(self, other)

    def __and__(self, other):
        return PredicateIntersection(self, other)

    def __sub__(self, other):
        return PredicateDifference(self, other)

    def __xor__(self, other):
        return PredicateSymmetricDifference(self, other)


class PredicateBoolean(Predicate):
    """Two predicates combined (``A`` and ``B``)."""

    def __init__(self, A, B):
        for name, p in (("A", A), ("B", B)):
            if not (callable(p) and hasattr(p, "aabb")):
                raise TypeError(f"{type(self).__name__}: {name} must be a predicate (callable with aabb()), got {p!r}")
        self.A, self.B = A, B

    def _boxes(self):
        (la, ha), (lb, hb) = self.A.aabb(), self.B.aabb()
        return [np.asarray(x, float) for x in (la, ha, lb, hb)]


class PredicateUnion(PredicateBoolean):
    """Inside ``A`` or inside ``B`` (``A | B``)."""

    def __call__(self, point, pad: float = 0.0) -> bool:
        return bool(self.A(point, pad) or self.B(point, pad))

    def aabb(self):
        la, ha, lb, hb = self._boxes()
        return _vector3(np.minimum(la, lb)), _vector3(np.maximum(ha, hb))


class PredicateIntersection(PredicateBoolean):
    """Inside both ``A`` and ``B`` (``A & B``)."""

    def __call__(self, point, pad: float = 0.0) -> bool:
        return bool(self.A(point, pad) and self.B(point, pad))

    def aabb(self):
        la, ha, lb, hb = self._boxes()
        return _vector3(np.maximum(la, lb)), _vector3(np.minimum(ha, hb))


class PredicateDifference(PredicateBoolean):
    """Inside ``A`` and outside ``B`` (``A - B``); the box is ``A``'s."""

    def __call__(self, point, pad: float = 0.0) -> bool:
        # the sphere must not reach into B: the point lies outside B grown by the pad
        return bool(self.A(point, pad) and not self.B(point, -pad))

    def aabb(self):
        return self.A.aabb()


class PredicateSymmetricDifference(PredicateBoolean):
    """Inside exactly one of ``A`` and ``B`` (``A ^ B``)."""

    def __call__(self, point, pad: float = 0.0) -> bool:
        return bool(self.A(point, pad)) != bool(self.B(point, pad))

    def aabb(self):
        la, ha, lb, hb = self._boxes()
        return _vector3(np.minimum(la, lb)), _vector3(np.maximum(ha, hb))


class inSphere(Predicate):
    """The ball of ``radius`` around ``center``."""

    def __init__(self, center, radius: float):
        if not radius > 0:
            raise ValueError(f"inSphere: radius must be positive, got {radius}")
        self._center, self.radius = _vec(center, "inSphere: center"), float(radius)

    def __call__(self, point, pad: float = 0.0) -> bool:
        return bool(np.linalg.norm(np.asarray(point, float) - self._center) <= self.radius - pad)

    def aabb(self):
        return _vector3(self._center - self.radius), _vector3(self._center + self.radius)


class inAlignedBox(Predicate):
    """The axis-aligned box between the corners ``minAABB`` and ``maxAABB``."""

    def __init__(self, minAABB, maxAABB):
        self.lo, self.hi = _vec(minAABB, "inAlignedBox: minAABB"), _vec(maxAABB, "inAlignedBox: maxAABB")
        if np.any(self.hi < self.lo):
            raise ValueError(f"inAlignedBox: maxAABB must not be below minAABB, got {minAABB}, {maxAABB}")

    def __call__(self, point, pad: float = 0.0) -> bool:
        p = np.asarray(point, float)
        return bool(np.all(self.lo + pad <= p) and np.all(self.hi - pad >= p))

    def aabb(self):
        return _vector3(self.lo), _vector3(self.hi)


class inParallelepiped(Predicate):
    """The parallelepiped with a corner at ``o`` whose edges from ``o`` end at ``a``, ``b``, ``c``."""

    def __init__(self, o, a, b, c):
        o, a, b, c = (_vec(v, f"inParallelepiped: {n}") for v, n in ((o, "o"), (a, "a"), (b, "b"), (c, "c")))
        x, y, z = a - o, b - o, c - o
        if abs(np.dot(np.cross(x, y), z)) == 0:
            raise ValueError("inParallelepiped: the edges o-a, o-b, o-c span no volume")
        # outer normals of the faces through o (-) and through the opposite corner (+)
        self._planes = []
        for u, v, w in ((y, z, x), (z, x, y), (x, y, z)):
            n = np.cross(u, v)
            n /= np.linalg.norm(n)
            if np.dot(n, w) > 0:
                n = -n
            self._planes += [(o, n), (o + w, -n)]
        corners = np.array([o + i * x + j * y + k * z for i in (0, 1) for j in (0, 1) for k in (0, 1)])
        self.lo, self.hi = corners.min(axis=0), corners.max(axis=0)

    def __call__(self, point, pad: float = 0.0) -> bool:
        p = np.asarray(point, float)
        return all(np.dot(p - q, n) <= -pad for q, n in self._planes)

    def aabb(self):
        return _vector3(self.lo), _vector3(self.hi)


class inCylinder(Predicate):
    """The cylinder of ``radius`` whose axis goes from ``centerBottom`` to ``centerTop``."""

    def __init__(self, centerBottom, centerTop, radius: float):
        self.c1, self.c2 = _vec(centerBottom, "inCylinder: centerBottom"), _vec(centerTop, "inCylinder: centerTop")
        self.axis = self.c2 - self.c1
        self.height = float(np.linalg.norm(self.axis))
        if not self.height > 0:
            raise ValueError("inCylinder: centerBottom and centerTop must differ")
        if not radius > 0:
            raise ValueError(f"inCylinder: radius must be positive, got {radius}")
        self.radius = float(radius)

    def _along_and_across(self, point):
        p = np.asarray(point, float)
        along = np.dot(p - self.c1, self.axis) / self.height
        across = np.linalg.norm(np.cross(p - self.c1, p - self.c2)) / self.height
        return along, across

    def __call__(self, point, pad: float = 0.0) -> bool:
        along, across = self._along_and_across(point)
        return bool(pad <= along <= self.height - pad and across <= self.radius - pad)

    def aabb(self):
        # a disc of normal n spans radius sqrt(1 - n_i^2) along axis i
        n = self.axis / self.height
        k = np.sqrt(np.maximum(0.0, 1 - n * n))
        return (_vector3(np.minimum(self.c1, self.c2) - self.radius * k),
                _vector3(np.maximum(self.c1, self.c2) + self.radius * k))


class inHyperboloid(inCylinder):
    """The one-sheet hyperboloid of revolution from ``centerBottom`` to ``centerTop``, of radius
    ``radius`` at its ends and ``skirt`` in the middle (Yade's: the pad is measured across the
    axis, not normal to the surface)."""

    def __init__(self, centerBottom, centerTop, radius: float, skirt: float):
        super().__init__(centerBottom, centerTop, radius)
        if not 0 < skirt < radius:
            raise ValueError(f"inHyperboloid: skirt must be in (0, radius), got {skirt} with radius {radius}")
        self.skirt = float(skirt)
        # r(u) = skirt sqrt(1 + u^2), u = (t - h/2) / c, with r = radius at the ends
        self._c = self.height / (2 * math.sqrt((self.radius / self.skirt) ** 2 - 1))

    def __call__(self, point, pad: float = 0.0) -> bool:
        along, across = self._along_and_across(point)
        if not pad <= along <= self.height - pad:
            return False
        u = (along - self.height / 2) / self._c
        return bool(across <= self.skirt * math.sqrt(1 + u * u) - pad)


class inEllipsoid(Predicate):
    """The axis-aligned ellipsoid of semi-axes ``abc`` around ``centerPoint`` (Yade's padding: the
    semi-axes shrink by the pad)."""

    def __init__(self, centerPoint, abc):
        self._center, self.abc = _vec(centerPoint, "inEllipsoid: centerPoint"), _vec(abc, "inEllipsoid: abc")
        if np.any(self.abc <= 0):
            raise ValueError(f"inEllipsoid: the semi-axes abc must be positive, got {abc!r}")

    def __call__(self, point, pad: float = 0.0) -> bool:
        d = np.asarray(point, float) - self._center
        return bool(np.sum((d / (self.abc - pad)) ** 2) <= 1) if np.all(self.abc > pad) else False

    def aabb(self):
        return _vector3(self._center - self.abc), _vector3(self._center + self.abc)


class notInNotch(Predicate):
    """Everything but an infinite notch (Yade's): the slab of width ``aperture`` around the plane
    through ``centerPoint`` of normal ``normal``, on the side ``edge x normal`` of the notch's
    edge (along ``edge``). Unbounded: intersect it (``&``) with a bounded predicate."""

    def __init__(self, centerPoint, edge, normal, aperture: float):
        self.c = _vec(centerPoint, "notInNotch: centerPoint")
        edge, normal = _vec(edge, "notInNotch: edge"), _vec(normal, "notInNotch: normal")
        if not np.linalg.norm(edge) > 0:
            raise ValueError("notInNotch: edge must be a non-zero vector")
        self.edge = edge / np.linalg.norm(edge)
        normal = normal - self.edge * np.dot(self.edge, normal)
        if not np.linalg.norm(normal) > 0:
            raise ValueError("notInNotch: normal must not be parallel to edge")
        self.normal = normal / np.linalg.norm(normal)
        self.inside = np.cross(self.edge, self.normal)
        if not aperture >= 0:
            raise ValueError(f"notInNotch: aperture must be >= 0, got {aperture}")
        self.aperture = float(aperture)

    def __call__(self, point, pad: float = 0.0) -> bool:
        d = np.asarray(point, float) - self.c
        up = np.dot(self.normal, d) - self.aperture / 2
        down = -np.dot(self.normal, d) - self.aperture / 2
        behind = -np.dot(self.inside, d)        # distance behind the notch's edge
        if behind >= pad or up >= pad or down >= pad:
            return True
        if behind < 0:
            return False
        # near the edge, above or below the notch. Yade uses the distance above in both cases
        # (also for a point below); kept, so that both programs keep the same spheres.
        if up > 0 or down > 0:
            return bool(math.hypot(behind, up) >= pad)
        return False

    def aabb(self):
        return _vector3((-_INF,) * 3), _vector3((_INF,) * 3)


class inSpace(Predicate):
    """All of space (an unbounded box); ``center()`` is the given point."""

    def __init__(self, _center=(0.0, 0.0, 0.0)):
        self._center = _vec(_center, "inSpace: center")

    def __call__(self, point, pad: float = 0.0) -> bool:
        return True

    def aabb(self):
        return _vector3((-_INF,) * 3), _vector3((_INF,) * 3)

    def center(self):
        return _vector3(self._center)

    def dim(self):
        return _vector3((_INF,) * 3)


class inHalfSpace(Predicate):
    """The half-space on the side ``_dir`` of the plane through ``_center`` (normal ``_dir``)."""

    def __init__(self, _center=(0.0, 0.0, 0.0), _dir=(1.0, 0.0, 0.0)):
        self._center, d = _vec(_center, "inHalfSpace: center"), _vec(_dir, "inHalfSpace: direction")
        if not np.linalg.norm(d) > 0:
            raise ValueError("inHalfSpace: the direction must be a non-zero vector")
        self._dir = d / np.linalg.norm(d)

    def __call__(self, point, pad: float = 0.0) -> bool:
        return bool(np.dot(self._dir, np.asarray(point, float) - self._center) > pad)

    def aabb(self):
        lo, hi = np.full(3, -_INF), np.full(3, _INF)
        for k in range(3):          # bounded only along an axis the plane is normal to
            if np.count_nonzero(self._dir) == 1 and self._dir[k] != 0:
                if self._dir[k] > 0:
                    lo[k] = self._center[k]
                else:
                    hi[k] = self._center[k]
        return _vector3(lo), _vector3(hi)

    def center(self):
        return _vector3(self._center)

    def dim(self):
        return _vector3((_INF,) * 3)


class inConvexPolyhedron(Predicate):
    """Inside every plane of ``planes``, a sequence of (point, normal) with the normals pointing
    inwards: a point is inside when it is at least ``pad`` inside each plane (Yade's)."""

    def __init__(self, planes):
        planes = list(planes)
        if len(planes) < 4:
            raise ValueError(f"inConvexPolyhedron: a bounded polyhedron needs at least 4 planes, got {len(planes)}")
        self._points = np.array([_vec(p, "inConvexPolyhedron: plane point") for p, _ in planes])
        normals = np.array([_vec(n, "inConvexPolyhedron: plane normal") for _, n in planes])
        lengths = np.linalg.norm(normals, axis=1)
        if not np.all(lengths > 0):
            raise ValueError("inConvexPolyhedron: every plane needs a non-zero normal")
        self._normals = normals / lengths[:, None]
        self._lo, self._hi = self._corners()

    def _inside_by(self, point) -> np.ndarray:
        return np.einsum("ij,ij->i", self._normals, np.asarray(point, float) - self._points)

    def __call__(self, point, pad: float = 0.0) -> bool:
        return bool(np.all(self._inside_by(point) >= pad))

    def _corners(self):
        """The bounding box of the polyhedron's vertices: the intersections of three planes
        inside all the others."""
        offsets = np.einsum("ij,ij->i", self._normals, self._points)
        vertices = []
        for trio in itertools.combinations(range(len(self._normals)), 3):
            a = self._normals[list(trio)]
            if abs(np.linalg.det(a)) < 1e-12:
                continue
            x = np.linalg.solve(a, offsets[list(trio)])
            if np.all(self._inside_by(x) >= -1e-9 * max(1.0, np.abs(x).max())):
                vertices.append(x)
        if not vertices:
            raise ValueError("inConvexPolyhedron: the planes do not bound a polyhedron")
        vertices = np.array(vertices)
        return vertices.min(axis=0), vertices.max(axis=0)

    def aabb(self):
        return _vector3(self._lo), _vector3(self._hi)


class inGtsSurface(Predicate):
    """Inside a closed triangulated surface (a :class:`gts.Surface`). With a pad, the point and
    the six points at the pad's distance along the axes must be inside (Yade's approximation);
    ``noPad`` tests the point only."""

    def __init__(self, surface, noPad: bool = False):
        from talus.dem.geometry import gts
        if not isinstance(surface, gts.Surface):
            raise TypeError(f"inGtsSurface: surface must be a gts.Surface, got {type(surface).__name__}")
        if not surface.is_closed():
            raise ValueError("inGtsSurface: the surface is not closed")
        self.surf, self.noPad = surface, bool(noPad)
        self._triangles = surface._triangles()
        self._outward = surface.volume() >= 0

    def __call__(self, point, pad: float = 0.0) -> bool:
        from talus.dem.geometry.gts import winding_numbers
        p = np.asarray(point, float)
        points = [p] if self.noPad or pad == 0 else [p] + [p + s * pad * e for e in np.eye(3) for s in (-1, 1)]
        w = winding_numbers(np.array(points), self._triangles)
        return bool(np.all(w > .5 if self._outward else w < -.5))

    def aabb(self):
        v = self._triangles.reshape(-1, 3)
        return _vector3(v.min(axis=0)), _vector3(v.max(axis=0))

    def surface(self):
        return self.surf
