"""What the contacts of the convex shapes (Potential Blocks, Potential Particles) share in Python,
as dem/shapes/ConvexContact.h does in C++: their geometry functors' 2D mode."""

from __future__ import annotations

import numpy as np


def two_dimension(geometry) -> tuple[bool, np.ndarray, float]:
    """The 2D mode of a convex shapes' geometry functor (Ig2_PB_PB_ScGeom, Ig2_PP_PP_ScGeom):
    twoDimension, the prisms' direction twoDdir (default (0, 1, 0)) and unitWidth2D (default 1)."""
    direction = (0.0, 1.0, 0.0) if geometry.twoDdir is None else tuple(float(x) for x in geometry.twoDdir)
    if len(direction) != 3:
        raise ValueError(f"{type(geometry).__name__}.twoDdir must be a 3-vector, got {geometry.twoDdir!r}")
    return (bool(geometry.twoDimension), np.asarray(direction, dtype=float),
            1.0 if geometry.unitWidth2D is None else float(geometry.unitWidth2D))


def geometry_functor(kind: type, engines: list):
    """The geometry functor of type ``kind`` whose settings a scene's convex contacts take: the
    first in an InteractionLoop of ``engines``, or one with the defaults."""
    for g in (g for e in engines for g in getattr(e, "geomFunctors", ())):
        if isinstance(g, kind):
            return g
    return kind()
