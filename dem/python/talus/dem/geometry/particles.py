"""Potential Particles (Yade's PotentialParticle; Houlsby 2009, Boon et al. 2013): rounded convex
particles given by planes and a fraction of a sphere.

    mat = O.materials.append(FrictMat(density=2000, frictionAngle=radians(30)))
    cube = PotentialParticle.cuboid((0.5, 0.5, 0.5), r=0.05, k=0.2)
    O.bodies.append(potentialParticle(cube, pos=(0, 0, 0.5), material=mat))
    O.engines = [ForceResetter(), InsertionSortCollider([PotentialParticle2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PP_PP_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=1e8, Kshear=1e7, viscousDamping=0.2)],
                                 [Law2_SCG_KnKsPhys_KnKsLaw()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0)]

The particle is f <= 0 for the normalised potential
f = (1 - k) (sum <a_i x + b_i y + c_i z - d_i>^2 / r^2 - 1) + k (|x|^2 / R^2 - 1); volume,
centroid and principal inertia are computed. Particles interact with particles and with walls
(``wall``); two boundary particles (``isBoundary``) do not interact.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from talus import _dem
from talus.atomic import write_atomically
from talus.dem.core.bodies import BodySpec
from talus.dem.geometry.convex_contact import geometry_functor, two_dimension
from talus.dem.step.engines import Functor, LawFunctor
from talus.dem.core.masks import group_mask
from talus.dem.geometry.shape_registry import ShapeKind, register
from talus.dem.files.vtu import vtu_bytes

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

VTK_QUAD = 9


class PotentialParticle:
    """The shape of a particle, with Yade's argument names (a, b, c, d, r, k, R, isBoundary).
    Yade's display and Aabb options (color, wire, highlight, minAabb, maxAabb, minAabbRotated,
    maxAabbRotated, AabbMinMax, fixedNormal, boundaryNormal, id, vertices) are accepted and
    ignored: Talus bounds particles exactly by their support points."""
    def __init__(self, a, b, c, d, r, k, R, isBoundary=False, **yadeOptions):
        self.a, self.b, self.c, self.d = (list(map(float, v)) for v in (a, b, c, d))
        self.r, self.k, self.R, self.isBoundary = float(r), float(k), float(R), bool(isBoundary)
        self.extra = yadeOptions

    def __repr__(self):
        return (f"PotentialParticle(a={self.a}, b={self.b}, c={self.c}, d={self.d}, r={self.r}, k={self.k}, "
                f"R={self.R}, isBoundary={self.isBoundary})")

    @classmethod
    def cuboid(cls, halfSizes, r, k, R=None, **kw) -> "PotentialParticle":
        """The six planes of a rectangular particle, written as Yade's examples do (d = half-size
        - r; R: half the diagonal unless given). Its faces bulge by the sphere term."""
        hx, hy, hz = (float(h) for h in halfSizes)
        R = float(np.sqrt(hx * hx + hy * hy + hz * hz)) if R is None else R
        return cls(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1],
                   d=[hx - r, hx - r, hy - r, hy - r, hz - r, hz - r], r=r, k=k, R=R, **kw)

    def properties(self, quadrature: int = 96) -> dict:
        """Volume, centroid, principal axes and inertia (per density) at the given quadrature."""
        return _dem.potential_particle_properties(self.a, self.b, self.c, self.d, self.r, self.k, self.R,
                                                  int(quadrature))


def potentialParticle(shape: PotentialParticle, pos=(0.0, 0.0, 0.0), orientation=(1.0, 0.0, 0.0, 0.0),
                      material=-1, fixed: bool = False, mask=1, **_ignored) -> BodySpec:
    """A body of the given shape whose local frame (the planes' frame) is at ``pos``, turned by
    ``orientation`` (w, x, y, z), as Yade's state.pos and state.ori. Mass and inertia come from
    the material's density and the computed volume and principal inertia."""
    if hasattr(orientation, "w"):
        orientation = (orientation.w, orientation.x, orientation.y, orientation.z)
    q = tuple(float(x) for x in orientation)
    if len(q) != 4:
        raise ValueError(f"potentialParticle: orientation must be a quaternion (w, x, y, z), got {orientation!r}")
    return BodySpec("PotentialParticle", tuple(float(x) for x in pos), material=material, fixed=fixed,
                    orientation=q, block=shape, group_mask=group_mask(mask, "potentialParticle"))


def _add(scene: "Scene", spec: BodySpec, material: int) -> int:
    """Add a PotentialParticle body spec to the scene (O.bodies.append)."""
    s = spec.block
    return _dem.add_potential_particle(scene._cpp, s.a, s.b, s.c, s.d, s.r, s.k, s.R, s.isBoundary,
                                       np.asarray(spec.center, dtype=float), np.asarray(spec.orientation, dtype=float),
                                       material, bool(spec.fixed))


def particleShape(scene: "Scene", id: int) -> dict:
    """Planes (in the shape frame), r, k, R, volume, principal inertia per density, the
    principal axes and centroid in the shape frame, bounding radius."""
    return _dem.particle_shape(scene._cpp, int(id))


def particleContact(scene: "Scene", id1: int, id2: int, repeats: int = 1, accuracyTol: float | None = None) -> dict:
    """Contact geometry of a particle pair (or wall id1, particle id2) as it stands now, and the
    solver's mean time per call over ``repeats`` calls (``seconds`` cold, ``secondsWarm``
    starting from the contact point). ``accuracyTol``: the solver's tolerance on |f1 - f2| at
    the contact point (None: the simulation's default)."""
    if accuracyTol is None:
        return _dem.particle_contact(scene._cpp, int(id1), int(id2), int(repeats))
    return _dem.particle_contact(scene._cpp, int(id1), int(id2), int(repeats), float(accuracyTol))


def particlePotential(scene: "Scene", id: int, points) -> np.ndarray:
    """The potential f of particle ``id`` at world points (negative inside)."""
    return _dem.particle_potential(scene._cpp, int(id), np.asarray(points, dtype=float).reshape(-1, 3))


def write_particles(scene: "Scene", path: str, nTheta: int = 24, nPhi: int = 48) -> int:
    """Write the live Potential Particles of ``scene`` to ``path`` (.vtu) as closed surfaces
    (quads on rays from each centroid to the true surface; cell data ``id``, ``velocity``);
    returns their number."""
    cpp = scene._cpp
    ids = [i for i in range(len(cpp.pos())) if cpp.alive()[i] and cpp.shapeKind(i) == "PotentialParticle"]
    points, conn, owner = [], [], []
    base = 0
    for i in ids:
        pts = np.asarray(_dem.particle_surface(cpp, i, nTheta, nPhi))
        points.append(pts)
        for t in range(nTheta):
            for q in range(nPhi):
                q1 = (q + 1) % nPhi
                conn.extend(base + k for k in (t * nPhi + q, t * nPhi + q1, (t + 1) * nPhi + q1, (t + 1) * nPhi + q))
                owner.append(i)
        base += len(pts)
    pts = np.concatenate(points) if points else np.zeros((0, 3))
    owner = np.asarray(owner, dtype=np.int32)
    offsets = 4 * np.arange(1, len(owner) + 1, dtype=np.int64)
    data = {"id": owner, "velocity": cpp.vel()[owner] if len(owner) else np.zeros((0, 3))}
    write_atomically(path, vtu_bytes(pts, np.asarray(conn, dtype=np.int64), offsets,
                                  np.full(len(owner), VTK_QUAD, dtype=np.uint8), cell_data=data, time=cpp.time))
    return len(ids)


# Yade's functors for Potential Particles.
class PotentialParticle2AABB(Functor):
    """Bounding box of particles (accepted; Talus bounds them exactly by support points)."""
    _parameters = ("aabbEnlargeFactor",)


class Ig2_PP_PP_ScGeom(Functor):
    """Particle-particle and wall-particle contact geometry. ``calContactArea`` False: area 1
    (constant stiffnesses). ``areaStep`` and ``accuracyTol`` are accepted for Yade's scripts
    but not used: Talus integrates the section with 72 rays (Yade's default 5 degrees) and
    solves every contact to its own tolerance, 1e-8 on |f1 - f2| (``particleContact`` takes
    another for a probe; docs/blocks.md charts error against cost). ``twoDimension`` (2D mode,
    as the blocks'): the particles are prisms along ``twoDdir`` (default (0, 1, 0)) and the
    contact area is the joint length (the overlap region's chord through the contact point
    along normal x twoDdir) times ``unitWidth2D`` (default 1)."""
    _parameters = ("calContactArea", "twoDimension", "unitWidth2D", "areaStep", "accuracyTol", "twoDdir")

    def _applyToScene(self, cpp):
        """Set the 2D settings for every particle contact of the scene whose engines hold us."""
        _dem.set_particle_contact_settings(cpp, *two_dimension(self))


class Ip2_FrictMat_FrictMat_KnKsPhys(Functor):
    """Stiffnesses per unit contact area ``Knormal``, ``Kshear`` (``kn_i``, ``ks_i`` accepted:
    Yade's particle law does not use them); ``viscousDamping``: fraction of the critical damping
    2 sqrt(m kn) of the normal spring. Friction from the FrictMat's frictionAngle."""
    _parameters = ("Knormal", "Kshear", "kn_i", "ks_i", "viscousDamping", "useFaceProperties")


class Law2_SCG_KnKsPhys_KnKsLaw(LawFunctor):
    """F_n = Knormal A u_n n, incremental F_s with Kshear A, Coulomb friction on the (damped)
    normal force, optional viscous damping (``allowViscousAttraction``: the damped normal force
    may pull). ``neverErase``, ``traceEnergy`` accepted (energies follow O.trackEnergy); Yade's
    rock-joint options (``allowBreakage``, ``Talesnick``, ``initialOverlapDistance``) only at
    their defaults."""
    _cpp_name = "Law2_SCG_KnKsPhys_KnKsLaw"
    _parameters = ("allowViscousAttraction", "neverErase", "traceEnergy", "preventGranularRatcheting",
                   "allowBreakage", "Talesnick", "initialOverlapDistance")
    _yade_only = ("neverErase", "traceEnergy", "useFaceProperties", "twoDimension", "unitWidth2D", "areaStep",
                  "accuracyTol", "twoDdir", "preventGranularRatcheting")
    _default_only = {"allowBreakage": False, "Talesnick": False, "initialOverlapDistance": 0.0}

    def _set(self, name: str, value):
        if name in self._default_only:
            if value != self._default_only[name]:
                raise ValueError(f"Law2_SCG_KnKsPhys_KnKsLaw: {name}={value!r} is not supported "
                                 f"(only {self._default_only[name]!r})")
            return
        if name in self._yade_only:
            if name == "useFaceProperties" and value:
                raise ValueError("Ip2_FrictMat_FrictMat_KnKsPhys: useFaceProperties=True is not supported")
            return
        super()._set(name, value)

    def _configureGeometry(self, geomFunctors):
        """Take calContactArea from Ig2_PP_PP_ScGeom."""
        for g in geomFunctors:
            if isinstance(g, Ig2_PP_PP_ScGeom):
                for name, value in g._io_params().items():
                    self._set(name, value)


def _view(scene: "Scene", id: int) -> PotentialParticle:
    """``b.shape`` of a particle: Yade's PotentialParticle, its planes in the shape frame."""
    s = _dem.particle_shape(scene._cpp, id)
    n = np.asarray(s["normals"], dtype=float).reshape(-1, 3)
    return PotentialParticle(n[:, 0], n[:, 1], n[:, 2], s["d"], r=s["r"], k=s["k"], R=s["R"],
                             isBoundary=s["isBoundary"])


register(ShapeKind("PotentialParticle", view=_view, add=_add,
                   configure=lambda cpp, engines: geometry_functor(Ig2_PP_PP_ScGeom, engines)._applyToScene(cpp)))

__all__ = ["PotentialParticle", "potentialParticle", "particleShape", "particleContact", "particlePotential",
           "write_particles", "PotentialParticle2AABB", "Ig2_PP_PP_ScGeom", "Ip2_FrictMat_FrictMat_KnKsPhys",
           "Law2_SCG_KnKsPhys_KnKsLaw"]
