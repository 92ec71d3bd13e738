"""Boundary geometry made of facets (Yade's ``geom`` module)."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from talus.dem.bodies import BodySpec, facet

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


def facetBox(center: Sequence[float], extents: Sequence[float], wallMask: int = 63, material=-1,
             **_ignored) -> list[BodySpec]:
    """A box of 12 facets with half-sizes ``extents``; bit i of ``wallMask`` keeps face i
    (-x, +x, -y, +y, -z, +z), as in Yade."""
    c = np.asarray(center, dtype=float)
    e = np.asarray(extents, dtype=float)
    if c.shape != (3,) or e.shape != (3,) or np.any(e <= 0) or not np.all(np.isfinite(np.r_[c, e])):
        raise ValueError(f"facetBox: center and positive extents must be 3 finite numbers, got {center}, {extents}")
    corners = [c + e * np.array([1 if k & 1 else -1, 1 if k & 2 else -1, 1 if k & 4 else -1]) for k in range(8)]
    specs = []
    for face, triangles in enumerate(_FACE_TRIANGLES):
        if wallMask & (1 << face):
            specs += [facet([corners[i] for i in tri], material=material) for tri in triangles]
    return specs
