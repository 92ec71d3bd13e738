"""Block generation by joint planes (talus.dem.geometry.blockgen) and its joint file."""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, JointFileError, Law2_SCG_KnKsPBPhys_KnKsPBLaw,
                       NewtonIntegrator, PotentialBlock, PotentialBlock2AABB, Scene, blockShape, generateBlocks,
                       potentialBlock, readJoints, wall)
from talus.dem.geometry.blockgen import dipNormal

pytestmark = pytest.mark.skipif(not _dem.have_potential_blocks, reason="built without CLP")

HEADER = "dip;dipDir;centreX;centreY;centreZ;traceX;traceY;phi_b;phi_r;JRC;JSC;asperity;simgaC;cohesion;tension; jointType;\n"
# Three persistent joints through the origin: normals x (dip 90, dipDir 180), y (90, 270), z (dip 0).
THREE = "90;180;0;0;0;10000;10000;40;40;0;0;0;0;0;0;1;joint;\n90;270;0;0;0;10000;10000;40;40;0;0;0;0;0;0;1;joint;\n" \
        "0;0;0;0;0;10000;10000;40;40;0;0;0;0;0;0;1;joint;\n"


def joints(tmp_path, body):
    path = tmp_path / "joints.csv"
    path.write_text(HEADER + body)
    return readJoints(str(path))


def test_dip_convention_is_yades():
    assert np.allclose(dipNormal(90, 315), [-math.sqrt(0.5), math.sqrt(0.5), 0])
    assert np.allclose(dipNormal(0, 123), [0, 0, 1])
    assert np.allclose(dipNormal(90, 180), [1, 0, 0])


def test_three_persistent_joints_cut_a_cube_in_eight(tmp_path):
    blocks = generateBlocks(PotentialBlock.cuboid((1, 1, 1), r=0.05), joints(tmp_path, THREE))
    assert len(blocks) == 8
    S = Scene()
    m = S.materials.append(FrictMat(density=1000))
    ids = S.bodies.append([potentialBlock(b, material=m) for b in blocks])
    volumes = [blockShape(S, i)["volume"] for i in ids]
    assert np.allclose(volumes, 1.0, rtol=1e-12)
    assert all(len(blockShape(S, i)["faces"]) == 6 for i in ids)   # the planes kept are faces
    centres = np.array([S.bodies[i].state.pos for i in ids])
    assert np.allclose(np.sort(np.abs(centres), axis=0), 0.5)   # the octants' centres


def test_a_joint_ending_inside_the_block_cuts_it_and_a_distant_one_does_not(tmp_path):
    # Yade's BlockGen: a joint whose trace meets the block cuts it through (the rest of the cut is
    # rock bridge, test_block_rock_bridges.py); one beside it does not.
    short = "90;180;0;0;0;0.5;0.5;40;40;0;0;0;0;0;0;1;joint;\n"
    assert len(generateBlocks(PotentialBlock.cuboid((1, 1, 1), r=0.05), joints(tmp_path, short))) == 2
    off = "90;180;5;0;0;10000;10000;40;40;0;0;0;0;0;0;1;joint;\n"   # outside the block
    assert len(generateBlocks(PotentialBlock.cuboid((1, 1, 1), r=0.05), joints(tmp_path, off))) == 1


@pytest.mark.parametrize("body, message", [
    ("90;180;abc;0;0;1;1;\n", "line 2: centreX 'abc' is not a number"),
    ("90;180;0;0;0;1;1;\n95;0;0;0;0;1;1;\n", "line 3: dip must be in"),
    ("90;180;0;0\n", "line 2: no value for centreZ"),
    ("90;400;0;0;0;1;1;\n", "line 2: dipDir must be in"),
    ("90;180;0;0;0;-1;1;\n", "line 2: traceX must be > 0"),
])
def test_malformed_joint_lines_are_named(tmp_path, body, message):
    with pytest.raises(JointFileError, match=f"joints.csv {message}"):
        joints(tmp_path, body)


def test_missing_column_is_named(tmp_path):
    path = tmp_path / "j.csv"
    path.write_text("dip;centreX;centreY;centreZ\n90;0;0;0\n")
    with pytest.raises(JointFileError, match="line 1: the header lacks the column.s. dipDir"):
        readJoints(str(path))


def test_generated_blocks_settle_on_a_floor_under_their_weight(tmp_path):
    blocks = generateBlocks(PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.02), joints(tmp_path, THREE))
    S = Scene()
    m = S.materials.append(FrictMat(density=1000, frictionAngle=0.6))
    S.bodies.append(wall(-0.5, axis=2, sense=1, material=m))
    S.bodies.append([potentialBlock(b, material=m) for b in blocks])
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PB_PB_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=1e8, Kshear=1e7, viscousDamping=0.5)],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3)]
    S.dt = 2e-4
    S.run(2000, True)
    floor = sum(c["force"][2] for c in S._cpp.contacts() if c["id1"] == 0)
    assert floor == pytest.approx(1000 * 9.81, rel=1e-4)
    assert np.all(np.isfinite(S._cpp.pos()))
