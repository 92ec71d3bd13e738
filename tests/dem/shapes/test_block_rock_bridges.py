"""Non-persistent joints (Yade's BlockGen): the cut goes through, the rock bridge is a bond.

A cube of side 1 m is cut by a horizontal joint whose trace covers half of its section; the
lower piece is fixed and gravity is turned by theta about y. The upper piece (weight W) holds if
the bridge's cohesion c over its area A_B plus friction carries the driving force:
W sin(theta) <= c A_B + W cos(theta) tan(phi), the strength of Jennings' non-persistent joint.
"""
import math

import numpy as np
import pytest

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_KnKsPBPhys, JointFileError, Law2_SCG_KnKsPBPhys_KnKsPBLaw,
                       NewtonIntegrator, PotentialBlock, PotentialBlock2AABB, Scene, blockShape,
                       generateBlocks, potentialBlock, readJoints)
from talus.dem.files import io

pytestmark = pytest.mark.skipif(not _dem.have_potential_blocks, reason="built without CLP")

HEADER = "dip;dipDir;centreX;centreY;centreZ;traceX;traceY;phi_b;phi_r;JRC;JSC;asperity;simgaC;cohesion;tension; jointType;\n"
# Horizontal joint (dip 0: strike along x, dip line along y), centred on the cube's left face,
# half-length 0.5 m along x: it covers x in [-0.5, 0], half of the section; the rest is bridge.
HALF = "0;0;-0.5;0;0;0.5;10;40;40;0;0;0;0;1e5;2e4;2;joint;\n"
RHO, PHI, THETA, G = 1000.0, math.radians(20), math.radians(40), 9.81
W = RHO * G * 0.5                                   # the upper half
BRIDGE = 0.5                                        # m^2, the section the joint does not cover
C_CRITICAL = W * (math.sin(THETA) - math.cos(THETA) * math.tan(PHI)) / BRIDGE   # 3571 Pa


def joints(tmp_path, body):
    path = tmp_path / "joints.csv"
    path.write_text(HEADER + body)
    return readJoints(str(path))


def test_a_non_persistent_joint_cuts_through_and_marks_the_bridge(tmp_path):
    cube = PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.01)
    j = joints(tmp_path, HALF)
    assert (j[0].cohesion, j[0].tension, j[0].jointType) == (1e5, 2e4, 2)
    blocks = generateBlocks(cube, j, rockCohesion=3000.0, rockTension=500.0)
    assert len(blocks) == 2
    for b in blocks:
        cut = [k for k in range(len(b.d)) if abs(b.c[k]) == 1 and abs(b.d[k] + b.r) < 1e-9]   # the plane z = 0
        assert len(cut) == 1
        k = cut[0]
        # Half joint (its own strength counts only with intactRockDegradation), half bridge.
        assert b.cohesion[k] == pytest.approx(0.5 * 3000.0, rel=1e-12)
        assert b.tension[k] == pytest.approx(0.5 * 500.0, rel=1e-12)
        assert b.intactRock[k] and b.jointType[k] == 2
        others = [i for i in range(len(b.d)) if i != k]
        assert not any(b.intactRock[i] for i in others) and not any(b.cohesion[i] for i in others)
    degraded = generateBlocks(cube, j, rockCohesion=3000.0, intactRockDegradation=True)
    assert max(degraded[0].cohesion) == pytest.approx(0.5 * 1e5 + 0.5 * 3000.0, rel=1e-12)
    # A trace that ends before the block leaves it whole.
    assert len(generateBlocks(cube, joints(tmp_path, "0;0;-2;0;0;0.5;10;\n"))) == 1
    # The properties reach the body and come back from it.
    S = Scene()
    m = S.materials.append(FrictMat(density=RHO))
    ids = S.bodies.append([potentialBlock(b, material=m) for b in blocks])
    shape = blockShape(S, ids[0])
    assert sorted(shape["cohesion"]) == [0.0] * 5 + [1500.0] and sum(shape["intactRock"]) == 1


def bridged_scene(tmp_path, rockCohesion, rockTension=0.0, gravity=(G * math.sin(THETA), 0, -G * math.cos(THETA)),
                  overlap=0.0, blockedDOFs="", viscous=0.0):
    """The cube cut by HALF, lower piece fixed, the cut bonded at the first steps; gravity turned
    by THETA (or `gravity`), ramped up over 0.2 s with Cundall damping (a sudden load would
    overshoot the static one twice), then undamped. `overlap`: the upper piece starts that much
    into the lower one, the law's initialOverlapDistance (so the bond can pull); `blockedDOFs`:
    the upper piece's; `viscous`: the Ip2's viscousDamping.
    Returns the scene and the upper piece's id."""
    blocks = generateBlocks(PotentialBlock.cuboid((0.5, 0.5, 0.5), r=0.01), joints(tmp_path, HALF),
                            rockCohesion=rockCohesion, rockTension=rockTension)
    S = Scene()
    m = S.materials.append(FrictMat(density=RHO, frictionAngle=PHI))
    low, up = sorted(blocks, key=lambda b: sum(b.c[k] * b.d[k] for k in range(len(b.d))))
    lower = S.bodies.append(potentialBlock(low, material=m, fixed=True))
    upper = S.bodies.append(potentialBlock(up, material=m))
    assert S.bodies[upper].state.pos[2] > S.bodies[lower].state.pos[2]
    S.bodies[upper].state.pos = S.bodies[upper].state.pos - np.array([0, 0, overlap])
    S.bodies[upper].state.blockedDOFs = blockedDOFs
    ip2 = Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=1e9, Kshear=1e8, useFaceProperties=True, cohesionBroken=False,
                                           tensionBroken=False, viscousDamping=viscous)
    S.engines = [ForceResetter(), InsertionSortCollider([PotentialBlock2AABB()], verletDist=0.01),
                 InteractionLoop([Ig2_PB_PB_ScGeom()], [ip2],
                                 [Law2_SCG_KnKsPBPhys_KnKsPBLaw(allowBreakage=True, initialOverlapDistance=overlap)]),
                 NewtonIntegrator(gravity=(0, 0, 0), damping=0.3)]
    S.dt = 1e-4
    newton = S.engines[-1]
    for k in range(1, 21):
        newton.gravity = tuple(k / 20 * g for g in gravity)
        S.run(100, True)
        ip2.cohesionBroken = ip2.tensionBroken = True   # the cut is bonded; later contacts are frictional
    newton.damping = 0.0
    return S, upper


def test_the_bridge_holds_below_its_strength(tmp_path):
    S, upper = bridged_scene(tmp_path, 1.3 * C_CRITICAL)
    x0 = S.bodies[upper].state.pos[0]
    S.run(3000, True)
    assert abs(S.bodies[upper].state.pos[0] - x0) < 1e-4        # elastic shear only (4e-5 m)
    assert np.linalg.norm(S.bodies[upper].state.vel) < 0.05


def test_the_bridge_breaks_above_its_strength_then_the_block_slides_by_friction(tmp_path):
    S, upper = bridged_scene(tmp_path, 0.7 * C_CRITICAL)
    S.run(1000, True)              # the bridge fails at once; 0.1 s of sliding
    t0, v0 = S.time, S.bodies[upper].state.vel[0]
    S.run(2000, True)
    a = (S.bodies[upper].state.vel[0] - v0) / (S.time - t0)
    expected = G * (math.sin(THETA) - math.cos(THETA) * math.tan(PHI))
    assert v0 > 0.1
    assert a == pytest.approx(expected, rel=0.01)


@pytest.mark.parametrize("factor, viscous", [(1.3, 0.0), (1.3, 0.2), (0.7, 0.0)])
def test_the_bridge_pulls_until_its_tensile_strength(tmp_path, factor, viscous):
    """Gravity turned upwards pulls the upper piece off: the bridge (tension t over A_B, the
    pieces overlapping by initialOverlapDistance 1e-5 m, more than the stretch W / (Knormal A)
    = 4.9e-6 m) holds it at 1.3 t* = 1.3 W / A_B, lets it go at 0.7 t*. (Its cohesion keeps a
    shear strength under the pull: with none, Mohr-Coulomb under tension has none, and the
    rounding's shear breaks the bond.) The piece may not turn: one contact point pulling has no
    rotational stiffness (pressed, the overlap region shifts to resist a tilt; pulled, it shrinks
    on the side that lifts), so a free piece peels off at 0.5 of the load (docs/blocks.md).
    With viscous damping, the dashpot must not cancel the pull."""
    S, upper = bridged_scene(tmp_path, 1e5, rockTension=factor * W / BRIDGE, gravity=(0, 0, G), overlap=1e-5,
                             blockedDOFs="XYZ", viscous=viscous)
    z0 = S.bodies[upper].state.pos[2]
    S.run(1000, True)
    if factor > 1:
        assert abs(S.bodies[upper].state.pos[2] - z0) < 1e-5
        assert S._cpp.contacts()[0]["normalForce"][2] == pytest.approx(-W, rel=1e-2)   # pulls (undamped: 0.4 %)
    else:
        assert not S._cpp.contacts() and S.bodies[upper].state.vel[2] > 0.5   # broke, flies off


@pytest.mark.parametrize("body, message", [
    ("0;0;0;0;0;1;1;40;40;0;0;0;0;lots;0;1;\n", "line 2: cohesion 'lots' is not a number"),
    ("0;0;0;0;0;1;1;40;40;0;0;0;0;0;-5;1;\n", "line 2: tension must be >= 0"),
    ("0;0;0;0;0;1;1;40;40;0;0;0;0;0;0;1;\n0;0;0;0;0;1;1;40;40;0;0;0;0;0;0;1.5;\n", "line 3: jointType must be an integer"),
])
def test_malformed_strength_columns_are_named(tmp_path, body, message):
    with pytest.raises(JointFileError, match=f"joints.csv {message}"):
        joints(tmp_path, body)


def test_bonds_and_face_strengths_survive_a_checkpoint(tmp_path):
    """Saved while the bridge holds, reloaded: the faces' strengths, the bond (its strengths and
    state) and the Ip2's bond settings come back, and the run continues bit-identically."""
    if not io.available():
        pytest.skip("built without HDF5")
    A, upper = bridged_scene(tmp_path, 1.3 * C_CRITICAL)
    path = tmp_path / "bridge.h5"
    io.save(A, path)
    A.run(300, True)
    B = Scene()
    io.load(B, path)
    assert blockShape(B, upper)["cohesion"] == blockShape(A, upper)["cohesion"]
    assert B.engines[2].physFunctors[0].cohesionBroken   # new contacts stay frictional
    B.run(300, True)
    for a, b in zip(_dem.contact_extra(A._cpp), _dem.contact_extra(B._cpp), strict=True):
        assert a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)
    assert np.array_equal(B._cpp.pos(), A._cpp.pos()) and _dem.contact_extra(B._cpp)[0]["intactRock"]
