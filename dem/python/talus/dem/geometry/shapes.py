"""Shapes as Yade scripts read and make them: ``b.shape.radius``, ``isinstance(b.shape, Sphere)``,
``b.shape.vertices``, ``Sphere(radius=0.1, color=(1, 0, 0))``.

A shape object is one of three things:

- a view of one body's geometry in a scene's arrays (``O.bodies[i].shape``; Talus stores shapes
  per kind in C++, nothing is copied when a body is indexed);
- a view of a body not yet appended (``utils.sphere(...).shape``, ``Body().shape``): it reads
  and writes that body's BodySpec, and the scene once the body is appended;
- a shape a script makes (``Sphere(radius=r)``, Yade's constructors with attributes), which
  ``b.shape = s`` gives to a body made by ``Body()`` (``s`` is a view of that body from then on,
  as Yade's body and script share one shape object).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from talus import _dem
from talus.dem.geometry.appearance import DEFAULT_COLOR, check_color
from talus.dem.base.linalg import Quaternion, Vector3
from talus.dem.base.serializable import Serializable
from talus.dem.geometry.shape_registry import ShapeKind, register, shape_kind


@dataclass(eq=False)
class ShapeSpec:
    """The geometry and looks of a body not yet in a scene: what a shape the script makes
    (``Sphere(radius=r)``) holds, and the shape part of a body made by ``sphere``, ``facet``, ...
    (talus.dem.core.bodies.BodySpec adds the body's material, mobility and mask)."""
    kind: str | None      # None: made by Body(), no shape yet
    center: tuple
    radius: float = 0.0
    axis: int = 2
    sense: int = 0
    vertices: tuple = ()
    extents: tuple = ()
    orientation: tuple = (1.0, 0.0, 0.0, 0.0)
    color: tuple = field(default=DEFAULT_COLOR)
    block: object = None  # the PotentialBlock or PotentialParticle shape (talus.dem.geometry.blocks, .particles)
    # State set before the append (velocities, mass, inertia, blocked DOFs, wire, highlight), applied by it.
    initial: dict = field(default_factory=dict)
    id: int = -1          # the body's id once appended
    _scene: object = field(default=None, repr=False)


class Shape(Serializable):
    """Base of the shapes; ``str(shape)`` is the kind's name (``"Sphere"``, ...)."""

    __slots__ = ("_scene", "_id", "_spec")
    _attributes = ("color", "wire", "highlight")

    def __init__(self, **attributes):
        # A shape of its own, kept in a ShapeSpec of no scene; an unknown attribute is Yade's
        # AttributeError.
        self._scene, self._id = None, -1
        self._spec = ShapeSpec(type(self).__name__, (0.0, 0.0, 0.0), radius=float("nan"), color=(1.0, 1.0, 1.0))  # Yade's
        for name, value in attributes.items():
            setattr(self, name, value)

    @classmethod
    def _view(cls, scene=None, id: int = -1, spec=None) -> "Shape":
        """A view of body ``id`` of ``scene``, or of the body ``spec`` stands for."""
        shape = cls.__new__(cls)
        shape._scene, shape._id, shape._spec = scene, id, spec
        return shape

    def _body(self):
        """(scene, id) of the body in a scene this shape is, None for one in no scene."""
        if self._spec is None:
            return self._scene, self._id
        return (self._spec._scene, self._spec.id) if self._spec._scene is not None else None

    def _data(self) -> dict:
        scene, id = self._body()
        return _dem.shape_data(scene._cpp, id)

    def _look(self, name: str):
        """Appearance ``name`` (color, highlight, wire): (array, index) of a body in a scene."""
        scene, id = self._body()
        from talus.dem import distributed     # under mpirun the looks are kept by body id, not by row
        if distributed.is_split(scene):
            id = distributed.global_ids(scene, [id])[0]
        look = scene._appearance
        look.ensure(len(scene.bodies))
        return getattr(look, name), id

    def _own(self, name: str, value=None):
        """An attribute of a shape in no scene: the shape's own spec field ``name``, set
        when ``value`` is given; an error naming the body for one in a scene."""
        where = self._body()
        if where is not None:
            raise AttributeError(f"{type(self).__name__}.{name} of body {where[1]} cannot be changed in Talus "
                                 "(its geometry is fixed once it is in a scene)")
        if value is not None:
            setattr(self._spec, name, value)
        return getattr(self._spec, name)

    @property
    def color(self) -> Vector3:
        """RGB colour in [0, 1], written to ParaView output (Yade's ``shape.color``)."""
        if self._body() is None:
            return Vector3(self._spec.color)
        array, id = self._look("color")
        return Vector3(array[id])

    @color.setter
    def color(self, value):
        if self._body() is None:
            self._spec.color = check_color(value)
        else:
            array, id = self._look("color")
            array[id] = check_color(value)

    def _flag(self, name: str) -> bool:
        if self._body() is None:
            return bool(self._spec.initial.get(name, False))
        array, id = self._look(name)
        return bool(array[id])

    def _set_flag(self, name: str, value):
        if self._body() is None:
            self._spec.initial[name] = bool(value)
        else:
            array, id = self._look(name)
            array[id] = bool(value)

    highlight = property(lambda s: s._flag("highlight"), lambda s, v: s._set_flag("highlight", v),
                         doc="Yade's highlight flag: kept and written to ParaView output")
    wire = property(lambda s: s._flag("wire"), lambda s, v: s._set_flag("wire", v),
                    doc="Yade's wire-frame flag: kept and written to ParaView output")

    def __str__(self):
        return type(self).__name__

    def __eq__(self, other):
        # ``b.shape == "Sphere"`` keeps working (scripts written when shapes were kind names).
        if isinstance(other, str):
            return other == type(self).__name__
        return isinstance(other, Shape) and type(other) is type(self) and \
            (other._body() == self._body() if self._body() is not None else other._spec is self._spec)

    def __hash__(self):
        return hash((type(self).__name__, self._id))

    def __repr__(self):
        where = self._body()
        return f"<{type(self).__name__} of body {where[1]}>" if where else f"<{type(self).__name__}>"


class Sphere(Shape):
    __slots__ = ()
    _attributes = ("radius",)

    @property
    def radius(self) -> float:
        if self._body() is None:
            return self._spec.radius
        scene, id = self._body()
        return float(scene._cpp.radius()[id])

    @radius.setter
    def radius(self, value: float):
        if not float(value) > 0:
            raise ValueError(f"Sphere.radius must be positive, got {value!r}")
        self._own("radius", float(value))


class Wall(Shape):
    """An infinite plane normal to ``axis``; ``sense`` -1/+1/0: which side interacts."""
    __slots__ = ()
    _attributes = ("sense", "axis")

    @property
    def axis(self) -> int:
        return self._own("axis") if self._body() is None else int(self._data()["axis"])

    @axis.setter
    def axis(self, value: int):
        if value not in (0, 1, 2):
            raise ValueError(f"Wall.axis must be 0, 1 or 2, got {value!r}")
        self._own("axis", int(value))

    @property
    def sense(self) -> int:
        return self._own("sense") if self._body() is None else int(self._data()["sense"])

    @sense.setter
    def sense(self, value: int):
        if value not in (-1, 0, 1):
            raise ValueError(f"Wall.sense must be -1, 0 or 1, got {value!r}")
        self._own("sense", int(value))


class Facet(Shape):
    """A triangle; ``vertices`` and ``normal`` in the body's frame, relative to its position (as Yade)."""
    __slots__ = ()
    _attributes = ("vertices", "normal", "area")

    @property
    def vertices(self) -> list[Vector3]:
        if self._body() is None:
            return [Vector3(np.subtract(v, self._spec.center)) for v in self._spec.vertices]
        return [Vector3(v) for v in self._data()["vertices"]]

    @vertices.setter
    def vertices(self, value):
        vertices = tuple(tuple(float(x) for x in v) for v in value)
        if len(vertices) != 3 or any(len(v) != 3 for v in vertices):
            raise ValueError(f"Facet.vertices must be three 3D points, got {value!r}")
        self._own("vertices", vertices)

    @property
    def normal(self) -> Vector3:
        if self._body() is None:
            a, b, c = (np.asarray(v, dtype=float) for v in self._spec.vertices)
            n = np.cross(b - a, c - b)        # Yade's order of operations (the sign of a zero)
            return Vector3(n / np.linalg.norm(n))
        return Vector3(self._data()["normal"])

    @property
    def area(self) -> float:
        """Area of the triangle (Yade's Facet.area)."""
        a, b, c = (np.asarray(v, dtype=float) for v in self.vertices)
        return float(0.5 * np.linalg.norm(np.cross(b - a, c - a)))


class Box(Shape):
    __slots__ = ()
    _attributes = ("extents",)

    @property
    def extents(self) -> Vector3:
        """Half-sizes along the body's axes."""
        if self._body() is None:
            return Vector3(self._spec.extents or (0.0, 0.0, 0.0))
        scene, id = self._body()
        return Vector3(_dem.box_extents(scene._cpp, id))

    @extents.setter
    def extents(self, value):
        extents = tuple(float(x) for x in value)
        if len(extents) != 3 or not all(x >= 0 for x in extents):
            raise ValueError(f"Box.extents must be three half-sizes >= 0, got {value!r}")
        self._own("extents", extents)


class Clump(Shape):
    __slots__ = ()

    @property
    def members(self) -> dict:
        """``{memberId: (relPos, relOri)}`` in ascending ids: each member's position and
        orientation in the clump's principal frame (Yade's Clump.members)."""
        where = self._body()
        if where is None:
            return {}     # a clump of no scene has no members (Yade's Clump())
        ids, relPos, relOri = _dem.clump_members(where[0]._cpp, where[1])
        from talus.dem import distributed     # under mpirun the rows hold other ids
        ids = distributed.global_ids(where[0], ids)
        return {int(i): (Vector3(p), Quaternion(*q)) for i, p, q in zip(ids, relPos, relOri)}


_BY_KIND = {cls.__name__: cls for cls in (Sphere, Wall, Facet, Box, Clump)}


def shape_of_spec(spec):
    """The shape of a body not yet appended (a view of its BodySpec)."""
    if spec.block is not None:      # a PotentialBlock or PotentialParticle: Yade's shape object itself
        return spec.block
    return _BY_KIND.get(spec.kind, Shape)._view(spec=spec)


def shape_of(scene, id: int):
    """``b.shape`` of body ``id``, as its kind's module makes it."""
    return shape_kind(scene._cpp.shapeKind(id)).view(scene, id)


# Adding a body of each kind, from the BodySpec of sphere(), wall(), facet(), box().
def _add_sphere(scene, spec, material: int) -> int:
    center = np.asarray(spec.center, dtype=float)   # as Yade, not wrapped into a periodic cell
    id = scene._cpp.addSphere(center, spec.radius, material)
    if spec.fixed:
        scene._cpp.setDynamic(id, False)
        scene._cpp.setBlockedDofs(id, 63)
    return id


def _add_box(scene, spec, material: int) -> int:
    return _dem.add_box(scene._cpp, np.asarray(spec.center, dtype=float), np.asarray(spec.extents, dtype=float),
                        np.asarray(spec.orientation, dtype=float), material, bool(spec.fixed))


def _add_facet(scene, spec, material: int) -> int:
    return scene._cpp.addFacet(*(np.asarray(v, dtype=float) for v in spec.vertices), material, spec.bounded)


def _add_wall(scene, spec, material: int) -> int:
    return scene._cpp.addWall(spec.center[spec.axis], spec.axis, spec.sense, material)


register(ShapeKind("Sphere", view=Sphere._view, add=_add_sphere))
register(ShapeKind("Wall", view=Wall._view, add=_add_wall))
register(ShapeKind("Facet", view=Facet._view, add=_add_facet))
register(ShapeKind("Box", view=Box._view, add=_add_box))
register(ShapeKind("Clump", view=Clump._view))   # made from other bodies by O.bodies.clump
