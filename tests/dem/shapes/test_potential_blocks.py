"""Potential Blocks: shape properties, contact geometry and the KnKsPB law against analytic
values (Yade's Debian build has no PotentialBlock to compare with)."""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, Law2_SCG_KnKsPBPhys_KnKsPBLaw, NewtonIntegrator,
                       PotentialBlock, PotentialBlock2AABB, Scene, blockContact, blockShape, blockVertices,
                       potentialBlock, wall, write_blocks)

from test_potential_particles import quat, scene

pytestmark = pytest.mark.skipif(not _dem.have_potential_blocks, reason="built without CLP")

T = math.sqrt(1 / 3)
# The corner tetrahedron x, y, z >= 0, x + y + z <= 1.
TETRA = dict(a=[-1, 0, 0, T], b=[0, -1, 0, T], c=[0, 0, -1, T], d=[0, 0, 0, T])


def test_tetrahedron_volume_centroid_and_principal_inertia():
    S, m = scene()
    i = S.bodies.append(potentialBlock(PotentialBlock(**TETRA), material=m))
    # Analytic: V = 1/6, centroid (1/4, 1/4, 1/4), central inertia per density 1/80 on the
    # diagonal and 1/480 off it: principal 1/96 (twice) and 1/60 (along (1, 1, 1)).
    assert blockShape(S, i)["volume"] == pytest.approx(1 / 6, rel=1e-12)
    assert np.allclose(S.bodies[i].state.pos, 0.25, atol=1e-12)
    assert np.allclose(np.sort(S._cpp.inertia()[i]) / 1000, [1 / 96, 1 / 96, 1 / 60], rtol=1e-10)
    assert S._cpp.mass()[i] == pytest.approx(1000 / 6, rel=1e-12)
    # The body frame is the principal frame, yet the block sits where its planes put it.
    v = blockVertices(S, i)
    expected = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    assert all(np.min(np.linalg.norm(v - e, axis=1)) < 1e-12 for e in expected)


def test_turned_cuboid_inertia_and_tight_aabb():
    S, m = scene()
    shape = PotentialBlock.cuboid((0.5, 0.2, 0.1), r=0.01)
    i = S.bodies.append(potentialBlock(shape, pos=(1, 2, 3), orientation=quat((0, 0, 1), math.pi / 4), material=m))
    mass = 1000 * 1.0 * 0.4 * 0.2
    assert S._cpp.mass()[i] == pytest.approx(mass, rel=1e-12)
    a, b, c = 1.0, 0.4, 0.2   # edge lengths
    expected = sorted([mass / 12 * (b * b + c * c), mass / 12 * (a * a + c * c), mass / 12 * (a * a + b * b)])
    assert np.allclose(np.sort(S._cpp.inertia()[i]), expected, rtol=1e-10)
    lo, hi = _dem.block_aabb(S._cpp, i)
    half = (0.5 + 0.2) / math.sqrt(2)   # a rectangle turned by 45 degrees
    assert np.allclose(hi - lo, [2 * half, 2 * half, 0.2], rtol=1e-12)
    assert np.allclose((hi + lo) / 2, [1, 2, 3], atol=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    (dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, 1], d=[1] * 6), "do not bound a finite"),
    (dict(a=[2, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1], d=[1] * 6), "plane 0 has a non-unit"),
    (dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1], d=[1, -2, 1, 1, 1, 1]), "empty"),
    (dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1], d=[1] * 6, r=-0.1), "r must be"),
    (dict(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1], d=[1] * 6, R=-1), "R must be"),
    (dict(a=[1, -1, 0], b=[0, 0, 1, -1], c=[0, 0, 0, 0], d=[1] * 4), "same length"),
])
def test_bad_planes_are_refused_naming_the_block(kwargs, message):
    S, m = scene()
    S.bodies.append(wall(0, axis=2, material=m))
    with pytest.raises(ValueError, match=f"PotentialBlock #1: .*{message}"):
        S.bodies.append(potentialBlock(PotentialBlock(**kwargs), material=m))


def test_face_to_face_overlap_normal_and_area():
    S, m = scene()
    cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.02)
    a = S.bodies.append(potentialBlock(cube, pos=(0, 0, 0), material=m))
    b = S.bodies.append(potentialBlock(cube, pos=(0.3, -0.1, 0.999), material=m))
    g = blockContact(S, a, b)
    assert g["touching"]
    assert np.allclose(g["normal"], [0, 0, 1], atol=1e-12)
    assert g["penetrationDepth"] == pytest.approx(1e-3, rel=1e-9)
    assert g["contactArea"] == pytest.approx(0.7 * 0.9, rel=1e-9)
    assert np.allclose(g["contactPoint"], [0.15, -0.05, 0.4995], atol=1e-9)
    # Turned by 45 degrees about the normal: a square and a diamond overlap in an octagon.
    d = S.bodies.append(potentialBlock(cube, pos=(0, 0, 0.999), orientation=quat((0, 0, 1), math.pi / 4), material=m))
    g = blockContact(S, a, d)
    octagon = 2 * (math.sqrt(2) - 1)   # area of a unit square cut by the 45-degree square
    assert g["contactArea"] == pytest.approx(octagon, rel=1e-9)
    assert g["penetrationDepth"] == pytest.approx(1e-3, rel=1e-9)
    # Separated: no contact
    S.bodies[b].state.pos = (0, 0, 1.001)
    assert not blockContact(S, a, b)["touching"]


def test_vertex_face_uses_the_linear_program_and_the_face_normal():
    S, m = scene()
    cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.05)
    a = S.bodies.append(potentialBlock(cube, pos=(0, 0, 0), material=m))
    # A cube standing on a corner above a's top face, that corner 2e-3 deep.
    # The turn taking the body diagonal (1, 1, 1) to z puts corner (-1, -1, -1) lowest, sqrt(3)/2 below.
    q = quat(np.cross([1, 1, 1], [0, 0, 1]), math.acos(1 / math.sqrt(3)))
    b = S.bodies.append(potentialBlock(cube, pos=(0.1, 0.05, 0.5 + math.sqrt(3) / 2 - 2e-3), orientation=q, material=m))
    assert blockVertices(S, b)[:, 2].min() == pytest.approx(0.5 - 2e-3, abs=1e-12)
    g = blockContact(S, a, b)
    assert g["touching"] and g["lpSolves"] == 1   # one corner inside: its mean lies on b's surface
    assert np.allclose(g["normal"], [0, 0, 1], atol=1e-9)
    # The chord through the analytic centre, which the far (redundant) faces pull slightly off
    # the corner's axis: 4e-4 short of the corner's depth.
    assert g["penetrationDepth"] == pytest.approx(2e-3, rel=1e-3)
    assert np.all(np.isfinite(g["contactPoint"])) and g["contactArea"] > 0


def _mul(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def crossed_bars(S, m):
    """Two bars turned 45 degrees about their axes, crossing at right angles, an edge of each
    1e-3 m into the other; returns their ids."""
    bar = PotentialBlock.cuboid((1.0, 0.2, 0.2), r=0.02)
    a = S.bodies.append(potentialBlock(bar, pos=(0, 0, 0), orientation=quat((1, 0, 0), math.pi / 4), material=m))
    b = S.bodies.append(potentialBlock(bar, pos=(0, 0, 0.4 * math.sqrt(2) - 1e-3),
                                       orientation=_mul(quat((0, 0, 1), math.pi / 2), quat((1, 0, 0), math.pi / 4)),
                                       material=m))
    return a, b


def test_edge_to_edge_crossing_gives_a_finite_unit_normal():
    S, m = scene()
    a, b = crossed_bars(S, m)
    g = blockContact(S, a, b)
    assert g["touching"]
    assert np.linalg.norm(g["normal"]) == pytest.approx(1, abs=1e-12)
    assert g["normal"][2] > 0.99   # the crossing edges' common normal is z
    assert g["penetrationDepth"] == pytest.approx(1e-3, rel=1e-2)


def engines(S, Knormal=1e8, Kshear=1e7, damping=0.0, viscous=0.0, gravity=(0, 0, -9.81), **geometry):
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PB_PB_ScGeom(calContactArea=True, **geometry)],
                                 [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=Knormal, Kshear=Kshear, kn_i=Knormal,
                                                                   ks_i=Kshear, viscousDamping=viscous)],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw()]),
                 NewtonIntegrator(gravity=gravity, damping=damping)]


@pytest.mark.parametrize("base", ["wall", "block"])
def test_cube_resting_on_a_base_reaches_the_weight(base):
    S, m = scene(density=1000)
    if base == "wall":
        S.bodies.append(wall(0, axis=2, sense=1, material=m))
    else:
        plate = PotentialBlock.cuboid((2, 2, 0.25), r=0.02, isBoundary=True)
        S.bodies.append(potentialBlock(plate, pos=(0, 0, -0.25), material=m, fixed=True))
    cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.02)
    c = S.bodies.append(potentialBlock(cube, pos=(0.2, 0, 0.5), material=m))
    engines(S, Knormal=1e8, damping=0.3, viscous=0.5)
    S.dt = 2e-4
    S.run(3000, True)
    weight = 1000 * 9.81
    contacts = S._cpp.contacts()
    assert len(contacts) == 1
    f = contacts[0]["normalForce"]
    assert f[2] == pytest.approx(weight, rel=1e-6)
    assert contacts[0]["penetrationDepth"] == pytest.approx(weight / 1e8, rel=1e-4)
    assert _dem.contact_areas(S._cpp)[0] == pytest.approx(1.0, rel=1e-9)
    assert S.bodies[c].state.pos[2] == pytest.approx(0.5 - weight / 1e8, rel=1e-6)


def test_vtk_output_has_the_true_faces(tmp_path):
    S, m = scene()
    S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.01), material=m))
    S.bodies.append(potentialBlock(PotentialBlock(**TETRA), material=m))
    path = tmp_path / "blocks.vtu"
    assert write_blocks(S, str(path)) == 2
    text = path.read_text()
    assert 'NumberOfPoints="12"' in text and 'NumberOfCells="10"' in text


def test_a_block_body_shows_its_planes_as_yade_does():
    S = Scene()
    S.materials.append(FrictMat(density=2000))
    i = S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.5, 0.25, 0.125), r=0.01), pos=(0, 0, 1)))
    shape = S.bodies[i].shape
    assert isinstance(shape, PotentialBlock) and shape.r == 0.01 and len(shape.a) == 6
    np.testing.assert_allclose(sorted(shape.d), sorted([0.49, 0.49, 0.24, 0.24, 0.115, 0.115]), atol=1e-12)


def test_2d_area_is_the_joint_length_times_the_unit_width():
    """Yade's 2D mode: a cube on a plank along y (the out-of-plane direction twoDdir), 0.4 m of
    their x extents overlapping: the joint is 0.4 m long, the area 0.4 unitWidth2D (in 3D the
    section, 0.4 x 1)."""
    S, m = scene()
    plank = S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.3, 3.0, 0.5), r=0.02), pos=(0, 0, 0), material=m))
    cube = S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.02), pos=(0.4, 0.2, 0.999),
                                          material=m))
    engines(S)
    g3 = blockContact(S, plank, cube)
    assert g3["contactArea"] == pytest.approx(0.4 * 1.0, rel=1e-12)
    engines(S, twoDimension=True, unitWidth2D=0.7)
    g2 = blockContact(S, plank, cube)
    assert g2["contactArea"] == pytest.approx(0.4 * 0.7, rel=1e-12)
    assert g2["penetrationDepth"] == g3["penetrationDepth"] and np.array_equal(g2["normal"], g3["normal"])
    engines(S, twoDimension=True, unitWidth2D=0.7, twoDdir=(1, 0, 0))   # the joint then runs along y
    assert blockContact(S, plank, cube)["contactArea"] == pytest.approx(1.0 * 0.7, rel=1e-12)
    with pytest.raises(ValueError, match="unitWidth2D must be finite and > 0"):
        engines(S, twoDimension=True, unitWidth2D=0)


def test_2d_prism_resting_on_a_wall_carries_its_weight():
    """A prism 1 m wide (x), 6 m long along twoDdir = y, in 2D mode with unitWidth2D = 1: the
    contact area is the joint, 1 m x 1, so it settles at the overlap m g / (Knormal x 1)
    (in 3D it would be six times smaller, the section being 6 m^2)."""
    S, m = scene(density=1000)
    S.bodies.append(wall(0, axis=2, sense=1, material=m))
    c = S.bodies.append(potentialBlock(PotentialBlock.cuboid((0.5, 3.0, 0.5), r=0.02), pos=(0, 0, 0.5), material=m))
    engines(S, Knormal=1e8, damping=0.3, viscous=0.5, twoDimension=True, unitWidth2D=1.0)
    S.dt = 2e-4
    S.run(3000, True)
    weight = 1000 * 6.0 * 9.81
    contacts = S._cpp.contacts()
    assert len(contacts) == 1
    assert contacts[0]["normalForce"][2] == pytest.approx(weight, rel=1e-6)
    assert _dem.contact_areas(S._cpp)[0] == pytest.approx(1.0, rel=1e-12)
    assert contacts[0]["penetrationDepth"] == pytest.approx(weight / 1e8, rel=1e-4)
    assert S.bodies[c].state.pos[2] == pytest.approx(0.5 - weight / 1e8, rel=1e-6)


def test_exact_depth_option_gives_the_penetration_depth():
    """exactDepth: crossed bars (an edge-edge contact) 1e-3 m deep, a cube's corner 2e-3 m into
    another's face and into a wall: the depth exactly (the seed's chord: within 1 % for the
    bars, 4e-4 short for the corner into the face)."""
    S, m = scene()
    a, b = crossed_bars(S, m)
    cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.05)
    corner_down = quat(np.cross([1, 1, 1], [0, 0, 1]), math.acos(1 / math.sqrt(3)))
    c = S.bodies.append(potentialBlock(cube, pos=(5, 0, 0), material=m))
    d = S.bodies.append(potentialBlock(cube, pos=(5.1, 0.05, 0.5 + math.sqrt(3) / 2 - 2e-3), orientation=corner_down,
                                       material=m))
    w = S.bodies.append(wall(-3, axis=2, sense=1, material=m))
    e = S.bodies.append(potentialBlock(cube, pos=(0, 5, -3 + math.sqrt(3) / 2 - 2e-3), orientation=corner_down,
                                       material=m))
    engines(S)
    chord = blockContact(S, c, d)["penetrationDepth"]
    assert chord == pytest.approx(2e-3, rel=1e-3) and abs(chord - 2e-3) > 1e-7
    engines(S, exactDepth=True)
    g = blockContact(S, a, b)
    assert g["penetrationDepth"] == pytest.approx(1e-3, rel=1e-9)
    assert np.allclose(g["normal"], [0, 0, 1], atol=1e-12)
    g = blockContact(S, c, d)
    assert g["penetrationDepth"] == pytest.approx(2e-3, rel=1e-9)
    assert np.allclose(g["normal"], [0, 0, 1], atol=1e-12)
    assert blockContact(S, w, e)["penetrationDepth"] == pytest.approx(2e-3, rel=1e-9)


def test_accuracy_tolerance_of_the_geometry_functor_reaches_the_solver():
    """Ig2_PB_PB_ScGeom(accuracyTol=...) sets the analytic centre's tolerance of every block
    contact, in the simulation and in the probe (a loose one moves the seed's chord of a corner
    into a face); 0 is refused."""
    def corner_into_face(**geometry):
        S, m = scene()
        cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.05)
        corner_down = quat(np.cross([1, 1, 1], [0, 0, 1]), math.acos(1 / math.sqrt(3)))
        S.bodies.append(potentialBlock(cube, pos=(0, 0, 0), material=m, fixed=True))
        S.bodies.append(potentialBlock(cube, pos=(0.1, 0.05, 0.5 + math.sqrt(3) / 2 - 2e-3), orientation=corner_down,
                                       material=m, fixed=True))
        engines(S, **geometry)
        return S

    tight, loose = corner_into_face(), corner_into_face(accuracyTol=0.1)
    assert blockContact(tight, 0, 1)["penetrationDepth"] == blockContact(tight, 0, 1, accuracyTol=1e-10)["penetrationDepth"]
    assert blockContact(loose, 0, 1)["penetrationDepth"] == blockContact(loose, 0, 1, accuracyTol=0.1)["penetrationDepth"]
    for S in (tight, loose):
        S.run(1, True)
    depths = [S._cpp.contacts()[0]["penetrationDepth"] for S in (tight, loose)]
    assert depths[0] == pytest.approx(2e-3, rel=1e-3) and depths[1] != depths[0]
    with pytest.raises(ValueError, match="accuracyTol must be finite and > 0"):
        engines(tight, accuracyTol=0)
