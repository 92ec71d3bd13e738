"""Packings (Yade's ``pack`` module): regular lattices clipped by a predicate.

A predicate is a solid: ``pred(point, pad)`` says whether a sphere of radius ``pad`` centred at
``point`` lies inside, and ``pred.aabb()`` bounds it.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from talus.dem.bodies import BodySpec, sphere


class inSphere:
    """The ball of ``radius`` around ``center``."""

    def __init__(self, center: Sequence[float], radius: float):
        if not radius > 0:
            raise ValueError(f"inSphere: radius must be positive, got {radius}")
        self.center, self.radius = np.asarray(center, dtype=float), float(radius)

    def __call__(self, point, pad: float = 0.0) -> bool:
        return float(np.linalg.norm(np.asarray(point) - self.center)) <= self.radius - pad

    def aabb(self):
        return self.center - self.radius, self.center + self.radius


class inAlignedBox:
    """The axis-aligned box between corners ``minAabb`` and ``maxAabb``."""

    def __init__(self, minAabb: Sequence[float], maxAabb: Sequence[float]):
        self.lo, self.hi = np.asarray(minAabb, dtype=float), np.asarray(maxAabb, dtype=float)
        if np.any(self.hi <= self.lo):
            raise ValueError(f"inAlignedBox: maxAabb must exceed minAabb, got {minAabb}, {maxAabb}")

    def __call__(self, point, pad: float = 0.0) -> bool:
        p = np.asarray(point)
        return bool(np.all(p - pad >= self.lo) and np.all(p + pad <= self.hi))

    def aabb(self):
        return self.lo, self.hi


def _lattice(predicate, radius: float, gap: float, kind: str, **kw) -> list[BodySpec]:
    if not radius > 0 or gap < 0:
        raise ValueError(f"regular packing: radius must be positive and gap >= 0, got {radius}, {gap}")
    a = 2 * radius + gap
    lo, hi = (np.asarray(x, dtype=float) for x in predicate.aabb())
    dim = hi - lo
    if not np.all(np.isfinite(dim)):
        raise ValueError("regular packing: the predicate's bounding box must be finite")
    spheres = []
    if kind == "hexa":
        # Simple hcp lattice: layers k at heights 2 sqrt(6)/3 k (a/2), rows j shifted by half a
        # sphere on odd (j + k), odd layers shifted by a third of a row.
        hy, hz = a * math.sqrt(3) / 2, a * math.sqrt(6) / 3
        counts = (int(dim[0] / a) + 1, int(dim[1] / hy) + 1, int(dim[2] / hz) + 1)
        for i in range(counts[0]):
            for j in range(counts[1]):
                for k in range(counts[2]):
                    p = np.array([2 * i + (j + k) % 2, math.sqrt(3.0) * (j + (k % 2) / 3.0),
                                  2.0 * math.sqrt(6.0) / 3.0 * k]) * (a / 2.0) + lo
                    if predicate(p, radius):
                        spheres.append(sphere(p, radius, **kw))
    else:
        counts = tuple(int(d / a) + 1 for d in dim)
        for i in range(counts[0]):
            for j in range(counts[1]):
                for k in range(counts[2]):
                    p = lo + radius + a * np.array([i, j, k])
                    if predicate(p, radius):
                        spheres.append(sphere(p, radius, **kw))
    return spheres


def regularHexa(predicate, radius: float, gap: float, **kw) -> list[BodySpec]:
    """Spheres of ``radius`` on a hexagonal close-packed lattice with ``gap`` between
    neighbours, kept where ``predicate`` holds (Yade's pack.regularHexa)."""
    return _lattice(predicate, radius, gap, "hexa", **kw)


def regularOrtho(predicate, radius: float, gap: float, **kw) -> list[BodySpec]:
    """Spheres on a simple cubic lattice of spacing 2 radius + gap (Yade's pack.regularOrtho)."""
    return _lattice(predicate, radius, gap, "ortho", **kw)
