"""Checkpoints (HDF5): a restart continues bit-identically, saveTmp/loadTmp slots, atomic writes
(a failed save leaves the old file as it was, no temporary file left), and damaged, missing or
foreign files give a CheckpointError naming the file, with the scene untouched."""
import json
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest
from flipped_bytes import load_flipped_copies

from talus import _dem
from talus.dem import (CohFrictMat, FrictMat, ForceResetter, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys,
                       Law2_ScGeom6D_CohFrictPhys_CohesionMoment, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Ip2_FrictMat_FrictMat_MindlinPhys,
                       Law2_ScGeom_MindlinPhys_Mindlin, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                       Law2_ScGeom_FrictPhys_CundallStrack, Law2_ScGeom_ViscElPhys_Basic, Matrix3,
                       NewtonIntegrator, PWaveTimeStep, PyRunner, Scene, TranslationEngine, ViscElMat, box,
                       facet, sphere, wall)
from talus.dem.files import io

pytestmark = pytest.mark.skipif(not io.available(), reason="built without HDF5")
TWINS = Path(__file__).parents[1] / "yade_twins" / "periodic"  # the packing the Yade twins read


def deposition(visco, m: int = 7) -> Scene:
    """m^3 spheres, nearly touching, settling in a box: walls on four sides, a floor of two
    facets (sphere-sphere, wall-sphere and facet-sphere contacts). `visco`: False (linear),
    True (visco-elastic) or "hertz" (Hertz-Mindlin with restitution 0.5, energy tracked)."""
    S = Scene()
    rng = np.random.default_rng(7)
    if visco == "cohfrict":
        S.materials.append(CohFrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, normalCohesion=2e3,
                                       shearCohesion=2e3, momentRotationLaw=True, etaRoll=0.1, label="clay"))
        law = ([Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionOnNewContacts=True)],
               [Law2_ScGeom6D_CohFrictPhys_CohesionMoment()])
    elif visco == "hertz":
        S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, label="sand"))
        law = ([Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)], [Law2_ScGeom_MindlinPhys_Mindlin()])
        S.trackEnergy = True
    elif visco:
        S.materials.append(ViscElMat(tc=2e-3, en=0.5, et=0.5, frictionAngle=0.5, density=2600, label="glass"))
        law = ([Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()])
    else:
        S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, label="sand"))
        law = ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])
    S.bodies.append([facet([(-0.1, -0.1, 0), (1.1, -0.1, 0), (1.1, 1.1, 0)]),
                     facet([(-0.1, -0.1, 0), (1.1, 1.1, 0), (-0.1, 1.1, 0)]),
                     wall(0, axis=0, sense=1), wall(1, axis=0, sense=-1), wall(0, axis=1, sense=1),
                     wall(1, axis=1, sense=-1)])
    grid = np.stack(np.meshgrid(np.arange(m), np.arange(m), np.arange(m), indexing="ij"), -1).reshape(-1, 3)
    centres = (grid + 0.5 + rng.uniform(-0.02, 0.02, grid.shape)) / m
    S.bodies.append([sphere(c, r) for c, r in zip(centres, rng.uniform(0.46, 0.5, len(grid)) / m)])
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *law),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3),
                 PyRunner(command="pass", iterPeriod=7, label="every7")]
    S.dt = 2e-4 if visco is True else 0.5 * PWaveTimeStep(S)
    return S


def state(S: Scene) -> dict:
    # Real contacts only: the candidate pairs within the collider's skin depend on when it last
    # re-detected (a loaded scene re-detects at its first step), and never touch the physics.
    c = _dem.contact_arrays(S._cpp, True)
    ori = np.array([S._cpp.ori(i) for i in range(len(S.bodies)) if S._cpp.alive()[i]])
    return {"pos": S.positions().copy(), "vel": S.velocities().copy(), "angVel": S.angular_velocities().copy(),
            "force": S.forces().copy(), "ori": ori, "iter": S.iter, "time": S.time,
            **{f"contact.{k}": v for k, v in c.items()}, "contact.extra": repr(_dem.contact_extra(S._cpp))}


def assert_identical(a: dict, b: dict):
    assert a.keys() == b.keys()
    for k in a:
        assert np.array_equal(a[k], b[k]), f"{k} differs"


def test_layout_is_covered():
    """Every field of these structures is written by dem/checkpoint/Checkpoint.cpp (Scene: all but its
    engines and the transient pauseRequested_, failedStep_, the sub-stepping state (subStep,
    subStepping, nextEngines, stepping_: how the steps are run, reset by loading) and stepLoop_:
    the step's scheduler, made at the first step (its plan, made again when the engines change,
    per-thread ranges, step count, skin check made ahead, forgotten at every run(), runs of
    boundary contacts, found again for every new contact list, energy sums per block and the
    time of the serial stages); and the contact list's
    version, renewed by the index built on loading), which change speed and diagnostics only).
    When one changes size, a field was added: store
    it there (save, load, validate; bump checkpointFormatVersion if the layout changes) unless it
    is transient, then update this table."""
    # Not stored: Bodies::blockContact and particleContact (Ig2_PB_PB_ScGeom's and
    # Ig2_PP_PP_ScGeom's settings, restored with the engines) and ContactExtra::contactArea
    # (recomputed by the geometry every step before the law reads it).
    assert _dem.layout_sizes() == {"Contact": 256, "Material": 216, "Bodies": 840, "WallShape": 8,
                                   "FacetShape": 104, "Cell": 296, "Scene": 1704, "ContactExtra": 288,
                                   "EnergyTracker": 144}


@pytest.mark.parametrize("visco", [False, True, "hertz", "cohfrict"], ids=["FrictMat", "ViscElMat", "Hertz", "CohFrict"])
def test_restart_continues_bit_identically(tmp_path, visco):
    A = deposition(visco)
    A.run(400 if visco is True else 200)    # settle into a contact-rich state
    path = tmp_path / "half.h5"
    io.save(A, path)                # N/2 steps ...
    A.run(200)
    reference = state(A)
    assert A._cpp.realContactCount() > 100, "the run should be contact-rich"

    B = Scene()                     # a fresh process would start like this
    io.load(B, path)
    assert [type(e) for e in B.engines] == [type(e) for e in A.engines]
    B.run(200)                      # ... and N/2 more after loading
    assert_identical(state(B), reference)
    assert B.trackEnergy == (visco == "hertz")
    if visco == "cohfrict":         # bonds and moments were part of the state
        x = _dem.contact_extra(B._cpp)
        assert sum(not e["cohesionBroken"] for e in x) > 100
        assert max(np.linalg.norm(e["moment_bending"]) for e in x) > 0
    assert list(B.energy.values()) == list(A.energy.values())
    assert B.engines[-1].nDone == A.engines[-1].nDone   # the PyRunner kept its rhythm


def test_restart_with_clumps_boxes_and_kinematics(tmp_path):
    """Clumps (aspherical rotation: the angular momentum must come back), a dynamic box and a
    fixed box pushed down by a TranslationEngine into a settling packing."""
    A = deposition(False, m=5)
    A.bodies.append(box((0.5, 0.5, 1.3), (0.3, 0.3, 0.05), fixed=True, label="lid"))
    lid = len(A.bodies) - 1
    A.bodies.append(box((0.2, 0.3, 1.1), (0.04, 0.05, 0.06), orientation=(0.9, 0.1, 0.2, 0.3)))
    for k, x in enumerate((0.3, 0.7)):
        A.bodies.appendClumped([sphere((x, 0.5, 1.1), 0.05), sphere((x + 0.07, 0.5, 1.13), 0.04),
                                sphere((x, 0.57, 1.15), 0.03)])
    engines = A.engines
    A.engines = [*engines[:3], TranslationEngine(translationAxis=(0, 0, -1), velocity=0.3, ids=[lid]), *engines[3:]]
    A.run(600)
    io.save(A, tmp_path / "c.h5")
    kinds = set()
    for _ in range(6):            # the box rocks on the spheres: touching them on and off
        A.run(50)
        kinds |= set(_dem.contact_arrays(A._cpp, True)["kind"])
    reference = state(A)
    assert 3 in kinds, "the box should touch spheres after the restart point"
    B = Scene()
    io.load(B, tmp_path / "c.h5")
    assert B.engines[3].ids == [lid] and B.engines[3].velocity == 0.3
    B.run(300)
    assert_identical(state(B), reference)


def test_periodic_restart_continues_bit_identically(tmp_path):
    data = json.loads((TWINS / "periodic_packing.json").read_text())
    A = Scene()
    A.periodic = True
    A.cell.hSize = Matrix3(*[x for row in data["hSize"] for x in row])
    A.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
    A.bodies.append([sphere(tuple(c), r) for c, r in zip(data["pos"], data["radius"])])
    A.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.2)]
    A.cell.velGrad = Matrix3(0, 0.5, 0, 0, 0, 0, 0, 0, -0.2)
    A.dt = 0.3 * PWaveTimeStep(A)
    A.run(150)
    io.save(A, tmp_path / "p.h5")
    h_saved = A.cell.hSize
    A.run(150)
    assert A._cpp.realContactCount() > 40 and not np.array_equal(A.cell.hSize, h_saved)
    B = Scene()
    io.load(B, tmp_path / "p.h5")
    assert B.periodic and np.array_equal(B.cell.hSize, h_saved)
    B.run(150)
    assert_identical(state(B), state(A))
    for name in ("hSize", "trsf", "velGrad", "prevVelGrad"):
        assert np.array_equal(np.array(getattr(B._cpp.cell, name)), np.array(getattr(A._cpp.cell, name))), name


def test_save_tmp_and_load_tmp(tmp_path):
    S = deposition(False, m=5)
    S.run(200)
    io.saveTmp(S)
    io.saveTmp(S, "init")
    saved = state(S)
    view = S.positions()                  # a view handed out before: must stay valid
    material = S.materials[0]
    S.run(300)
    after = state(S)
    io.loadTmp(S, "init")
    assert S.iter == saved["iter"] and S.time == saved["time"]
    assert_identical(state(S), saved)
    assert np.array_equal(view, saved["pos"])
    assert S.materials[0] is material and material.label == "sand"
    material.frictionAngle = 0.3          # still edits the scene's material
    assert S._cpp.material(0).frictionAngle == 0.3
    material.frictionAngle = 0.5
    S.run(300)
    assert_identical(state(S), after)     # the same 300 steps again
    # Keeping the engines (and the collider's state from later on) gives the same steps too.
    collider = S.engines[1]
    io.loadTmp(S, "init", engines="current")
    assert S.engines[1] is collider
    S.run(300)
    assert_identical(state(S), after)
    assert sorted(io.lsTmp(S)) == ["", "init"]
    with pytest.raises(io.CheckpointError, match=r"no slot 'nope' .*slots: '', 'init'"):
        io.loadTmp(S, "nope")


def test_load_restores_materials_engines_and_labels(tmp_path):
    S = deposition(True, m=3)
    S.engines[1].verletDist = -0.3
    S.engines[1].label = "collider"
    S.engines[4].dead = True
    S.run(20)
    io.save(S, tmp_path / "s.h5")
    T = Scene()
    T.materials.append(FrictMat(label="other"))
    T.materials.append(FrictMat(label="other2"))
    T.bodies.append(sphere((0, 0, 0), 1.0))
    io.load(T, tmp_path / "s.h5")
    assert len(T.materials) == 1 and isinstance(T.materials[0], ViscElMat)
    assert T.materials[0].label == "glass" and T.materials[0].tc == 2e-3
    assert np.isnan(T.materials[0].kn)
    assert len(T.bodies) == len(S.bodies) and T.iter == 20 and T.dt == S.dt
    assert T.engines[1].verletDist == -0.3 and T.engines[1].label == "collider"
    assert T.engines[3].gravity == (0, 0, -9.81) and T.engines[3].damping == 0.3
    assert T.engines[4].command == "pass" and T.engines[4].iterPeriod == 7 and T.engines[4].dead
    assert [type(f).__name__ for f in T.engines[2].lawFunctors] == ["Law2_ScGeom_ViscElPhys_Basic"]


def test_callable_command_warns_and_load_keeps_current_engines(tmp_path):
    S = deposition(False, m=2)
    S.engines = [*S.engines, PyRunner(command=lambda: None, label="cb")]
    with pytest.warns(io.CheckpointWarning, match="PyRunner 'cb': a Python callable cannot be written"):
        io.save(S, tmp_path / "c.h5")
    T = deposition(False, m=2)
    current = T.engines
    with pytest.warns(io.CheckpointWarning, match="keeps its current engines"):
        io.load(T, tmp_path / "c.h5")
    assert T.engines == current
    with pytest.raises(io.CheckpointError, match="saved engines cannot be rebuilt"):
        io.load(T, tmp_path / "c.h5", engines="saved")
    # In memory the callable is kept: loadTmp rebuilds all engines.
    io.saveTmp(S)
    io.loadTmp(S)
    assert S.engines[-1].label == "cb" and callable(S.engines[-1].command)


def test_empty_scene_round_trip(tmp_path):
    S = Scene()
    S.dt = 1e-3
    io.save(S, tmp_path / "e.h5")
    T = deposition(False, m=2)
    io.load(T, tmp_path / "e.h5", engines="current")
    assert len(T.bodies) == 0 and len(T.materials) == 0 and T.dt == 1e-3 and T.iter == 0
    T.run(3)   # the old engines run on the empty scene


# ------------------------------------------------------------------------------------------------
# Atomic writes.

def leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if ".tmp-" in p.name]


FULL_DISK = """
import resource, signal, sys
import numpy as np
from talus.dem import Scene, sphere
from talus.dem.files import io
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)       # writes past the limit fail with EFBIG
S = Scene()
S.bodies.append([sphere((i, 0, 0), 0.4) for i in range(2000)])
resource.setrlimit(resource.RLIMIT_FSIZE, (16384, 16384))
try:
    io.save(S, sys.argv[1])
except io.CheckpointError as e:
    print("ERROR", e)
"""


def test_failed_write_leaves_the_previous_checkpoint(tmp_path, build_dir):
    path = tmp_path / "run.h5"
    S = deposition(False, m=3)
    S.run(10)
    io.save(S, path)
    before = path.read_bytes()
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    done = subprocess.run([sys.executable, "-c", FULL_DISK, str(path)], capture_output=True, text=True, env=env,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith(f"ERROR checkpoint '{path}': cannot "), done.stdout
    assert path.read_bytes() == before
    assert leftovers(tmp_path) == []
    T = Scene()
    io.load(T, path)                      # and it still loads
    assert T.iter == 10


def dead_pid() -> int:
    """The id of a process that has ended (reaped: no process has it, unless reused since)."""
    done = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    return int(done.stdout)


@pytest.mark.parametrize("action", ["save", "load"])
def test_stale_temporary_files_of_dead_writers_are_removed(tmp_path, action):
    """Saves killed mid-write leave `.<name>.tmp-<pid>-<n>[@<host>]`: the next save or load in
    the folder removes those of dead processes of this host, and nothing else."""
    import socket
    path = tmp_path / "ck.h5"
    S = deposition(False, m=2)
    io.save(S, path)
    live = subprocess.Popen(["sleep", "60"])      # a writer still writing
    try:
        gone, host = dead_pid(), socket.gethostname()
        stale = [f".ck.h5.tmp-{gone}-0", f".ck.h5.tmp-{gone}-3@{host}", f".other.h5.tmp-{gone}-1@{host}"]
        kept = [f".ck.h5.tmp-{live.pid}-0@{host}", f".ck.h5.tmp-{os.getpid()}-7@{host}",
                f".ck.h5.tmp-{gone}-0@another-host",      # a folder shared with another machine
                f"ck.h5.tmp-{gone}-0", f".ck.h5.tmp-{gone}", f".ck.h5.tmp-x{gone}-0", "notes.txt"]
        for name in stale + kept:
            (tmp_path / name).write_bytes(b"\0" * 1000)
        if action == "save":
            io.save(S, path)
        else:
            io.load(Scene(), path)
        assert sorted(p.name for p in tmp_path.iterdir()) == sorted(kept + ["ck.h5"])
    finally:
        live.kill()
        live.wait()


def test_bad_targets_are_refused(tmp_path):
    S = deposition(False, m=2)
    with pytest.raises(io.CheckpointError, match=r"checkpoint '.*/missing/x.h5': cannot write: the folder .* does not exist"):
        io.save(S, tmp_path / "missing" / "x.h5")
    (tmp_path / "dir.h5").mkdir()
    with pytest.raises(io.CheckpointError, match="dir.h5': cannot write: it is a folder"):
        io.save(S, tmp_path / "dir.h5")
    assert leftovers(tmp_path) == []


def test_save_replaces_the_previous_checkpoint(tmp_path):
    S = deposition(False, m=2)
    io.save(S, tmp_path / "x.h5")
    S.run(5)
    io.save(S, tmp_path / "x.h5")
    T = Scene()
    io.load(T, tmp_path / "x.h5")
    assert T.iter == 5 and leftovers(tmp_path) == []


# ------------------------------------------------------------------------------------------------
# Bad files: a clear error naming the file, the scene untouched.

@pytest.fixture(scope="module")
def small_checkpoint(tmp_path_factory):
    S = deposition(False, m=2)
    S.run(300)
    assert S._cpp.realContactCount() > 0
    path = tmp_path_factory.mktemp("ck") / "small.h5"
    io.save(S, path)
    # Only the real contacts are stored: the candidate pairs inside the skin are found again.
    assert S._cpp.contactCount() > S._cpp.realContactCount()
    return path, state(S), S._cpp.realContactCount()


def untouched_scene():
    T = Scene()
    T.materials.append(FrictMat(label="mine"))
    T.bodies.append(sphere((0, 0, 0), 0.5))
    return T


def check_untouched(T):
    assert len(T.bodies) == 1 and T.materials[0].label == "mine" and T.iter == 0


def test_missing_file(tmp_path):
    T = untouched_scene()
    with pytest.raises(io.CheckpointError, match=r"checkpoint '.*nothing.h5': no such file"):
        io.load(T, tmp_path / "nothing.h5")
    check_untouched(T)


def test_not_hdf5(tmp_path):
    (tmp_path / "text.h5").write_text("hello\n" * 100)
    T = untouched_scene()
    with pytest.raises(io.CheckpointError, match=r"text.h5': not an HDF5 file"):
        io.load(T, tmp_path / "text.h5")
    check_untouched(T)


@pytest.mark.parametrize("fraction", [0.0, 0.01, 0.3, 0.6, 0.95, 0.9999])
def test_truncated_file(tmp_path, small_checkpoint, fraction):
    data = small_checkpoint[0].read_bytes()
    path = tmp_path / "cut.h5"
    path.write_bytes(data[: int(len(data) * fraction)])
    T = untouched_scene()
    with pytest.raises(io.CheckpointError, match=r"checkpoint '.*cut.h5': "):
        io.load(T, path)
    check_untouched(T)


def test_corrupted_bytes_never_load_wrong_state(tmp_path, small_checkpoint):
    """Flip bytes all over the file: each load either fails with a CheckpointError naming the
    file, or (a byte nothing reads) gives exactly the saved state."""
    source, saved, _ = small_checkpoint
    t0 = time.monotonic()
    failures, copies = load_flipped_copies(source, tmp_path / "bad.h5", 600, untouched_scene,
                                           lambda T: assert_identical(state(T), saved), check_untouched)
    assert failures > 0.5 * copies
    print(f"\n{copies} damaged files, {failures} refused, in {time.monotonic() - t0:.1f} s")


def with_h5py(script: str, *args):
    """Run an h5py script in another process (h5py's HDF5 is not the one Talus links)."""
    pytest.importorskip("h5py")
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(script), *map(str, args)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_wrong_version_and_foreign_files(tmp_path, small_checkpoint):
    source, saved, pairs = small_checkpoint
    newer, foreign = tmp_path / "newer.h5", tmp_path / "foreign.h5"
    newer.write_bytes(source.read_bytes())
    out = with_h5py("""
        import sys, h5py, numpy as np
        with h5py.File(sys.argv[1], "r") as f:   # a standard HDF5 file, readable by other tools
            print(f.attrs["magic"].decode(), f.attrs["format_version"], f["bodies/pos"].shape, f["contacts/id1"].shape)
        with h5py.File(sys.argv[1], "r+") as f:
            f.attrs["format_version"] = 99
        with h5py.File(sys.argv[2], "w") as f:
            f["data"] = np.arange(10)
        """, newer, foreign)
    version = _dem.checkpoint_format_version()
    assert out.split() == ["talus-checkpoint", str(version), f"({len(saved['pos'])},", "3)", f"({pairs},)"]
    T = untouched_scene()
    with pytest.raises(io.CheckpointError, match=rf"newer.h5': checkpoint format version 99 .*reads versions 7 to {version}"):
        io.load(T, newer)
    with pytest.raises(io.CheckpointError, match=r"foreign.h5': not a Talus checkpoint"):
        io.load(T, foreign)
    check_untouched(T)


def test_version_7_files_still_load(tmp_path, small_checkpoint):
    """Version 7 stored every candidate pair in the same layout; its files load as before."""
    source, saved, _ = small_checkpoint
    older = tmp_path / "older.h5"
    older.write_bytes(source.read_bytes())
    with_h5py("""
        import sys, h5py
        with h5py.File(sys.argv[1], "r+") as f:
            f.attrs["format_version"] = 7
        """, older)
    T = Scene()
    io.load(T, older)
    assert_identical(state(T), saved)


def test_size_and_speed_of_a_1000_sphere_checkpoint(tmp_path):
    S = deposition(False, m=10)         # 1000 spheres
    S.run(300)
    path = tmp_path / "k.h5"
    t0 = time.perf_counter()
    io.save(S, path)
    t_save = time.perf_counter() - t0
    T = Scene()
    t0 = time.perf_counter()
    io.load(T, path)
    t_load = time.perf_counter() - t0
    size = path.stat().st_size
    print(f"\n1000 spheres, {S._cpp.contactCount()} contact pairs: {size / 1e3:.0f} kB, "
          f"save {t_save * 1e3:.1f} ms, load {t_load * 1e3:.1f} ms")
    assert size < 2_000_000 and t_save < 2 and t_load < 2


def test_scene_methods(tmp_path):
    """Scene has O.save/O.load/O.saveTmp/O.loadTmp/O.reload/O.lsTmp (from io.CheckpointMethods)."""
    assert issubclass(Scene, io.CheckpointMethods)
    S = Scene()
    S.bodies.append(sphere((0, 0, 1), 0.1))
    S.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -10))]
    S.dt = 1e-3
    S.save(tmp_path / "m.h5")
    S.saveTmp("a")
    S.run(10)
    S.reload()
    assert S.iter == 0
    S.run(10)
    S.loadTmp("a")
    assert S.iter == 0 and S.lsTmp() == ["a"]
    S.run(3)
    S.load(tmp_path / "m.h5", engines="current")
    assert S.iter == 0


def test_class_paths_written_before_the_sub_packages_still_load():
    # Checkpoints of earlier versions name the engines' module flat: talus.dem.engines.
    from talus.dem.files import io
    from talus.dem.step.engines import ForceResetter
    assert io._import_class("talus.dem.engines:ForceResetter") is ForceResetter
    # and modules that moved between sub-packages since (the value types left core for base)
    from talus.dem.base.linalg import Vector3
    assert io._import_class("talus.dem.core.linalg:Vector3") is Vector3
    with pytest.raises(ModuleNotFoundError):
        io._import_class("talus.dem.no_such_module:Thing")
