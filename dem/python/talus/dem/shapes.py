"""Shapes as Yade scripts read them: ``b.shape.radius``, ``isinstance(b.shape, Sphere)``,
``b.shape.vertices``. Each is a read-only view of one body's geometry in the scene's arrays
(Talus stores shapes per kind in C++; nothing is copied when a body is indexed)."""

from __future__ import annotations

import numpy as np

from talus import _dem
from talus.dem.appearance import check_color
from talus.dem.linalg import Quaternion, Vector3


class Shape:
    """Base of the shape views; ``str(shape)`` is the kind's name (``"Sphere"``, ...)."""

    __slots__ = ("_scene", "_id")

    def __init__(self, scene, id: int):
        self._scene, self._id = scene, id

    def _data(self) -> dict:
        return _dem.shape_data(self._scene._cpp, self._id)

    def _look(self):
        look = self._scene._appearance
        look.ensure(self._scene._cpp.bodyCount())
        return look

    @property
    def color(self) -> Vector3:
        """RGB colour in [0, 1], written to ParaView output (Yade's ``shape.color``)."""
        return Vector3(self._look().color[self._id])

    @color.setter
    def color(self, value):
        self._look().color[self._id] = check_color(value)

    highlight = property(lambda s: bool(s._look().highlight[s._id]),
                         lambda s, v: s._look().highlight.__setitem__(s._id, bool(v)),
                         doc="Yade's highlight flag: kept and written to ParaView output")
    wire = property(lambda s: bool(s._look().wire[s._id]),
                    lambda s, v: s._look().wire.__setitem__(s._id, bool(v)),
                    doc="Yade's wire-frame flag: kept and written to ParaView output")

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
    def vertices(self) -> list[Vector3]:
        return [Vector3(v) for v in self._data()["vertices"]]

    @property
    def normal(self) -> Vector3:
        return Vector3(self._data()["normal"])


class Box(Shape):
    __slots__ = ()

    @property
    def extents(self) -> Vector3:
        """Half-sizes along the body's axes."""
        return Vector3(_dem.box_extents(self._scene._cpp, self._id))


class Clump(Shape):
    __slots__ = ()

    @property
    def members(self) -> dict:
        """``{memberId: (relPos, relOri)}`` in ascending ids: each member's position and
        orientation in the clump's principal frame (Yade's Clump.members)."""
        ids, relPos, relOri = _dem.clump_members(self._scene._cpp, self._id)
        return {int(i): (Vector3(p), Quaternion(*q)) for i, p, q in zip(ids, relPos, relOri)}


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
