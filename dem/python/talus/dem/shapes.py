"""Shapes as Yade scripts read them: ``b.shape.radius``, ``isinstance(b.shape, Sphere)``,
``b.shape.vertices``. Each is a read-only view of one body's geometry in the scene's arrays
(Talus stores shapes per kind in C++; nothing is copied when a body is indexed)."""

from __future__ import annotations

import numpy as np

from talus import _dem


class Shape:
    """Base of the shape views; ``str(shape)`` is the kind's name (``"Sphere"``, ...)."""

    __slots__ = ("_scene", "_id")

    def __init__(self, scene, id: int):
        self._scene, self._id = scene, id

    def _data(self) -> dict:
        return _dem.shape_data(self._scene._cpp, self._id)

    def __str__(self):
        return type(self).__name__

    def __eq__(self, other):
        # ``b.shape == "Sphere"`` keeps working (scripts written when shapes were kind names).
        if isinstance(other, str):
            return other == type(self).__name__
        return isinstance(other, Shape) and (type(other), other._scene, other._id) == (type(self), self._scene, self._id)

    def __hash__(self):
        return hash((type(self).__name__, self._id))

    def __repr__(self):
        return f"<{type(self).__name__} of body {self._id}>"


class Sphere(Shape):
    __slots__ = ()

    @property
    def radius(self) -> float:
        return float(self._scene._cpp.radius()[self._id])


class Wall(Shape):
    """An infinite plane normal to ``axis``; ``sense`` -1/+1/0: which side interacts."""
    __slots__ = ()

    @property
    def axis(self) -> int:
        return int(self._data()["axis"])

    @property
    def sense(self) -> int:
        return int(self._data()["sense"])


class Facet(Shape):
    """A triangle; ``vertices`` and ``normal`` in the body's frame, relative to its position (as Yade)."""
    __slots__ = ()

    @property
    def vertices(self) -> list[np.ndarray]:
        return [np.array(v) for v in self._data()["vertices"]]

    @property
    def normal(self) -> np.ndarray:
        return np.array(self._data()["normal"])


class Box(Shape):
    __slots__ = ()

    @property
    def extents(self) -> np.ndarray:
        """Half-sizes along the body's axes."""
        return np.array(_dem.box_extents(self._scene._cpp, self._id))


class Clump(Shape):
    __slots__ = ()

    @property
    def members(self) -> list[int]:
        """Ids of the member bodies."""
        return list(_dem.clump_members(self._scene._cpp, self._id))


_BY_KIND = {cls.__name__: cls for cls in (Sphere, Wall, Facet, Box, Clump)}


def shape_of(scene, id: int):
    kind = scene._cpp.shapeKind(id)
    if kind == "PotentialBlock":   # Yade's PotentialBlock shape: its planes, r, R, isBoundary
        from talus.dem.blocks import PotentialBlock
        s = _dem.block_shape(scene._cpp, id)   # planes in the body's principal frame
        n = np.asarray(s["normals"], dtype=float).reshape(-1, 3)
        return PotentialBlock(n[:, 0], n[:, 1], n[:, 2], s["d"], r=s["r"], R=s["R"], isBoundary=s["isBoundary"])
    if kind == "PotentialParticle":   # Yade's PotentialParticle shape: its planes, r, k, R, isBoundary
        from talus.dem.particles import PotentialParticle
        s = _dem.particle_shape(scene._cpp, id)   # planes in the shape frame
        n = np.asarray(s["normals"], dtype=float).reshape(-1, 3)
        return PotentialParticle(n[:, 0], n[:, 1], n[:, 2], s["d"], r=s["r"], k=s["k"], R=s["R"],
                                 isBoundary=s["isBoundary"])
    return _BY_KIND[kind](scene, id)
