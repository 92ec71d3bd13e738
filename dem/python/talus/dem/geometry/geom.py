"""Boundary geometry made of facets (Yade's ``geom`` module)."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from talus.dem.core.bodies import BodySpec, facet

__all__ = ["facetBox", "facetCylinder", "facetCone", "facetBunker"]

# The corners of a box, indexed by (x, y, z) bits, and its faces as two triangles each, in the
# order Yade's facetBox uses (-x, +x, -y, +y, -z, +z), so the diagonals match Yade's.
_FACE_TRIANGLES = [
    ((0, 2, 6), (0, 6, 4)),   # -x
    ((1, 5, 7), (1, 7, 3)),   # +x
    ((0, 4, 5), (0, 5, 1)),   # -y
    ((2, 3, 7), (2, 7, 6)),   # +y
    ((0, 1, 3), (0, 3, 2)),   # -z
    ((4, 6, 7), (4, 7, 5)),   # +z
]


def facetBox(center: Sequence[float], extents: Sequence[float], orientation=(1.0, 0.0, 0.0, 0.0), wallMask: int = 63,
             material=-1, **_ignored) -> list[BodySpec]:
    """A box of 12 facets with half-sizes ``extents``, turned by ``orientation`` (a quaternion);
    bit i of ``wallMask`` keeps face i (-x, +x, -y, +y, -z, +z), as in Yade. A flat box (one
    extent zero) is the one rectangle of that axis's lower face, whatever the mask (Yade's)."""
    c = np.asarray(center, dtype=float)
    e = np.asarray(extents, dtype=float)
    if c.shape != (3,) or e.shape != (3,) or np.any(e < 0) or not np.all(np.isfinite(np.r_[c, e])):
        raise ValueError(f"facetBox: center and extents (>= 0) must be 3 finite numbers, got {center}, {extents}")
    if np.count_nonzero(e) < 2:
        raise ValueError(f"facetBox: at least two extents must be non-zero, got {extents}")
    if np.count_nonzero(e) == 2:
        wallMask = 1 << (2 * int(np.flatnonzero(e == 0)[0]))
    local = [e * np.array([1 if k & 1 else -1, 1 if k & 2 else -1, 1 if k & 4 else -1]) for k in range(8)]
    corners = list(_rotate(orientation, np.array(local)) + c)
    specs = []
    for face, triangles in enumerate(_FACE_TRIANGLES):
        if wallMask & (1 << face):
            specs += [facet([corners[i] for i in tri], material=material) for tri in triangles]
    return specs


def _rotate(q, v: np.ndarray) -> np.ndarray:
    """Rotate rows of ``v`` by quaternion ``q`` = (w, x, y, z) or an object with w, x, y, z."""
    if hasattr(q, "w"):
        q = (q.w, q.x, q.y, q.z)
    w, x, y, z = (float(c) for c in q)
    n = np.sqrt(w * w + x * x + y * y + z * z)
    if not n > 0:
        raise ValueError(f"orientation must be a non-zero quaternion (w, x, y, z), got {q!r}")
    w, x, y, z = w / n, x / n, y / n, z / n
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return v @ R.T


def _revolution(name: str, center, radiusTop: float, radiusBottom: float, height: float, orientation, segmentsNumber: int,
                wallMask: int, angleRange, material) -> list[BodySpec]:
    """Facets of a cylinder or cone about z (before ``orientation``): top disc (mask 1), bottom
    disc (2), side (4), in Yade's triangles and vertex order."""
    c = np.asarray(center, dtype=float)
    if c.shape != (3,) or not np.all(np.isfinite(c)):
        raise ValueError(f"{name}: center must be 3 finite numbers, got {center!r}")
    if not (radiusTop > 0 and radiusBottom > 0):
        raise ValueError(f"{name}: the radii must be positive, got {radiusTop}, {radiusBottom}")
    if not height >= 0:
        raise ValueError(f"{name}: height must be >= 0, got {height}")
    if segmentsNumber < 3:
        raise ValueError(f"{name}: segmentsNumber must be at least 3, got {segmentsNumber}")
    lo, hi = angleRange if angleRange is not None else (0.0, 2 * np.pi)
    if hi < lo or hi - lo > 2 * np.pi:
        raise ValueError(f"{name}: angleRange must be (min, max) with 0 <= max - min <= 2 pi, got {angleRange!r}")
    angles = np.linspace(lo, hi, segmentsNumber + 1, endpoint=True)
    ring = np.c_[np.cos(angles), np.sin(angles)]
    top = np.r_[[[0.0, 0.0, height / 2]], np.c_[radiusTop * ring, np.full(len(ring), height / 2)]]
    bottom = np.r_[[[0.0, 0.0, -height / 2]], np.c_[radiusBottom * ring, np.full(len(ring), -height / 2)]]
    top, bottom = _rotate(orientation, top) + c, _rotate(orientation, bottom) + c
    specs = []
    for i in range(2, len(top)):
        if wallMask & 1:
            specs.append(facet((top[0], top[i], top[i - 1]), material=material))
        if wallMask & 2:
            specs.append(facet((bottom[0], bottom[i - 1], bottom[i]), material=material))
        if wallMask & 4:
            specs.append(facet((top[i], bottom[i], bottom[i - 1]), material=material))
            specs.append(facet((bottom[i - 1], top[i - 1], top[i]), material=material))
    return specs


def facetCylinder(center: Sequence[float], radius: float, height: float, orientation=(1.0, 0.0, 0.0, 0.0),
                  segmentsNumber: int = 10, wallMask: int = 7, angleRange=None, material=-1,
                  **_ignored) -> list[BodySpec]:
    """A cylinder of facets (Yade's geom.facetCylinder), axis along z before ``orientation``
    (quaternion w, x, y, z) is applied, centred at ``center``. ``wallMask`` bits: 1 top disc,
    2 bottom disc, 4 side; ``angleRange`` (min, max) makes a part of it. The triangles and their
    vertex order are Yade's, so normals and contacts match."""
    if height == 0:
        wallMask = 1
    return _revolution("facetCylinder", center, radius, radius, height, orientation, segmentsNumber, wallMask,
                       angleRange, material)


def facetCone(center: Sequence[float], radiusTop: float, radiusBottom: float, height: float,
              orientation=(1.0, 0.0, 0.0, 0.0), segmentsNumber: int = 10, wallMask: int = 7, angleRange=None,
              material=-1, **_ignored) -> list[BodySpec]:
    """A truncated cone of facets (Yade's geom.facetCone): as :func:`facetCylinder` with the
    radius ``radiusTop`` at the top (+z) and ``radiusBottom`` at the bottom."""
    return _revolution("facetCone", center, radiusTop, radiusBottom, height, orientation, segmentsNumber, wallMask,
                       angleRange, material)


def facetBunker(center: Sequence[float], dBunker: float, dOutput: float, hBunker: float, hOutput: float,
                hPipe: float = 0.0, orientation=(1.0, 0.0, 0.0, 0.0), segmentsNumber: int = 10, wallMask: int = 4,
                angleRange=None, closeGap: bool = False, material=-1, **_ignored) -> list[BodySpec]:
    """A bunker of facets (Yade's geom.facetBunker), from its bottom at ``center`` up the z axis
    (before ``orientation``): a pipe of diameter ``dOutput`` and height ``hPipe``, a cone of
    height ``hOutput`` widening to ``dBunker``, a cylinder of diameter ``dBunker`` and height
    ``hBunker``. ``wallMask``: 1 the top disc, 2 the bottom disc, 4 the side walls."""
    if closeGap:
        raise NotImplementedError("facetBunker: closeGap is not available in Talus")
    if not dBunker > 0 or not dOutput > 0 or not hOutput > 0:
        raise ValueError(f"facetBunker: dBunker, dOutput and hOutput must be positive, got {dBunker}, {dOutput}, {hOutput}")
    if not hBunker >= 0 or not hPipe >= 0:
        raise ValueError(f"facetBunker: hBunker and hPipe must be >= 0, got {hBunker}, {hPipe}")
    common = dict(segmentsNumber=segmentsNumber, angleRange=angleRange, material=material)
    parts = []
    if hPipe > 0 or wallMask & 2:
        parts += facetCylinder((0, 0, hPipe / 2), dOutput / 2, hPipe, wallMask=wallMask & 6, **common)
    parts += facetCone((0, 0, hPipe + hOutput / 2), dBunker / 2, dOutput / 2, hOutput, wallMask=wallMask & 4, **common)
    if hBunker > 0:
        parts += facetCylinder((0, 0, hPipe + hOutput + hBunker / 2), dBunker / 2, hBunker, wallMask=wallMask & 5,
                               **common)
    # Yade builds the parts about the origin and then turns and moves each facet
    c = np.asarray(center, dtype=float).reshape(3)
    return [facet(_rotate(orientation, np.array(f.vertices)) + c, material=material) for f in parts]
