"""Checkpoints of scenes with Potential Blocks and Potential Particles: the shapes (planes and
their derived geometry) and the contacts (normal, overlap, shear force history, warm-start
point) come back, so a reloaded scene continues bit-identically; damaged shape data is refused
with a CheckpointError naming the file and the shape."""
import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from flipped_bytes import load_flipped_copies

from talus import _dem
from talus.dem import (ForceResetter, FrictMat, Ig2_PB_PB_ScGeom, Ig2_PP_PP_ScGeom, InsertionSortCollider,
                       InteractionLoop, Ip2_FrictMat_FrictMat_KnKsPBPhys, Ip2_FrictMat_FrictMat_KnKsPhys,
                       Law2_SCG_KnKsPBPhys_KnKsPBLaw, Law2_SCG_KnKsPhys_KnKsLaw, NewtonIntegrator,
                       PotentialBlock, PotentialBlock2AABB, PotentialParticle, PotentialParticle2AABB, Scene,
                       blockShape, particleShape, potentialBlock, potentialParticle, wall)
from talus.dem.files import io

pytestmark = pytest.mark.skipif(not io.available(), reason="built without HDF5")
HALF = 0.25


def pile(kind: str, n: int = 5, turned: bool = True, **geometry) -> Scene:
    """n cubes of half-size 0.25 m, randomly turned (or not), dropped into a box of five walls
    under a gravity tilted 15 degrees about y (so that the contacts slide and build a shear force
    history). `geometry`: settings of Ig2_PB_PB_ScGeom."""
    S = Scene()
    m = S.materials.append(FrictMat(density=2000, frictionAngle=math.radians(25)))
    S.bodies.append([wall(0, axis=2, sense=1, material=m), wall(-1, axis=0, sense=1, material=m),
                     wall(1, axis=0, sense=-1, material=m), wall(-1, axis=1, sense=1, material=m),
                     wall(1, axis=1, sense=-1, material=m)])
    rng = np.random.default_rng(3)
    # four side by side, the others above them, all apart (0.9 m > twice the bounding radius)
    places = [(-0.45, -0.45, 0.5), (0.45, -0.45, 0.5), (-0.45, 0.45, 0.5), (0.45, 0.45, 0.5), (0.1, 0.05, 1.4)]
    for k in range(n):
        q = rng.normal(size=4) if turned else np.array([1.0, 0, 0, 0])
        pos = places[k]
        if kind == "blocks":
            shape = PotentialBlock.cuboid((HALF, HALF, HALF), r=0.01)
            S.bodies.append(potentialBlock(shape, pos=pos, orientation=q / np.linalg.norm(q), material=m))
        else:
            shape = PotentialParticle.cuboid((HALF, HALF, HALF), r=0.02, k=0.1)
            S.bodies.append(potentialParticle(shape, pos=pos, orientation=q / np.linalg.norm(q), material=m))
    if kind == "blocks":
        functors = ([PotentialBlock2AABB()], [Ig2_PB_PB_ScGeom(**geometry)],
                    [Ip2_FrictMat_FrictMat_KnKsPBPhys(Knormal=1e8, Kshear=1e7, kn_i=1e8, ks_i=1e7, viscousDamping=0.2)],
                    [Law2_SCG_KnKsPBPhys_KnKsPBLaw()])
    else:
        functors = ([PotentialParticle2AABB()], [Ig2_PP_PP_ScGeom()],
                    [Ip2_FrictMat_FrictMat_KnKsPhys(Knormal=1e8, Kshear=1e7, viscousDamping=0.2)],
                    [Law2_SCG_KnKsPhys_KnKsLaw()])
    tilt = math.radians(15)
    S.engines = [ForceResetter(), InsertionSortCollider(functors[0], verletDist=0.01), InteractionLoop(*functors[1:]),
                 NewtonIntegrator(gravity=(9.81 * math.sin(tilt), 0, -9.81 * math.cos(tilt)), damping=0.3)]
    S.dt = 1e-4
    return S


def state(S: Scene) -> dict:
    """Everything a continuation depends on: body state, and every real contact's geometry,
    forces and contact area."""
    c = _dem.contact_arrays(S._cpp, True)
    ori = np.array([S._cpp.ori(i) for i in range(len(S.bodies))])
    return {"pos": S.positions().copy(), "vel": S.velocities().copy(), "angVel": S.angular_velocities().copy(),
            "force": S.forces().copy(), "ori": ori, "iter": S.iter, "areas": np.array(_dem.contact_areas(S._cpp)),
            **{f"contact.{k}": v for k, v in c.items()}}


def shapes(S: Scene) -> list:
    return [repr(blockShape(S, i)) if S._cpp.shapeKind(i) == "PotentialBlock" else repr(particleShape(S, i))
            for i in range(len(S.bodies)) if S._cpp.shapeKind(i) in ("PotentialBlock", "PotentialParticle")]


@pytest.mark.parametrize("kind", ["blocks", "particles"])
def test_restart_continues_bit_identically(tmp_path, kind):
    A = pile(kind)
    A.run(6000)                         # the cubes land on the floor and on each other
    assert A._cpp.realContactCount() >= 4, "the run should be contact-rich"
    shear = np.linalg.norm(_dem.contact_arrays(A._cpp, True)["shearForce"], axis=1)
    assert shear.max() > 1.0, "the contacts should carry a shear force history"
    path = tmp_path / f"{kind}.h5"
    io.save(A, path)
    A.saveTmp("half")
    A.run(400)
    reference = state(A)

    B = Scene()                         # a fresh process would start like this
    io.load(B, path)
    assert shapes(B) == shapes(A)
    B.run(400)
    for name, value in reference.items():
        assert np.array_equal(state(B)[name], value), f"{name} differs after the file round trip"

    A.loadTmp("half")                   # the in-memory slot writes the same layout
    A.run(400)
    for name, value in reference.items():
        assert np.array_equal(state(A)[name], value), f"{name} differs after the saveTmp round trip"


def test_block_contact_settings_come_from_the_engines(tmp_path):
    """2D mode and the exact depth are Ig2_PB_PB_ScGeom's: saved with the engines, restored with
    them, and reset by engines without them. (Cubes not turned: in 2D mode the blocks are prisms
    moving in the plane normal to twoDdir, whose joints are edges, not corners.)"""
    A = pile("blocks", n=5, turned=False, twoDimension=True, unitWidth2D=0.5, exactDepth=True)
    A.run(6000)
    assert A._cpp.realContactCount() >= 2
    path = tmp_path / "2d.h5"
    io.save(A, path)
    A.run(200)
    B = Scene()
    io.load(B, path)
    B.run(200)
    assert np.array_equal(state(B)["areas"], state(A)["areas"])
    assert B.engines[2].geomFunctors[0].twoDimension and B.engines[2].geomFunctors[0].exactDepth
    # engines without the settings reset them: the same step then gives other areas
    C = Scene()
    io.load(C, path, engines="current")
    C.engines = pile("blocks", n=0).engines
    C.run(200)
    assert not np.array_equal(state(C)["areas"], state(A)["areas"])


# ------------------------------------------------------------------------------------------------
# Damaged files.

def edited(tmp_path, source, script: str):
    """A copy of `source` changed by an h5py script (in another process: h5py's HDF5 is not the
    one Talus links)."""
    pytest.importorskip("h5py")
    target = tmp_path / "edited.h5"
    target.write_bytes(source.read_bytes())
    done = subprocess.run([sys.executable, "-c", "import sys, h5py, numpy as np\n"
                           "with h5py.File(sys.argv[1], 'r+') as f:\n" + textwrap.indent(textwrap.dedent(script), "    "),
                           str(target)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return target


@pytest.fixture(scope="module")
def saved_piles(tmp_path_factory):
    folder = tmp_path_factory.mktemp("piles")
    out = {}
    for kind in ("blocks", "particles"):
        S = pile(kind, n=2)
        S.run(5000)
        assert S._cpp.realContactCount() >= 2
        out[kind] = folder / f"{kind}.h5"
        io.save(S, out[kind])
    return out


@pytest.mark.parametrize("kind, script, message", [
    ("blocks", "v = f['bodies/blocks/faceVertices']; v[v.shape[0] - 1] = 999", r"Potential Block shape 1 is invalid"),
    ("blocks", "s = f['bodies/blocks/verticesStart'][...]; s[1] = s[2] + 1; f['bodies/blocks/verticesStart'][...] = s",
     r"/bodies/blocks/verticesStart does not partition"),
    ("blocks", "del f['bodies/blocks/edgeDirections']", r"missing /bodies/blocks/edgeDirections"),
    ("blocks", "f['bodies/shapeIndex'][6] = 7", r"body 6 has an invalid shape index 7"),
    ("particles", "f['bodies/particles/k'][0] = 2.0", r"Potential Particle shape 0 is invalid"),
    ("particles", "f['bodies/particles/normals'][0] = (3.0, 0.0, 0.0)", r"Potential Particle shape 0 is invalid"),
    ("particles", "f['contacts/kind'][...] = 4", r"has a kind that does not match the shapes of its bodies"),
], ids=["face-vertex", "vertex-lists", "missing-edges", "shape-index", "particle-k", "particle-normal", "contact-kind"])
def test_damaged_shape_data_is_refused(tmp_path, saved_piles, kind, script, message):
    path = edited(tmp_path, saved_piles[kind], script)
    T = Scene()
    T.materials.append(FrictMat(label="mine"))
    with pytest.raises(io.CheckpointError, match=rf"checkpoint '.*edited.h5': .*{message}"):
        io.load(T, path)
    assert len(T.bodies) == 0 and T.materials[0].label == "mine"    # untouched


def test_flipped_bytes_never_load_wrong_blocks(tmp_path, saved_piles):
    """Flip bytes over a block checkpoint: each load fails with a CheckpointError naming the
    file, or (a byte nothing reads) restores exactly the saved shapes."""
    source = saved_piles["blocks"]
    S = Scene()
    io.load(S, source, engines="current")
    saved = shapes(S)

    def same_shapes(T):
        assert shapes(T) == saved

    def untouched(T):
        assert len(T.bodies) == 0

    refused, copies = load_flipped_copies(source, tmp_path / "bad.h5", 150, Scene, same_shapes, untouched)
    assert refused > 0.5 * copies
