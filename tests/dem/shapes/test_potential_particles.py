"""Potential Particles: shape properties (volume, inertia, Aabb), contact geometry and the KnKs
law against analytic values and an independent voxel integration; bad input. (Degenerate
contacts: test_convex_degenerate_contacts.py; the side-by-side runs with Yade are in
cases/dem/dem_potential_particles.py.)"""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PP_PP_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPhys, Law2_SCG_KnKsPhys_KnKsLaw, NewtonIntegrator,
                       PotentialParticle, PotentialParticle2AABB, Scene, particleContact, particlePotential,
                       particleShape, potentialParticle, wall, write_particles)

CUBE = dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1])


def cube(d=0.45, r=0.05, k=0.2, R=math.sqrt(3) * 0.5, **kw):
    return PotentialParticle(**CUBE, d=[d] * 6, r=r, k=k, R=R, **kw)


def scene(density=1000.0, friction=0.5):
    S = Scene()
    m = S.materials.append(FrictMat(density=density, frictionAngle=friction))
    return S, m


def quat(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    return (math.cos(angle / 2), *(math.sin(angle / 2) * axis))


def face_centre(d, r, k, R):
    """Distance of a cube particle's face centre from its centre: the root s > d of
    (1 - k) ((s - d)^2 / r^2 - 1) + k (s^2 / R^2 - 1) = 0."""
    A = (1 - k) / r**2 + k / R**2
    B = -2 * d * (1 - k) / r**2
    C = (1 - k) * d * d / r**2 - 1
    return (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)


def test_sphere_limit_volume_and_inertia():
    # k = 1: f = |x|^2 / R^2 - 1, a ball of radius R whatever the planes.
    p = PotentialParticle(**CUBE, d=[0.3] * 6, r=0.05, k=1.0, R=0.4).properties()
    V = 4 / 3 * math.pi * 0.4**3
    assert p["volume"] == pytest.approx(V, rel=1e-9)
    assert np.allclose(p["inertiaPerDensity"], 0.4 * V * 0.4**2, rtol=1e-9)
    assert np.allclose(p["centroid"], 0, atol=1e-12)


def test_rounded_cube_limit_volume():
    # k -> 0: the planes at d expanded by r with rounded edges and corners, i.e. the Minkowski
    # sum of a cube of side 2d and a ball of radius r.
    d, r = 0.4, 0.1
    p = PotentialParticle(**CUBE, d=[d] * 6, r=r, k=1e-7, R=1.0).properties(quadrature=160)
    a = 2 * d
    V = a**3 + 6 * a * a * r + 3 * math.pi * a * r * r + 4 / 3 * math.pi * r**3
    assert p["volume"] == pytest.approx(V, rel=2e-5)


def test_asymmetric_particle_against_voxels():
    # A wedge-like particle off its origin: volume, centroid and principal inertia against a
    # voxel integration of f <= 0 (midpoint rule, h = 1/150 of the box).
    n = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, -1], [0.6, 0, 0.8]], float)
    shape = PotentialParticle(n[:, 0], n[:, 1], n[:, 2], d=[0.5, 0.3, 0.4, 0.4, 0.3, 0.35], r=0.08, k=0.3, R=0.7)
    S, m = scene(density=1.0)
    i = S.bodies.append(potentialParticle(shape, material=m))
    props = particleShape(S, i)
    h = 1.6 / 150
    g = -0.8 + h * (np.arange(150) + 0.5)
    X, Y, Z = np.meshgrid(g, g, g, indexing="ij")
    pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    inside = pts[particlePotential(S, i, pts) <= 0]
    V = len(inside) * h**3
    c = inside.mean(axis=0)
    q = inside - c
    J = h**3 * (np.eye(3) * (q * q).sum() - q.T @ q)
    assert props["volume"] == pytest.approx(V, rel=2e-3)
    assert np.allclose(S.bodies[i].state.pos, c, atol=2e-3)
    assert np.allclose(np.sort(S._cpp.inertia()[i]), np.sort(np.linalg.eigvalsh(J)), rtol=5e-3)
    # the body frame is the principal frame: the tensor turned into it is diagonal
    axes = np.asarray(props["axes"])
    Jb = axes.T @ J @ axes
    assert np.abs(Jb - np.diag(np.diag(Jb))).max() < 5e-3 * np.trace(J)


def test_aabb_is_tight_under_rotation():
    S, m = scene()
    q = quat((1, 2, 3), 0.7)
    i = S.bodies.append(potentialParticle(cube(d=0.3, r=0.05, k=0.3, R=0.6), pos=(1, 2, 3), orientation=q, material=m))
    lo, hi = _dem.particle_aabb(S._cpp, i)
    pts = np.asarray(_dem.particle_surface(S._cpp, i, 200, 400))
    # the box holds every surface point and its faces touch the surface (to the sampling's
    # resolution: rays 0.9 degrees apart, 3 mm on this surface)
    assert np.all(pts >= lo - 1e-12) and np.all(pts <= hi + 1e-12)
    assert np.abs(pts.max(axis=0) - hi).max() < 5e-4 and np.abs(pts.min(axis=0) - lo).max() < 5e-4
    # the surface points sampled are on f = 0
    assert np.abs(particlePotential(S, i, pts)).max() < 1e-9


BAD = [
    (dict(CUBE, d=[0.4] * 6, r=0.05, k=0.0, R=0.5), "k .* must be in \\(0, 1\\]"),
    (dict(CUBE, d=[0.4] * 6, r=0.05, k=1.5, R=0.5), "k .* must be in \\(0, 1\\]"),
    (dict(CUBE, d=[0.4] * 6, r=-0.05, k=0.2, R=0.5), "r .* must be finite and > 0"),
    (dict(CUBE, d=[0.4] * 6, r=0.05, k=0.2, R=-0.5), "R .* must be finite and > 0"),
    (dict(a=[2, -1, 0, 0, 0, 0], b=CUBE["b"], c=CUBE["c"], d=[0.4] * 6, r=0.05, k=0.2, R=0.5), "plane 0 has a non-unit"),
    (dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, 1], d=[0.4] * 6, r=0.05, k=0.2, R=0.5),
     "do not bound a finite"),
    (dict(a=[1, -1, 0], b=[0, 0, 1], c=[0, 0, 0], d=[1, 1, 1], r=0.05, k=0.2, R=0.5), "do not bound a finite|at least 4"),
    (dict(a=[1, -1], b=[0, 0, 1], c=[0, 0], d=[1, 1], r=0.05, k=0.2, R=0.5), "same length"),
    (dict(CUBE, d=[0.4, -0.6, 0.4, 0.4, 0.4, 0.4], r=0.05, k=0.2, R=0.5), "empty"),
]


@pytest.mark.parametrize("kwargs, message", BAD)
def test_bad_input_is_refused_naming_the_particle_and_parameter(kwargs, message):
    S, m = scene()
    S.bodies.append(wall(0, axis=2, material=m))
    with pytest.raises(ValueError, match=f"PotentialParticle #1: .*({message})"):
        S.bodies.append(potentialParticle(PotentialParticle(**kwargs), material=m))


def midplane_rays(shape, x0, u):
    """Distances from (x0, 0, 0) to the surface of a particle at the origin along the unit rows
    of u (bisection in numpy, independent of the C++ solvers)."""
    a, b, c = (np.asarray(v, float) for v in (shape.a, shape.b, shape.c))
    N = np.stack([a, b, c], axis=1)
    d = np.asarray(shape.d)

    def f(p):
        g = np.maximum(p @ N.T - d, 0)
        return (1 - shape.k) * ((g * g).sum(-1) / shape.r**2 - 1) + shape.k * ((p * p).sum(-1) / shape.R**2 - 1)

    lo, hi = np.zeros(len(u)), np.full(len(u), 2 * shape.R)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        inside = f(np.array([x0, 0, 0]) + mid[:, None] * u) <= 0
        lo, hi = np.where(inside, mid, lo), np.where(inside, hi, mid)
    return lo


def midplane_area(shape, x0, n=720):
    """Area of {(y, z) : f(x0, y, z) <= 0} of a particle at the origin."""
    th = 2 * np.pi * np.arange(n) / n
    rho = midplane_rays(shape, x0, np.stack([np.zeros(n), np.cos(th), np.sin(th)], axis=1))
    return 0.5 * np.sum(rho**2) * 2 * np.pi / n


@pytest.mark.parametrize("overlap", [1e-5, 1e-3, 2e-2])
def test_face_to_face_overlap_normal_point_and_area(overlap):
    shape = cube()
    s = face_centre(0.45, 0.05, 0.2, math.sqrt(3) * 0.5)
    S, m = scene()
    a = S.bodies.append(potentialParticle(shape, pos=(0, 0, 0), material=m))
    b = S.bodies.append(potentialParticle(shape, pos=(2 * s - overlap, 0, 0), material=m))
    g = particleContact(S, a, b)
    assert g["touching"]
    assert np.allclose(g["normal"], [1, 0, 0], atol=1e-9)
    assert g["penetrationDepth"] == pytest.approx(overlap, rel=1e-8, abs=1e-13)
    assert np.allclose(g["contactPoint"], [s - overlap / 2, 0, 0], atol=1e-9)
    assert g["contactArea"] == pytest.approx(midplane_area(shape, s - overlap / 2), rel=1e-3)
    # apart by 1e-9: no contact
    S.bodies[b].state.pos = (2 * s + 1e-9, 0, 0)
    assert not particleContact(S, a, b)["touching"]


def test_2d_area_is_the_joint_length_times_the_unit_width():
    """2D mode (as the blocks'): two cubes face to face along x, the prisms' axis twoDdir = y:
    the area is the overlap's chord along n x twoDdir = z through the contact point times
    unitWidth2D; a wall contact's chord runs along x; twoDdir along the normal leaves the
    section's area."""
    shape = cube()
    s = face_centre(0.45, 0.05, 0.2, math.sqrt(3) * 0.5)
    overlap = 1e-3
    S, m = scene()
    a = S.bodies.append(potentialParticle(shape, pos=(0, 0, 0), material=m))
    b = S.bodies.append(potentialParticle(shape, pos=(2 * s - overlap, 0, 0), material=m))
    w = S.bodies.append(wall(-3, axis=2, sense=1, material=m))
    p = S.bodies.append(potentialParticle(shape, pos=(0.3, -0.2, -3 + s - 1e-3), material=m))

    def engines(**geometry):
        S.engines = [ForceResetter(), InsertionSortCollider([PotentialParticle2AABB()]),
                     InteractionLoop([Ig2_PP_PP_ScGeom(**geometry)], [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=1e8)],
                                     [Law2_SCG_KnKsPhys_KnKsLaw()])]

    g3 = particleContact(S, a, b)
    engines(twoDimension=True, unitWidth2D=0.7)
    g2 = particleContact(S, a, b)
    joint = 2 * midplane_rays(shape, s - overlap / 2, np.array([[0.0, 0, 1]]))[0]
    assert g2["contactArea"] == pytest.approx(0.7 * joint, rel=1e-8)
    assert g2["penetrationDepth"] == g3["penetrationDepth"] and np.array_equal(g2["normal"], g3["normal"])
    wall_joint = 2 * midplane_rays(shape, s - 5e-4, np.array([[0.0, 1, 0]]))[0]   # the cube's section is square
    assert particleContact(S, w, p)["contactArea"] == pytest.approx(0.7 * wall_joint, rel=1e-8)
    engines(twoDimension=True, unitWidth2D=0.7, twoDdir=(1, 0, 0))   # along the normal: no chord in the plane
    assert particleContact(S, a, b)["contactArea"] == pytest.approx(g3["contactArea"], rel=1e-12)
    with pytest.raises(ValueError, match="unitWidth2D must be finite and > 0"):
        engines(twoDimension=True, unitWidth2D=0)


def test_wall_contact_is_the_support_depth():
    shape = cube()
    s = face_centre(0.45, 0.05, 0.2, math.sqrt(3) * 0.5)
    S, m = scene()
    w = S.bodies.append(wall(0, axis=2, sense=1, material=m))
    p = S.bodies.append(potentialParticle(shape, pos=(0.3, -0.2, s - 1e-3), material=m))
    g = particleContact(S, w, p)
    assert np.allclose(g["normal"], [0, 0, 1])
    assert g["penetrationDepth"] == pytest.approx(1e-3, rel=1e-8)
    assert np.allclose(g["contactPoint"], [0.3, -0.2, -5e-4], atol=1e-9)
    assert g["contactArea"] == pytest.approx(midplane_area(shape, s - 5e-4), rel=1e-3)


def make_scene(friction=0.5, damping=0.0, viscous=0.0, gravity=(0, 0, -9.81), kn=1e8, ks=1e7):
    S = Scene()
    m = S.materials.append(FrictMat(density=1000, frictionAngle=friction))
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialParticle2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PP_PP_ScGeom(calContactArea=True)],
                                 [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=kn, Kshear=ks, viscousDamping=viscous)],
                                 [Law2_SCG_KnKsPhys_KnKsLaw()]),
                 NewtonIntegrator(gravity=gravity, damping=damping)]
    S.dt = 2e-4
    return S, m


def test_cube_resting_on_a_wall_carries_its_weight(tmp_path):
    S, m = make_scene(damping=0.3, viscous=0.5)
    s = face_centre(0.45, 0.05, 0.2, math.sqrt(3) * 0.5)
    S.bodies.append(wall(0, axis=2, sense=1, material=m))
    i = S.bodies.append(potentialParticle(cube(), pos=(0, 0, s + 1e-4), material=m))
    S.run(4000, True)
    mass = S._cpp.mass()[i]
    contacts = S._cpp.contacts()
    assert len(contacts) == 1
    assert contacts[0]["normalForce"][2] == pytest.approx(mass * 9.81, rel=1e-6)
    assert np.linalg.norm(S.bodies[i].state.vel) < 1e-5
    # the overlap that carries it: Knormal A u = m g with the area the geometry reports
    area = _dem.contact_areas(S._cpp)[0]
    assert contacts[0]["penetrationDepth"] == pytest.approx(mass * 9.81 / (1e8 * area), rel=1e-6)
    # the VTK writer writes a closed surface
    assert write_particles(S, str(tmp_path / "pp.vtu")) == 1
    assert 'NumberOfCells="1152"' in (tmp_path / "pp.vtu").read_text()
