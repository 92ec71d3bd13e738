"""Potential Blocks (Yade's PotentialBlock, Boon et al. 2012): convex polyhedra given by planes.

    mat = O.materials.append(FrictMat(density=2000, frictionAngle=radians(30)))
    cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.01)
    O.bodies.append(potentialBlock(cube, pos=(0, 0, 0.5), material=mat))
    O.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PB_PB_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=1e8, Kshear=1e7, viscousDamping=0.2)],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0)]

A block is { x : a_i x + b_i y + c_i z <= d_i + r } with unit normals (a_i, b_i, c_i); volume,
centroid and principal inertia are computed from its vertices. Blocks interact with blocks and
with walls (``wall``); two boundary blocks (``isBoundary``) do not interact.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from talus import _dem
from talus.atomic import write_atomically
from talus.dem.core.bodies import BodySpec
from talus.dem.geometry.convex_contact import geometry_functor, two_dimension
from talus.dem.step.engines import Functor, LawFunctor
from talus.dem.base.linalg import Quaternion
from talus.dem.core.masks import group_mask
from talus.dem.geometry.shape_registry import ShapeKind, register
from talus.dem.files.vtu import vtu_bytes

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

VTK_POLYGON = 7


class PotentialBlock:
    """The shape of a block, with Yade's argument names. ``R`` = 0: half the largest distance
    between vertices. ``k`` is accepted as Yade's (must be 0: blocks have no spherical term);
    Yade's display and Aabb options (color, wire, minAabb, AabbMinMax, ...) are accepted and
    ignored: Talus always bounds blocks tightly from their turned vertices. ``cohesion``,
    ``tension`` (stresses), ``intactRock``, ``jointType``: the faces' rock-joint properties, one
    entry per plane (empty: frictional faces), read by the contact law with
    ``useFaceProperties`` (``generateBlocks`` fills them from the joint file)."""
    def __init__(self, a, b, c, d, r=0.0, R=0.0, isBoundary=False, k=0.0, cohesion=(), tension=(), intactRock=(),
                 jointType=(), **yadeOptions):
        self.a, self.b, self.c, self.d = (list(map(float, v)) for v in (a, b, c, d))
        self.r, self.R, self.isBoundary, self.k = float(r), float(R), bool(isBoundary), float(k)
        if self.k != 0:
            raise ValueError(f"PotentialBlock: k must be 0 (blocks have no spherical term), got {k}")
        self.cohesion, self.tension = list(map(float, cohesion)), list(map(float, tension))
        self.intactRock, self.jointType = list(map(bool, intactRock)), list(map(int, jointType))
        self.extra = yadeOptions

    def __repr__(self):
        return (f"PotentialBlock(a={self.a}, b={self.b}, c={self.c}, d={self.d}, r={self.r}, R={self.R}, "
                f"isBoundary={self.isBoundary})")

    @classmethod
    def cuboid(cls, halfSizes, r=0.0, **kw) -> "PotentialBlock":
        """A rectangular block of half-sizes ``halfSizes`` whose faces are at the half-sizes
        (planes d = half-size - r, as Yade's examples write them)."""
        hx, hy, hz = (float(h) for h in halfSizes)
        return cls(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1],
                   d=[hx - r, hx - r, hy - r, hy - r, hz - r, hz - r], r=r, **kw)


def potentialBlock(shape: PotentialBlock, pos=None, orientation=(1.0, 0.0, 0.0, 0.0), material=-1,
                   fixed: bool = False, mask=1, **_ignored) -> BodySpec:
    """A body of the given shape whose centroid is at ``pos`` (None: where the planes put it,
    i.e. planes given in world coordinates), turned by ``orientation`` (w, x, y, z) about the
    centroid. Its mass and inertia come from the material's density and the block's volume."""
    if hasattr(orientation, "w"):
        orientation = (orientation.w, orientation.x, orientation.y, orientation.z)
    q = tuple(float(x) for x in orientation)
    if len(q) != 4:
        raise ValueError(f"potentialBlock: orientation must be a quaternion (w, x, y, z), got {orientation!r}")
    center = None if pos is None else tuple(float(x) for x in pos)
    return BodySpec("PotentialBlock", center, material=material, fixed=fixed, orientation=q, block=shape,
                    group_mask=group_mask(mask, "potentialBlock"))


def _add(scene: "Scene", spec: BodySpec, material: int) -> int:
    """Add a PotentialBlock body spec to the scene (O.bodies.append)."""
    s = spec.block
    center = None if spec.center is None else np.asarray(spec.center, dtype=float)
    return _dem.add_potential_block(scene._cpp, s.a, s.b, s.c, s.d, s.r, s.R, s.isBoundary, center,
                                    np.asarray(spec.orientation, dtype=float), material, bool(spec.fixed),
                                    s.cohesion, s.tension, s.intactRock, s.jointType)


def blockShape(scene: "Scene", id: int) -> dict:
    """The block's planes, vertices and faces in its principal frame, volume, r, R, and the
    faces' rock-joint properties (cohesion, tension, intactRock, jointType per plane)."""
    return _dem.block_shape(scene._cpp, int(id))


def blockVertices(scene: "Scene", id: int) -> np.ndarray:
    """World coordinates of the block's corners."""
    cpp = scene._cpp
    v = np.asarray(_dem.block_shape(cpp, int(id))["vertices"], dtype=float)
    return cpp.pos()[int(id)] + v @ Quaternion(*cpp.ori(int(id))).toRotationMatrix().T


def blockContact(scene: "Scene", id1: int, id2: int, repeats: int = 1, accuracyTol: float | None = None) -> dict:
    """Contact geometry of a block pair (or wall id1, block id2) as it stands now, and the
    solver's mean time per call over ``repeats`` calls (``seconds`` cold, ``secondsWarm``
    starting from the contact point). ``accuracyTol``: the analytic centre's stopping Newton
    decrement (None: the scene's, Ig2_PB_PB_ScGeom.accuracyTol, default 1e-10)."""
    return _dem.block_contact(scene._cpp, int(id1), int(id2), int(repeats),
                              None if accuracyTol is None else float(accuracyTol))


def write_blocks(scene: "Scene", path: str) -> int:
    """Write the live Potential Blocks of ``scene`` to ``path`` (.vtu) as their true polygonal
    faces (not a rounded approximation); returns their number."""
    cpp = scene._cpp
    ids = [i for i in range(len(cpp.pos())) if cpp.alive()[i] and cpp.shapeKind(i) == "PotentialBlock"]
    points, conn, offsets, owner = [], [], [], []
    for i in ids:
        shape = _dem.block_shape(cpp, i)
        base = sum(len(p) for p in points)
        points.append(cpp.pos()[i] + np.asarray(shape["vertices"]) @ Quaternion(*cpp.ori(i)).toRotationMatrix().T)
        for face in shape["faces"]:
            conn.extend(base + k for k in face)
            offsets.append(len(conn))
            owner.append(i)
    pts = np.concatenate(points) if points else np.zeros((0, 3))
    owner = np.asarray(owner, dtype=np.int32)
    data = {"id": owner, "velocity": cpp.vel()[owner] if len(owner) else np.zeros((0, 3))}
    write_atomically(path, vtu_bytes(pts, np.asarray(conn, dtype=np.int64), np.asarray(offsets, dtype=np.int64),
                                  np.full(len(offsets), VTK_POLYGON, dtype=np.uint8), cell_data=data, time=cpp.time))
    return len(ids)


# Yade's functors for Potential Blocks.
class PotentialBlock2AABB(Functor):
    """Bounding box of blocks (accepted; Talus bounds blocks tightly from their vertices)."""
    _parameters = ("AabbMinMax",)


class Ig2_PB_PB_ScGeom(Functor):
    """Block-block and wall-block contact geometry. ``calContactArea`` False: area 1 (constant
    stiffnesses). ``twoDimension`` (Yade's 2D mode): the blocks are prisms along ``twoDdir``
    (default (0, 1, 0)) and the contact area is the joint length (the overlap region's chord
    through the contact point along normal x twoDdir) times ``unitWidth2D`` (default 1).
    ``exactDepth`` (Talus only, default False): the overlap is the polyhedra's penetration depth
    and the normal its direction, instead of Yade's chord through the analytic centre.
    ``accuracyTol``: the analytic centre's stopping Newton decrement (default 1e-10; Yade's is
    its conic solver's tolerance)."""
    _parameters = ("calContactArea", "twoDimension", "unitWidth2D", "twoDdir", "exactDepth", "accuracyTol")

    def _applyToScene(self, cpp):
        """Set these settings for every block contact of the scene whose engines hold us."""
        _dem.set_block_contact_settings(cpp, *two_dimension(self), bool(self.exactDepth),
                                        _dem.default_block_accuracy_tol if self.accuracyTol is None
                                        else float(self.accuracyTol))


class Ip2_FrictMat_FrictMat_KnKsPBPhys(Functor):
    """Stiffnesses per unit contact area: ``Knormal``, ``Kshear`` between blocks, ``kn_i``,
    ``ks_i`` with a boundary block; ``viscousDamping``: fraction of the critical damping
    2 sqrt(m kn) of the normal spring. Friction from the FrictMat's frictionAngle.
    ``useFaceProperties``: a new contact between two intact-rock faces (``PotentialBlock``'s
    ``intactRock``) is a bond with the smaller of the faces' ``cohesion`` and ``tension``, its
    state ``cohesionBroken``, ``tensionBroken`` (Yade's defaults True: no bond). A scene of
    generated blocks sets both False for its first step and True afterwards (Yade scripts set
    them on the functor mid-run), so that only the faces that were cut are bonded.
    ``viscousDamping`` set mid-run applies to every contact from the next step."""
    _parameters = ("Knormal", "Kshear", "kn_i", "ks_i", "viscousDamping", "useFaceProperties", "cohesionBroken",
                   "tensionBroken")

    def __init__(self, label: str = "", **params):
        self._laws = []
        self._state = {}
        super().__init__(label, **params)

    def _live(name, cast):   # noqa: N805 (a property factory used in the class body)
        def get(self):
            return self._state.get(name)

        def set(self, value):
            self._state[name] = value
            for law in self._laws:
                law._set(name, cast(value))
        return property(get, set)

    # Set mid-run as Yade scripts do: the bonds' state, and the dashpot (WedgeYADE.py switches
    # viscousDamping from 0 to 0.5 after its first 500 steps, for every contact).
    cohesionBroken = _live("cohesionBroken", bool)
    tensionBroken = _live("tensionBroken", bool)
    viscousDamping = _live("viscousDamping", float)
    del _live


class Law2_SCG_KnKsPBPhys_KnKsPBLaw(LawFunctor):
    """F_n = Knormal A u_n n, incremental F_s with Kshear A, Coulomb friction, optional viscous
    damping (``allowViscousAttraction``: the damped normal force may pull). Bonds (see
    Ip2_FrictMat_FrictMat_KnKsPBPhys.useFaceProperties) pull down to -tension A and add
    cohesion A to the shear strength; ``allowBreakage``: a bond whose shear strength is
    exceeded breaks (else it yields at its strength); a bond pulled beyond its tension always
    breaks. ``initialOverlapDistance``: the overlap at zero normal force. ``neverErase`` and
    ``traceEnergy`` are accepted (energies follow O.trackEnergy)."""
    _cpp_name = "Law2_SCG_KnKsPBPhys_KnKsPBLaw"
    _parameters = ("allowViscousAttraction", "allowBreakage", "initialOverlapDistance", "neverErase", "traceEnergy")
    # Accepted, but not the law's: Yade's options without effect here, and the geometry's
    # settings that go to the scene (Ig2_PB_PB_ScGeom._applyToScene).
    _not_the_laws = ("neverErase", "traceEnergy", "twoDimension", "unitWidth2D", "twoDdir",
                     "exactDepth", "accuracyTol", "AabbMinMax")

    def _set(self, name: str, value):
        if name in self._not_the_laws:
            return
        super()._set(name, value)

    def _configure(self, phys: Functor):
        super()._configure(phys)
        if isinstance(phys, Ip2_FrictMat_FrictMat_KnKsPBPhys):
            phys._laws.append(self)   # for cohesionBroken, tensionBroken set mid-run

    def _configureGeometry(self, geomFunctors):
        """Take calContactArea from Ig2_PB_PB_ScGeom."""
        for g in geomFunctors:
            if isinstance(g, Ig2_PB_PB_ScGeom):
                for name, value in g._io_params().items():
                    self._set(name, value)


def _view(scene: "Scene", id: int) -> PotentialBlock:
    """``b.shape`` of a block: Yade's PotentialBlock, its planes in the body's principal frame."""
    s = _dem.block_shape(scene._cpp, id)
    n = np.asarray(s["normals"], dtype=float).reshape(-1, 3)
    return PotentialBlock(n[:, 0], n[:, 1], n[:, 2], s["d"], r=s["r"], R=s["R"], isBoundary=s["isBoundary"])


register(ShapeKind("PotentialBlock", view=_view, add=_add,
                   configure=lambda cpp, engines: geometry_functor(Ig2_PB_PB_ScGeom, engines)._applyToScene(cpp)))

__all__ = ["PotentialBlock", "potentialBlock", "blockShape", "blockVertices", "blockContact", "write_blocks",
           "PotentialBlock2AABB", "Ig2_PB_PB_ScGeom", "Ip2_FrictMat_FrictMat_KnKsPBPhys",
           "Law2_SCG_KnKsPBPhys_KnKsPBLaw"]
