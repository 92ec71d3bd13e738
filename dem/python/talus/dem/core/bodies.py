"""Bodies: Yade-style constructors (``sphere``, ``wall``) and proxies over the scene's arrays."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Sequence

import numpy as np

from talus import _dem
from talus.dem.base.linalg import Quaternion, Vector3
from talus.dem.core import heat
from talus.dem.core.masks import group_mask
from talus.dem.geometry.appearance import DEFAULT_COLOR, check_color
from talus.dem.base.serializable import Serializable
from talus.dem.geometry.shapes import Box, Shape, ShapeSpec, Sphere, Wall, shape_of, shape_of_spec
from talus.dem.core.scenes import default_scene

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

_DOF_LETTERS = "xyzXYZ"


@dataclass(eq=False)
class BodySpec(ShapeSpec):
    """A body made by ``sphere``, ``wall``, ``facet``, ``box`` (what Yade's ``utils.sphere``
    returns), or by ``Body()`` (Yade's: no shape yet, mass and inertia 0; the script gives it
    ``b.shape = Sphere(radius=r)``, ``b.state.pos``, ``b.state.mass``, ``b.mat``). As in Yade, a
    script may set its ``state``, ``shape.color`` or ``dynamic`` before appending it to
    ``O.bodies``; once appended it stands for the body in the scene (``id``, ``state``,
    ``shape`` read and write the scene). Its shape fields are ShapeSpec's."""
    material: object = -1
    fixed: bool = False
    bounded: bool = True  # False: a facet the collider never pairs (Yade's noBound)
    group_mask: int = 1   # Yade's groupMask (``mask``), see Body.mask

    # What Body() accepts as attributes, as Yade's Body(shape=..., material=...).
    _YADE_ATTRIBUTES = ("shape", "material", "mat", "dynamic", "mask", "groupMask")

    @classmethod
    def blank(cls, **attributes) -> "BodySpec":
        """Yade's ``Body()``: no shape, mass and inertia 0 (as Yade, a script sets them: a
        dynamic body without mass is refused at the step), the last material unless given."""
        spec = cls(None, (0.0, 0.0, 0.0), material=None, initial={"mass": 0.0, "inertia": (0.0, 0.0, 0.0)})
        for name, value in attributes.items():
            if name not in cls._YADE_ATTRIBUTES:
                raise AttributeError(f"Body has no attribute {name!r} that Talus sets before the body is appended "
                                     f"(it takes {', '.join(cls._YADE_ATTRIBUTES)}; set state.* on b.state)")
            setattr(spec, name, value)
        return spec

    def _body(self) -> "Body | None":
        return Body(self._scene, self.id) if self._scene is not None else None

    @property
    def state(self):
        body = self._body()
        return body.state if body else _DetachedState(self)

    @state.setter
    def state(self, value):
        raise AttributeError("b.state = ... is not supported in Talus (a body's state lives in its scene's arrays): "
                             "set its attributes instead (b.state.pos = ..., b.state.mass = ...)")

    @property
    def shape(self):
        body = self._body()
        return body.shape if body else shape_of_spec(self)

    @shape.setter
    def shape(self, shape: Shape):
        """Yade's ``b.shape = Sphere(radius=r)`` for a body of no scene yet (a Sphere, Box or
        Wall made by the script); ``shape`` is a view of this body from then on."""
        if self._scene is not None:
            raise AttributeError(f"body {self.id} is in a scene: its shape cannot be replaced in Talus "
                                 "(erase it and append another)")
        if not isinstance(shape, Shape) or shape._spec is None or shape._spec._scene is not None:
            raise TypeError(f"b.shape takes a shape made by the script (Sphere(radius=r), Box(extents=...), "
                            f"Wall(axis=..)), got {shape!r}")
        if type(shape) not in (Sphere, Box, Wall):
            raise ValueError(f"b.shape = {type(shape).__name__}(): Talus makes a body of that shape only with "
                             "utils.facet, utils.sphere ... (Body() takes a Sphere, Box or Wall)")
        own = shape._spec
        self.kind, self.radius, self.extents, self.axis, self.sense = own.kind, own.radius, own.extents, own.axis, \
            own.sense
        self.color = own.color
        self.initial.update((k, own.initial[k]) for k in ("wire", "highlight") if k in own.initial)
        shape._spec = self

    @property
    def dynamic(self) -> bool:
        body = self._body()
        return body.dynamic if body else not self.fixed

    @dynamic.setter
    def dynamic(self, value: bool):
        body = self._body()
        if body:
            body.dynamic = value
        else:
            self.fixed = not value

    @property
    def mask(self) -> int:
        body = self._body()
        return body.mask if body else self.group_mask

    @mask.setter
    def mask(self, value):
        body = self._body()
        if body:
            body.mask = value
        else:
            self.group_mask = group_mask(value, "a body not yet appended")

    groupMask = mask   # Yade's C++ name

    @property
    def mat(self):
        """The body's material (Yade's ``b.mat``); before the append, the one ``material`` names
        (an index or a label in the default scene), as Yade resolves it when the body is made."""
        body = self._body()
        if body:
            return body.material
        from talus.dem.core.materials import Material
        if self.material is None:      # Body() before a material is given (the last one when appended)
            return None
        if isinstance(self.material, Material):
            return self.material
        O = default_scene()
        return O.materials[O.materials.resolve(self.material)]

    @mat.setter
    def mat(self, material):
        if self._scene is not None:
            raise AttributeError(f"body {self.id} is in a scene: its material cannot be replaced in Talus")
        self.material = material

    # A body not yet appended is alone and bounded, as Yade's.
    _UNAPPENDED = {"isClump": False, "isClumpMember": False, "isStandalone": True, "clumpId": -1, "bounded": True}

    def __getattr__(self, name):
        # Any other Body attribute (isClump, clumpId, ...) once appended.
        if self._scene is None and name in self._UNAPPENDED:
            return self._UNAPPENDED[name]
        if name.startswith("_") or self._scene is None:
            raise AttributeError(f"{type(self).__name__} has no attribute {name!r}"
                                 + ("" if self._scene is not None else " (before it is appended to O.bodies)"))
        return getattr(self._body(), name)


class _DetachedState:
    """``state`` of a body not yet appended: position and orientation are the spec's, the rest
    is kept and applied when the body is appended."""

    __slots__ = ("_spec",)
    _KEPT = ("vel", "angVel", "mass", "inertia", "blockedDOFs", "refPos", "refOri", "isDamped")

    def __init__(self, spec: BodySpec):
        object.__setattr__(self, "_spec", spec)

    @property
    def pos(self) -> Vector3:
        return Vector3(self._spec.center)

    @pos.setter
    def pos(self, value):
        self._spec.center = tuple(Vector3(value))

    @property
    def ori(self) -> Quaternion:
        return Quaternion(*self._spec.orientation)

    @ori.setter
    def ori(self, value):
        q = value if isinstance(value, Quaternion) else Quaternion(*value)
        self._spec.orientation = (q.w, q.x, q.y, q.z)

    def __getattr__(self, name):
        if name in ("vel", "angVel"):
            return Vector3(self._spec.initial.get(name, (0.0, 0.0, 0.0)))
        if name == "isDamped":
            return bool(self._spec.initial.get(name, True))
        if name == "blockedDOFs":
            return self._spec.initial.get(name, "xyzXYZ" if self._spec.fixed else "")
        if name in ("refPos", "refOri") and name not in self._spec.initial:   # as Yade: where it is made
            return self.pos if name == "refPos" else self.ori
        if name in self._spec.initial:
            return self._spec.initial[name]
        raise AttributeError(f"state.{name} of a body not yet appended: it is known once the body is in O.bodies")

    def __setattr__(self, name, value):
        if name in ("pos", "ori"):
            object.__setattr__(self, name, value)      # the properties
        elif name in self._KEPT:
            self._spec.initial[name] = value
        else:
            raise AttributeError(f"State has no attribute {name!r}")


def _yade_material(material):
    """``material`` as Yade's utils take it when they make a body: the default (-1) while O has
    no material yet makes Yade's default FrictMat there and then (len(O.materials) is 1 after
    the first utils.sphere); it is resolved when the body is appended."""
    if isinstance(material, int) and material < 0:
        O = default_scene()
        if len(O.materials) == 0:
            O.materials.resolve(-1)
    return material


def _look(color, wire: bool, highlight: bool) -> dict:
    """The BodySpec fields of Yade's display arguments (kept as data, see talus.dem.geometry.appearance)."""
    return {"color": DEFAULT_COLOR if color is None else check_color(color),
            "initial": {"wire": bool(wire), "highlight": bool(highlight)}}


def sphere(center: Sequence[float], radius: float, material=-1, fixed: bool = False, color=None, wire=False,
           highlight=False, mask=1, **_ignored) -> BodySpec:
    """A sphere of the given centre and radius; ``material`` is an index, a label or a
    Material (default: the last material added, or Yade's default FrictMat); ``mask``: its
    group mask (Body.mask)."""
    return BodySpec("Sphere", tuple(float(x) for x in center), float(radius), material=_yade_material(material),
                    fixed=fixed, group_mask=group_mask(mask, "sphere"),
                    **_look(color, wire, highlight))


def wall(position, axis: int, sense: int = 0, material=-1, color=None, mask=1, **_ignored) -> BodySpec:
    """An infinite wall normal to ``axis`` through ``position`` (a number or a point, as in Yade);
    ``sense`` -1/+1 makes only that side interact, 0 both. Walls are fixed."""
    if axis not in (0, 1, 2):
        raise ValueError(f"wall: axis must be 0, 1 or 2, got {axis!r}")
    if isinstance(position, (int, float)):
        coord = float(position)
    else:
        coord = float(tuple(position)[axis])
    center = [0.0, 0.0, 0.0]
    center[axis] = coord
    return BodySpec("Wall", tuple(center), axis=axis, sense=sense, material=_yade_material(material), fixed=True,
                    group_mask=group_mask(mask, "wall"), **_look(color, False, False))


def aabbWalls(extrema=None, thickness: float = 0, material=-1, **_ignored) -> list[BodySpec]:
    """Six walls on the faces of the box ``extrema = (minCorner, maxCorner)`` (default: the
    box of the default scene's spheres, as Yade), in the order a TriaxialStressController
    expects by default (x-, x+, y-, y+, z-, z+). Talus walls are planes: ``thickness`` is
    accepted for Yade scripts and ignored."""
    if extrema is None:
        from talus.dem.analysis.measure import aabbExtrema
        extrema = aabbExtrema()
    lo, hi = (np.asarray(x, dtype=float).reshape(3) for x in extrema)
    if np.any(hi <= lo):
        raise ValueError(f"aabbWalls: the upper corner must exceed the lower one, got {lo}, {hi}")
    return [wall(corner[axis], axis, material=material) for axis in range(3) for corner in (lo, hi)]


def facet(vertices: Sequence[Sequence[float]], material=-1, color=None, wire=True, highlight=False,
          noBound=False, mask=1, **_ignored) -> BodySpec:
    """A fixed triangle with the three given vertices (its position is the incentre, as in Yade;
    drawn as wire frame by default, as Yade's). ``noBound``: the collider never pairs it (it
    touches nothing: a surface factories place particles on)."""
    verts = tuple(tuple(float(x) for x in v) for v in vertices)
    if len(verts) != 3 or any(len(v) != 3 for v in verts):
        raise ValueError(f"facet: needs three 3D vertices, got {vertices!r}")
    return BodySpec("Facet", verts[0], material=_yade_material(material), fixed=True, vertices=verts,
                    bounded=not noBound, group_mask=group_mask(mask, "facet"), **_look(color, wire, highlight))


def box(center: Sequence[float], extents: Sequence[float], orientation=(1.0, 0.0, 0.0, 0.0), fixed: bool = False,
        material=-1, dynamic=None, color=None, wire=False, highlight=False, mask=1, **_ignored) -> BodySpec:
    """A box of half-sizes ``extents`` (Yade's utils.box); ``orientation`` is a quaternion
    (w, x, y, z) or anything with w, x, y, z attributes. Dynamic unless ``fixed`` (or
    ``dynamic=False``); its mass and inertia come from the material's density. Boxes interact
    with spheres (faces, edges and corners), not with walls, facets or other boxes."""
    c = tuple(float(x) for x in center)
    e = tuple(float(x) for x in extents)
    if len(c) != 3 or len(e) != 3:
        raise ValueError(f"box: center and extents must be 3 numbers, got {center!r}, {extents!r}")
    if hasattr(orientation, "w"):
        q = (orientation.w, orientation.x, orientation.y, orientation.z)
    else:
        q = tuple(float(x) for x in orientation)
    if len(q) != 4:
        raise ValueError(f"box: orientation must be a quaternion (w, x, y, z), got {orientation!r}")
    if dynamic is not None:
        fixed = not dynamic
    return BodySpec("Box", c, material=_yade_material(material), fixed=fixed, extents=e, orientation=q,
                    group_mask=group_mask(mask, "box"), **_look(color, wire, highlight))


def _dofs_to_mask(letters: str) -> int:
    bad = set(letters) - set(_DOF_LETTERS)
    if bad:
        raise ValueError(f"blockedDOFs: unknown letters {''.join(sorted(bad))!r}; use any of 'xyzXYZ'")
    return sum(1 << _DOF_LETTERS.index(c) for c in set(letters))


class _StateVector3(Vector3):
    """``vel``, ``angVel``, ``inertia`` or ``refPos`` of a body as Yade hands them: a reference,
    so that ``b.state.vel[0] = 1`` (or ``v = b.state.vel; v[0] = 1``) sets the body's (Yade's
    ``pos`` is a copy). It is a snapshot otherwise: it does not follow the body's later motion.
    Arithmetic on it gives plain Vector3s."""

    def __setitem__(self, key, value):
        super().__setitem__(key, value)
        owner = getattr(self, "_owner", None)     # none on views and results numpy derives
        if owner is not None:
            setattr(owner[0], owner[1], np.asarray(self))

    def __array_wrap__(self, out, context=None, return_scalar=False):
        result = super().__array_wrap__(out, context, return_scalar)
        return result.view(Vector3) if isinstance(result, _StateVector3) else result

    def __repr__(self):
        return repr(self.view(Vector3))

    __str__ = __repr__


def _reference(state: "State", name: str, values) -> _StateVector3:
    return _owned(np.array(values, dtype=float).view(_StateVector3), state, name)


def _owned(vector: _StateVector3, state: "State", name: str) -> _StateVector3:
    vector._owner = (state, name)
    return vector


class State(Serializable):
    """Position, velocity and other state of one body, read and written through the arrays."""

    # No other attributes: a misspelt one (or a Yade attribute Talus lacks) is an error, not a
    # silently ignored assignment.
    __slots__ = ("_scene", "_id")
    _attributes = ("se3", "vel", "mass", "angVel", "angMom", "inertia", "refPos", "refOri", "blockedDOFs",
                   "isDamped", "densityScaling", "temp", "Cp", "k", "alpha")

    def __init__(self, scene: "Scene", id: int):
        object.__setattr__(self, "_scene", scene)
        object.__setattr__(self, "_id", id)

    # The heat of Yade's ThermalState, per-body fields of the DEM core (talus.dem.core.heat): the
    # value given, else the default of the scene's heat engine; checked when set.
    temp = property(lambda s: heat.value_of(s._scene, s._id, "temp"), lambda s, v: heat.assign(s._scene, s._id, "temp", v),
                    doc="temperature (K or °C, as the script's values); Yade's ThermalState.temp")
    Cp = property(lambda s: heat.value_of(s._scene, s._id, "Cp"), lambda s, v: heat.assign(s._scene, s._id, "Cp", v),
                  doc="specific heat capacity, J/(kg K); Yade's ThermalState.Cp")
    k = property(lambda s: heat.value_of(s._scene, s._id, "k"), lambda s, v: heat.assign(s._scene, s._id, "k", v),
                 doc="thermal conductivity, W/(m K); Yade's ThermalState.k")
    alpha = property(lambda s: heat.value_of(s._scene, s._id, "alpha"),
                     lambda s, v: heat.assign(s._scene, s._id, "alpha", v),
                     doc="linear thermal expansion coefficient, 1/K; Yade's ThermalState.alpha")

    # Per-body fields an engine of the scene keeps (ThermalEngine: Tcondition), listed by its
    # _bodyFields() as name -> (get(id), set(id, value)).
    def _engine_field(self, name):
        for engine in self._scene.engines:
            fields = engine._bodyFields() if hasattr(engine, "_bodyFields") else {}
            if name in fields:
                return fields[name]
        raise AttributeError(f"'State' object has no attribute {name!r} (nor has any engine of the scene "
                             f"such a per-body field)")

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        if name in heat.FIELDS:     # its property raised: the same error, not the generic one
            return heat.value_of(self._scene, self._id, name)
        return self._engine_field(name)[0](self._id)

    def __setattr__(self, name, value):
        if hasattr(type(self), name):
            object.__setattr__(self, name, value)
        else:
            self._engine_field(name)[1](self._id, value)

    def _row(self, name):
        return getattr(self._scene._cpp, name)()[self._id]

    def _set(self, name, value):
        value = np.asarray(value, dtype=float)
        if value.shape != (3,) or not np.all(np.isfinite(value)):
            raise ValueError(f"body {self._id}: {name} must be 3 finite numbers, got {value}")
        getattr(self._scene._cpp, name)()[self._id] = value

    # As Yade hands them: pos a copy (changing the Vector3 one got does not move the body;
    # assigning it does), vel, angVel, inertia and refPos references (see _StateVector3).
    # (Scripts read them body by body in their loops: the core copies the row into the vector.)
    pos = property(lambda s: _dem.body_pos(s._scene._cpp, s._id, Vector3), lambda s, v: s._set("pos", v))
    vel = property(lambda s: _owned(_dem.body_vel(s._scene._cpp, s._id, _StateVector3), s, "vel"),
                   lambda s, v: s._set("vel", v))
    inertia = property(lambda s: _reference(s, "inertia", s._row("inertia")),
                       lambda s, v: s._scene._cpp.setInertia(s._id, np.asarray(v, dtype=float).reshape(3)),
                       doc="principal inertia (kg m^2); settable, as in Yade")
    mass = property(lambda s: float(s._row("mass")), lambda s, v: s._scene._cpp.setMass(s._id, float(v)),
                    doc="mass (kg); settable, as in Yade")
    # The C++ core hands (w, x, y, z).
    ori = property(lambda s: Quaternion(*s._scene._cpp.ori(s._id)), doc="orientation (``ori * v`` rotates v)")
    se3 = property(lambda s: (s.pos, s.ori), doc="(pos, ori), as Yade's")

    @property
    def angVel(self):
        return _owned(_dem.body_ang_vel(self._scene._cpp, self._id, _StateVector3), self, "angVel")

    @angVel.setter
    def angVel(self, value):
        # Aspherical bodies integrate their angular momentum: it is set with the velocity.
        value = np.asarray(value, dtype=float)
        if value.shape != (3,) or not np.all(np.isfinite(value)):
            raise ValueError(f"body {self._id}: angVel must be 3 finite numbers, got {value}")
        _dem.set_ang_vel(self._scene._cpp, self._id, value)

    @property
    def angMom(self):
        """Angular momentum (world frame) integrated for aspherical bodies (clumps, boxes)."""
        return Vector3(_dem.ang_mom(self._scene._cpp, self._id))

    # Yade's reference configuration (talus.dem.core.reference): data the physics never reads.
    @property
    def refPos(self) -> Vector3:
        """Reference position: where the body was made (a clump: the origin) unless set."""
        states, at = self._reference()
        return _reference(self, "refPos", states.pos[at])

    @refPos.setter
    def refPos(self, value):
        value = np.asarray(value, dtype=float)
        if value.shape != (3,) or not np.all(np.isfinite(value)):
            raise ValueError(f"body {self._id}: refPos must be 3 finite numbers, got {value}")
        states, at = self._reference()
        states.pos[at] = value

    @property
    def refOri(self) -> Quaternion:
        """Reference orientation: the one the body was made with (a clump: none) unless set."""
        states, at = self._reference()
        return Quaternion(*states.ori[at])

    @refOri.setter
    def refOri(self, value):
        q = value if isinstance(value, Quaternion) else Quaternion(*value)
        states, at = self._reference()
        states.ori[at] = (q.w, q.x, q.y, q.z)

    def _reference(self):
        """The scene's reference states and this body's entry in them: its row in one process; its
        id once the scene is split over the processes, every process keeping every body's (as it
        built the whole scene), which a loop over O.bodies writes alike on every process."""
        from talus.dem import distributed     # (imports this module's package)
        scene, at = self._scene, self._id
        if distributed.is_split(scene):
            if scene._reference_by_row:
                distributed.refuse("State.refPos and refOri in a scene holding a packing read in slabs (each "
                                   "process kept its own slab's only)")
            at = distributed.global_ids(scene, [at])[0]
        states = scene._reference
        states.ensure(len(scene.bodies))
        return states, at
    @property
    def blockedDOFs(self) -> str:
        mask = int(self._row("blockedDofs"))
        return "".join(c for i, c in enumerate(_DOF_LETTERS) if mask & (1 << i))

    @blockedDOFs.setter
    def blockedDOFs(self, letters: str):
        self._scene._cpp.setBlockedDofs(self._id, _dofs_to_mask(letters))

    @property
    def isDamped(self) -> bool:
        """Whether NewtonIntegrator's damping acts on the body (Yade's; default True)."""
        return bool(_dem.is_damped(self._scene._cpp, self._id))

    @isDamped.setter
    def isDamped(self, value: bool):
        _dem.set_damped(self._scene._cpp, self._id, bool(value))


class Body:
    """One body of a scene (Yade's Body): ``id``, ``state``, ``shape``, ``material``, ``dynamic``."""

    # `id` is the body's id in the scene the script built; `_row` its row in this process's
    # arrays (the same but under mpirun, where a process holds some bodies only)
    __slots__ = ("_scene", "_row", "id", "state")   # unknown attributes are errors (see State)

    def __new__(cls, *view, **attributes):
        # Body(scene, id) is a view; Yade's Body(**attributes) a body of no scene yet.
        return super().__new__(cls) if view else BodySpec.blank(**attributes)

    def __init__(self, scene: "Scene", row: int, id: int | None = None):
        scene._cpp.checkBody(row)
        for name, value in (("_scene", scene), ("_row", row), ("id", row if id is None else id),
                            ("state", State(scene, row))):
            object.__setattr__(self, name, value)

    def __setattr__(self, name, value):
        # O.bodies hands one view per body: its id and state are not the script's to replace.
        if name == "id":
            raise AttributeError("Body.id cannot be set (Yade's is read-only too)")
        if name == "state":
            raise AttributeError("Body.state cannot be replaced in Talus: set its attributes instead "
                                 "(b.state.pos = ..., b.state.vel = ...)")
        object.__setattr__(self, name, value)

    @property
    def dynamic(self) -> bool:
        return bool(self._scene._cpp.dynamic()[self._row])

    @dynamic.setter
    def dynamic(self, value: bool):
        self._scene._cpp.setDynamic(self._row, bool(value))

    @property
    def mask(self) -> int:
        """Yade's group mask (``groupMask``, default 1): the collider pairs two bodies only if
        their masks share a bit (and InsertionSortCollider.avoidSelfInteractionMask keeps bodies
        of one mask apart); GravityEngine.mask and NewtonIntegrator.mask act on the bodies
        sharing a bit with theirs. A change applies to the contacts that begin after it: as in
        Yade, a contact in progress lasts until it ends."""
        return int(_dem.group_mask(self._scene._cpp, self._row))

    @mask.setter
    def mask(self, value):
        _dem.set_group_mask(self._scene._cpp, self._row, group_mask(value, f"body {self.id}"))

    groupMask = mask   # Yade's C++ name

    @property
    def subdomain(self) -> int:
        """Yade's MPI subdomain of the body: under mpirun, once the scene is split, the rank of
        the process owning it (0 for the walls, facets and boxes every process holds, as Yade's
        master holds them); before, the value the script set (default 0). Setting it is
        accepted, not used: Talus's decomposition partitions with Zoltan (yade.mpy)."""
        from talus.dem import distributed     # (imports this module's package)
        if distributed.is_split(self._scene):
            return distributed.rank() if self._scene._cpp.shapeKind(self._row) in ("Sphere", "Clump") else 0
        return getattr(self._scene, "_subdomains", {}).get(self.id, 0)

    @subdomain.setter
    def subdomain(self, value: int):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise ValueError(f"body {self.id}: subdomain must be a rank (an integer >= 0), got {value!r}")
        if not hasattr(self._scene, "_subdomains"):
            self._scene._subdomains = {}
        self._scene._subdomains[self.id] = int(value)

    @property
    def radius(self) -> float:
        return float(self._scene._cpp.radius()[self._row])

    @property
    def shape(self) -> Shape:
        """The body's shape (talus.dem.geometry.shapes): ``b.shape.radius``, ``isinstance(b.shape, Sphere)``."""
        return shape_of(self._scene, self._row)

    @property
    def isClump(self) -> bool:
        return self._scene._cpp.shapeKind(self._row) == "Clump"

    @property
    def clumpId(self) -> int:
        """Id of the clump this body belongs to (its own id for a clump, -1 if standalone)."""
        if self.isClump:
            return self.id
        from talus.dem import distributed     # (imports this module's package)
        clump = int(_dem.clump_id(self._scene._cpp, self._row))
        return distributed.global_ids(self._scene, [clump])[0] if clump >= 0 else -1   # a row under mpirun

    @property
    def isClumpMember(self) -> bool:
        return not self.isClump and self.clumpId >= 0

    @property
    def isStandalone(self) -> bool:
        return not self.isClump and self.clumpId < 0

    @property
    def material(self):
        """The body's material; None for a clump (Yade's: its members have theirs)."""
        if self.isClump:
            return None
        return self._scene.materials[int(self._scene._cpp.materialIds()[self._row])]

    mat = material   # Yade's short name

    @property
    def bound(self) -> "Aabb | None":
        """Yade's ``b.bound``: the box the collider last bounded the body with (its shape at the
        position of the last re-detection, grown by the skin), as a snapshot. None without a
        collider and for a clump (its members are bounded); NaN everywhere while the collider
        has not bounded the body (before its first run, after bodies changed, after O.load:
        Yade does not save bounds either)."""
        if self.isClump:
            return None
        for engine in self._scene.engines:
            cpp = getattr(engine, "_cpp", None)
            if isinstance(cpp, _dem.Collider) and not engine.dead:
                found = cpp.boundOf(self._scene._cpp, self._row)
                if found is None:
                    nan = Vector3(float("nan"), float("nan"), float("nan"))
                    return Aabb(nan, nan, nan, float("nan"))
                return Aabb(*(Vector3(v) for v in found[:3]), float(found[3]))
        return None

    @property
    def bounded(self) -> bool:
        """Whether the collider bounds the body: all but clumps, whose members are bounded, and
        facets made with noBound."""
        if self.isClump:
            return False
        return _dem.shape_data(self._scene._cpp, self._row).get("bounded", True)

    # Body objects are views made on each access: two views of one body are equal, as Yade's
    # shared pointers to the same body are.
    def __eq__(self, other):
        return isinstance(other, Body) and other._scene is self._scene and other.id == self.id

    def __hash__(self):
        return hash((id(self._scene), self.id))

    def __repr__(self):
        return f"<Body {self.id} {self.shape}>"


@dataclass(frozen=True)
class Aabb:
    """A body's bound (Yade's Aabb): ``min``, ``max``, the position it was taken at ``refPos`` and
    the skin ``sweepLength`` it is grown by."""
    min: Vector3
    max: Vector3
    refPos: Vector3
    sweepLength: float
