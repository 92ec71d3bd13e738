"""The seed's rock wedge (cases/dem/dem_rock_wedge.py) in small: blocks generated from joints of
jointC.csv partition the rock, Yade's minSize pruning, the limit equilibrium of a block
(talus.dem.analysis.analytic.block_sliding_mode) against Hoek & Bray's closed forms, and a wedge freed by
a cut that holds above and slides below its critical friction."""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, Law2_SCG_KnKsPBPhys_KnKsPBLaw, NewtonIntegrator,
                       PotentialBlock, PotentialBlock2AABB, Scene, blockShape, generateBlocks, potentialBlock,
                       readJoints)
from talus.dem.analysis.analytic import block_sliding_mode
from talus.dem.geometry.blockgen import Joint, dipNormal

pytestmark = pytest.mark.skipif(not _dem.have_potential_blocks, reason="built without CLP")

HEADER = "dip;dipDir;centreX;centreY;centreZ;traceX;traceY;phi_b;phi_r;JRC;JSC;asperity;simgaC;cohesion;tension; jointType;\n"
# jointC.csv's cut (90/315) and one joint of each of its four sets, through the origin.
SUBSET = "".join(f"{dip};{dd};0;0;0;10000;10000;40;40;0;0;0;0;787000;76000;1;joint;\n"
                 for dip, dd in [(90, 315), (60, 240), (60, 90), (70, 160), (70, 350)])


def box(half, top, bottom, r=0.05):
    """x, y in [-half, half], z (down) in [top, bottom]."""
    return PotentialBlock(a=[1, -1, 0, 0, 0, 0], b=[0, 0, 1, -1, 0, 0], c=[0, 0, 0, 0, 1, -1],
                          d=[half - r, half - r, half - r, half - r, bottom - r, -top - r], r=r)


def volumes(blocks):
    S = Scene()
    m = S.materials.append(FrictMat())
    return [blockShape(S, i)["volume"] for i in S.bodies.append([potentialBlock(b, material=m) for b in blocks])]


def test_blocks_from_joints_of_jointC_partition_the_rock(tmp_path):
    path = tmp_path / "joints.csv"
    path.write_text(HEADER + SUBSET)
    blocks = generateBlocks(box(5, -5, 5), readJoints(str(path)))
    v = volumes(blocks)
    assert len(blocks) >= 16   # the cut and four sets through the centre: at least 2^4 pieces
    assert sum(v) == pytest.approx(1000.0, rel=1e-10)
    assert min(v) > 0


def test_min_size_leaves_a_block_uncut_by_a_joint_that_would_make_a_thin_piece():
    cube = box(1, -1, 1)
    thin = Joint(dipNormal(90, 180), np.array([0.8, 0, 0]))     # would leave a slab 0.2 m thick
    half = Joint(dipNormal(90, 180), np.zeros(3))
    assert len(generateBlocks(cube, [thin])) == 2
    assert len(generateBlocks(cube, [thin], minSize=0.5)) == 1
    assert len(generateBlocks(cube, [half, thin], minSize=0.5)) == 2          # 1 m pieces: cut
    assert len(generateBlocks(cube, [half], minSize=1.5)) == 1                # inscribed ball 1 m < 1.5
    assert len(generateBlocks(cube, [half], maxRatio=1.5)) == 1               # 2 m long / 1 m across
    with pytest.raises(ValueError, match="minSize must be finite and >= 0"):
        generateBlocks(cube, [half], minSize=-1)


def test_limit_equilibrium_against_hoek_and_bray():
    W = np.array([0, 0, 1.0])   # z down
    # Plane sliding on a face dipping psi: FS = tan phi / tan psi.
    psi = math.radians(35)
    mode = block_sliding_mode(W, [dipNormal(35, 0), dipNormal(90, 90), dipNormal(90, 270)], [0.7, 0, 0])
    assert mode["mode"] == "plane" and mode["FS"] == pytest.approx(0.7 / math.tan(psi), rel=1e-12)
    # Symmetric wedge (line plunging psi along x, wedge angle xi, beta = 90 deg):
    # FS = tan phi / (tan psi sin(xi / 2)).
    psi, xi = math.radians(40), math.radians(70)
    s = np.array([math.cos(psi), 0, math.sin(psi)])
    down = np.array([-math.sin(psi), 0, math.cos(psi)])
    e = np.array([0, 1.0, 0])
    faces = [math.cos(xi / 2) * e + math.sin(xi / 2) * down, -math.cos(xi / 2) * e + math.sin(xi / 2) * down]
    mode = block_sliding_mode(W, faces, 0.6)
    assert mode["mode"] == "wedge"
    assert np.allclose(mode["direction"], s, atol=1e-12)
    assert mode["FS"] == pytest.approx(0.6 / (math.tan(psi) * math.sin(xi / 2)), rel=1e-12)
    # A block held from below all round is not removable; one hanging free falls.
    assert block_sliding_mode(W, faces + [np.array([1.0, 0, 0])], 0.6)["mode"] == "none"
    assert block_sliding_mode(W, [np.array([0, 0, -1.0])], 0.6)["mode"] == "lift"


def wedge_scene(phi_deg):
    """A 12 x 12 x 12 m rock cut by jointC's 60/090 and 70/160 joints through (0, 0, 6) and
    excavated south-east of its 90/315 joint through the origin: the piece above both joints
    is a wedge on them, free at the top and in the cut face; the other pieces are fixed.
    Returns the scene, the wedge's id and its sliding mode (friction phi_deg)."""
    joints = [Joint(dipNormal(90, 315), np.zeros(3)), Joint(dipNormal(60, 90), np.array([0, 0, 6.0])),
              Joint(dipNormal(70, 160), np.array([0, 0, 6.0]))]
    blocks = generateBlocks(box(6, 0, 12, r=0.02), joints)
    cut = dipNormal(90, 315)
    S = Scene()
    rock = S.materials.append(FrictMat(density=2700, frictionAngle=math.radians(phi_deg)))
    kept = [b for b in blocks if cut @ np.mean(_dem.potential_block_geometry(
        list(b.a), list(b.b), list(b.c), list(b.d), b.r, "block")["vertices"], axis=0) < 0]
    ids = S.bodies.append([potentialBlock(b, material=rock) for b in kept])
    above = [i for i in ids if _above_both(S, i, joints[1:])]
    assert len(above) == 1
    wedge = above[0]
    for i in ids:
        S.bodies[i].dynamic = i == wedge
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.05),
                 InteractionLoop([Ig2_PB_PB_ScGeom(calContactArea=True)],
                                 [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=2e8, Kshear=1e7, viscousDamping=0.5)],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw()]),
                 NewtonIntegrator(gravity=(0, 0, 9.81), damping=0.0)]
    S.dt = 2e-3
    m = blockShape(S, wedge)["volume"] * 2700 * 9.81
    shape = kept[ids.index(wedge)]
    free = [(np.array([0, 0, -1.0]), 0.0), (cut, 0.0)]
    normals = [n for n, h in zip(np.column_stack([shape.a, shape.b, shape.c]), np.asarray(shape.d) + shape.r)
               if not any(np.allclose(n, f) and abs(h - o) < 1e-9 for f, o in free)]
    return S, wedge, block_sliding_mode(np.array([0, 0, m]), normals, math.tan(math.radians(phi_deg)))


def _above_both(S, i, joints):
    corners = np.asarray(S.bodies[i].state.pos) + np.asarray(blockShape(S, i)["vertices"]) @ \
        S.bodies[i].state.ori.toRotationMatrix().T
    return all(((corners - j.centre) @ j.normal).max() < 1e-6 for j in joints)


@pytest.mark.parametrize("offset, slides", [(-1.5, True), (1.5, False)])
def test_wedge_holds_above_and_slides_below_its_critical_friction(offset, slides):
    # Hoek & Bray for the 60/090 - 70/160 wedge: phi_c = 55.84 deg (line plunging 58.9 deg).
    phi = 55.84 + offset
    S, wedge, mode = wedge_scene(phi)
    assert mode["mode"] == "wedge"
    assert (mode["FS"] < 1) == slides
    # Gravity ramped up over 0.5 s with Cundall damping (a sudden load makes the shear springs
    # overshoot: the wedge then slips ~0.1 m even 2 deg above its limit), then 1 s undamped.
    newton = S.engines[-1]
    newton.damping = 0.3
    for k in range(1, 21):
        newton.gravity = (0, 0, 9.81 * k / 20)
        S.run(13, True)
    newton.damping = 0.0
    start = np.array(S.bodies[wedge].state.pos)
    S.run(500, True)
    moved = np.array(S.bodies[wedge].state.pos) - start
    if slides:
        # Along the joints' intersection line, as limit equilibrium says.
        assert np.linalg.norm(moved) > 0.05
        assert moved / np.linalg.norm(moved) @ mode["direction"] > 0.999
    else:
        assert np.linalg.norm(moved) < 2e-3
