"""Yade's ``bodiesHandling``: the extent of a group of spheres or facets, moving and scaling
spheres, copying one. Bodies are given as ids or as Body objects of ``O``, or by ``mask`` alone
(the bodies whose mask shares a bit with it); with both, those of the list the mask selects.
Erased ids are skipped, and so are bodies of another shape (as in Yade). A sphere in a scene
keeps its radius in Talus, so ``spheresModify`` scales only copies (``copy=True``) or with
scale 1.
"""

from __future__ import annotations

import math
from numbers import Integral
from typing import Iterable

from talus.dem.core.bodies import sphere
from talus.dem.base.linalg import Quaternion, Vector3
from talus.dem.geometry.shapes import Facet, Sphere
from talus.dem.core.scenes import default_scene


def _bodies(ids: Iterable, mask: int, function: str) -> list:
    """The live bodies named by ``ids`` (ids or Body objects), in order, that ``mask`` selects
    (Yade's test: any mask >= 0)."""
    O = default_scene()
    bodies = []
    for item in ids:
        if isinstance(item, Integral):
            bodies.append(O.bodies[int(item)])
        elif hasattr(item, "state") and hasattr(item, "id"):
            bodies.append(item)
        else:
            raise TypeError(f"{function}: expected body ids or bodies, got {item!r}")
    return [b for b in bodies if b is not None and (mask < 0 or b.mask & mask)]


def _given(ids, mask: int, fewest: int, function: str) -> list:
    """Yade's choice of bodies: ``ids``, or without them every body ``mask`` selects (at least
    ``fewest`` of them, else Yade's RuntimeWarning, raised)."""
    if len(ids) >= 1:
        return _bodies(ids, mask, function)
    if mask < 0:
        raise RuntimeWarning("Only a list of particles with length > 1 can be analyzed" if fewest > 1
                             else "No bodies to modify")
    O = default_scene()
    chosen = _bodies([b for b in O.bodies if b is not None], mask, function)
    if len(chosen) < fewest:
        raise RuntimeWarning("Not enough bodies to analyze with given mask" if fewest > 1
                             else "No bodies to modify with given mask")
    return chosen


def _extent(boxes: list[tuple[int, Vector3, Vector3]]) -> dict:
    """Yade's dictionary for the bounding boxes (id, low corner, high corner) of some bodies:
    min, max, the ids reaching them per axis, center, extends, number."""
    low, high = Vector3.Zero, Vector3.Zero
    lowId, highId = Vector3.Zero, Vector3.Zero
    for k, (id, lo, hi) in enumerate(boxes):
        for axis in range(3):
            if k == 0 or hi[axis] > high[axis]:
                high[axis], highId[axis] = hi[axis], id
            if k == 0 or lo[axis] < low[axis]:
                low[axis], lowId[axis] = lo[axis], id
    return {"max": high, "min": low, "maxId": highId, "minId": lowId, "center": (high - low) / 2.0 + low,
            "extends": high - low, "number": len(boxes)}


def spheresPackDimensions(idSpheres=(), mask: int = -1) -> dict:
    """Extent of the spheres among ``idSpheres``: ``min``, ``max`` (corners of their bounding
    box), ``minId``, ``maxId`` (per axis, the sphere reaching it), ``center``, ``extends``,
    ``volume`` (of the spheres), ``mass``, ``number``."""
    spheres = [b for b in _given(idSpheres, mask, 2, "spheresPackDimensions") if isinstance(b.shape, Sphere)]
    boxes = []
    for b in spheres:
        r = b.shape.radius
        boxes.append((b.id, b.state.pos - Vector3(r, r, r), b.state.pos + Vector3(r, r, r)))
    dimensions = _extent(boxes)
    dimensions["volume"] = sum(4.0 / 3.0 * math.pi * b.shape.radius ** 3 for b in spheres)
    dimensions["mass"] = sum(b.state.mass for b in spheres)
    return dimensions


def facetsDimensions(idFacets=(), mask: int = -1) -> dict:
    """Extent of the facets among ``idFacets`` (from their vertices): ``min``, ``max``,
    ``minId``, ``maxId``, ``center``, ``extends``, ``number``."""
    boxes = []
    for b in _given(idFacets, mask, 2, "facetsDimensions"):
        if not isinstance(b.shape, Facet):
            continue
        corners = [b.state.pos + b.state.ori * v for v in b.shape.vertices]
        boxes.append((b.id, Vector3(*(min(c[a] for c in corners) for a in range(3))),
                      Vector3(*(max(c[a] for c in corners) for a in range(3)))))
    return _extent(boxes)


def spheresModify(idSpheres=(), mask: int = -1, shift=Vector3.Zero, scale: float = 1.0,
                  orientation=Quaternion((0, 1, 0), 0.0), copy: bool = False):
    """Turn the spheres of ``idSpheres`` by ``orientation`` and scale them by ``scale`` about
    the centre of their extent, then move them by ``shift``; with ``copy``, their copies
    instead (returned, to append). Returns True without ``copy``."""
    chosen = _given(idSpheres, mask, 1, "spheresModify")
    centre = spheresPackDimensions(chosen)["center"]
    copies = []
    for b in chosen:
        if not isinstance(b.shape, Sphere):
            continue
        if copy:
            b = sphereDuplicate(b)
        pos = orientation * (b.state.pos - centre) + centre
        if scale != 1.0:
            # A copy not yet appended gets its mass and inertia from the new radius, as Yade's
            # scaled ones (by scale^3 and scale^5, from the material's density).
            b.shape.radius *= scale
        b.state.pos = (pos - centre) * scale + centre + Vector3(shift)
        if copy:
            copies.append(b)
    return copies if copy else True


def sphereDuplicate(idSphere):
    """A copy of a sphere (its position, radius, material, dynamic flag and look) to append;
    False for a body that is not a sphere."""
    (b,) = _bodies([idSphere], -1, "sphereDuplicate") or (None,)
    if b is None or not isinstance(b.shape, Sphere):
        return False
    return sphere(b.state.pos, b.shape.radius, material=b.material, fixed=not b.dynamic, wire=b.shape.wire,
                  color=b.shape.color, highlight=b.shape.highlight, mask=b.mask)


__all__ = ["spheresPackDimensions", "facetsDimensions", "spheresModify", "sphereDuplicate"]
