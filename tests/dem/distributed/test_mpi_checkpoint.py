"""O.save / O.load of a script under `mpirun -np N talus run`: one file written by every
process, in the serial checkpoint's layout (the file written at 4 processes holds the serial
run's datasets), read at any process count; the run continued from it is the uninterrupted
run's bit for bit at 4, 2 and 1 processes, and from a serial file at 2. Bad files are refused on
every process with one message, and a save that fails leaves the previous file as it was."""
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import talus_run as run_script

SCENE = Path(__file__).resolve().parents[3] / "cases" / "scenes" / "mpi_checkpoint.py"

try:
    from talus import _distributed_checkpoint  # noqa: F401  (mpi_dem with parallel HDF5 only)
except ImportError:
    _distributed_checkpoint = None
pytestmark = pytest.mark.skipif(_distributed_checkpoint is None or shutil.which("mpirun") is None,
                                reason="the mpi_dem feature or parallel HDF5 is off, or mpirun is missing")
SPHERES, STEPS = 400, 1000


def talus_run(*args, processes=None):
    return run_script(*args, processes=processes, timeout=120)      # a checkpoint's processes take longer


def scene(mode, checkpoint, output, processes=None, law="linear", *flags):
    done = talus_run(SCENE, mode, SPHERES, STEPS, checkpoint, output, law, *flags, processes=processes)
    assert done.returncode == 0, done.stdout + done.stderr
    return json.loads(Path(output).read_text())


def datasets(path):
    """Every dataset of an HDF5 file by name (h5py), and the clock's time and step."""
    h5py = pytest.importorskip("h5py")
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, item: out.__setitem__(name, item[()]) if isinstance(item, h5py.Dataset) else None)
        out["clock"] = (f["clock"].attrs["time"], f["clock"].attrs["iter"])
    return out


@pytest.mark.parametrize("law", ["linear", "hertz"])
def test_written_at_four_processes_continued_at_four_two_and_one_bit_for_bit(tmp_path, law):
    saved = scene("save", tmp_path / "run.h5", tmp_path / "saved.json", processes=4, law=law)
    uninterrupted = np.asarray(saved["positions"])
    assert saved["iter"] == 2 * STEPS and len(uninterrupted) == SPHERES + 5
    for processes in (4, 2, None):
        restarted = scene("load", tmp_path / "run.h5", tmp_path / f"load-{processes}.json", processes=processes)
        assert restarted["iter"] == 2 * STEPS
        assert np.array_equal(np.asarray(restarted["positions"]), uninterrupted), processes
    # The file is the one a run in one process writes: the same bodies, the contacts once each
    # in (id1, id2) order with their state; a wall's force is summed over the processes, in
    # another order than its contacts' in one process.
    serial = scene("save", tmp_path / "serial.h5", tmp_path / "serial.json", law=law)
    assert np.array_equal(np.asarray(serial["positions"]), uninterrupted)
    assert_the_serial_file(tmp_path / "run.h5", tmp_path / "serial.h5")


def assert_the_serial_file(path, serial, contacts=SPHERES // 4):
    """The file at `path` holds the datasets of the one at `serial` (written in one process),
    with more than `contacts` contacts, the walls' forces within round-off (the last five bodies)."""
    mine, theirs = datasets(path), datasets(serial)
    compared = [name for name in theirs if name.startswith(("bodies/", "contacts/")) or name == "clock"]
    assert sorted(mine) == sorted(theirs)       # no heat written where no body has any, as in one process
    assert len(mine["contacts/id1"]) > contacts
    walls = np.arange(len(mine["bodies/shape"])) >= len(mine["bodies/shape"]) - 5
    for name in compared:
        if name in ("bodies/force", "bodies/torque"):
            assert np.array_equal(mine[name][~walls], theirs[name][~walls]), name
            assert np.allclose(mine[name][walls], theirs[name][walls], rtol=1e-12, atol=0), name
            assert np.abs(mine["bodies/force"][walls]).max() > 0
        else:
            assert np.array_equal(mine[name], theirs[name]), name


@pytest.mark.parametrize("processes", [3, 4])
def test_clumps_written_continued_at_the_same_count_and_read_at_two_and_one_bit_for_bit(tmp_path, processes):
    # Each process holds its clumps' member lists by its own rows: the file names them by id,
    # as a serial file does.
    saved = scene("save", tmp_path / "run.h5", tmp_path / "saved.json", processes, "linear", "clumps")
    uninterrupted = np.asarray(saved["positions"])
    for restart in (processes, 2, None):
        restarted = scene("load", tmp_path / "run.h5", tmp_path / f"load-{restart}.json", restart)
        assert np.array_equal(np.asarray(restarted["positions"]), uninterrupted), restart
    serial = scene("save", tmp_path / "serial.h5", tmp_path / "serial.json", None, "linear", "clumps")
    assert np.array_equal(np.asarray(serial["positions"]), uninterrupted)
    assert_the_serial_file(tmp_path / "run.h5", tmp_path / "serial.h5", contacts=15)   # smaller members: fewer yet
    clumps = datasets(tmp_path / "run.h5")["bodies/clumps/members"]
    assert len(clumps) == 2 * (SPHERES - SPHERES // 4)      # two members a clump, every fourth sphere free


def test_the_energy_tracked_continues_from_a_checkpoint_at_another_process_count(tmp_path):
    # Each process accumulates its share of the terms: the file holds their sums, and the
    # per-body memory of imposed motions by id, as a serial file does.
    saved = scene("save", tmp_path / "run.h5", tmp_path / "saved.json", 4, "linear", "energy")
    serial = scene("save", tmp_path / "serial.h5", tmp_path / "serial.json", None, "linear", "energy")
    mine, theirs = datasets(tmp_path / "run.h5"), datasets(tmp_path / "serial.h5")
    for name in ("energy/previousDisplacement", "energy/previousRotation"):
        assert np.array_equal(mine[name], theirs[name], equal_nan=True), name
    restarted = scene("load", tmp_path / "run.h5", tmp_path / "load.json", processes=2)
    assert np.array_equal(np.asarray(restarted["positions"]), np.asarray(saved["positions"]))
    assert saved["energy"]["plastDissip"] > 0 and saved["energy"]["nonviscDamp"] > 0
    for term, value in saved["energy"].items():
        assert restarted["energy"][term] == pytest.approx(value, rel=1e-12, abs=1e-12), term
        assert serial["energy"][term] == pytest.approx(value, rel=1e-12, abs=1e-12), term


def test_a_serial_checkpoint_continues_under_mpirun(tmp_path):
    saved = scene("save", tmp_path / "run.h5", tmp_path / "saved.json")
    restarted = scene("load", tmp_path / "run.h5", tmp_path / "load.json", processes=2)
    assert np.array_equal(np.asarray(restarted["positions"]), np.asarray(saved["positions"]))


def test_saved_before_the_split_loaded_after_it_and_memory_slots_refused(tmp_path):
    # Before the first step every process holds the whole scene (process 0 writes it); a load
    # after steps brings the whole scene back, split again at the next step.
    script = tmp_path / "early.py"
    checkpoint = tmp_path / "early.h5"
    script.write_text(
        "O.materials.append(FrictMat(young=1e7, density=2600))\n"
        "for k in range(20):\n"
        "    O.bodies.append(utils.sphere((0.1 * k, 0, 0), 0.04))\n"
        "O.bodies.append(utils.wall(-0.05, axis=2, sense=1))\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],\n"
        "                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
        "O.dt = 1e-5\n"
        f"O.save({str(checkpoint)!r})\n"
        "O.run(50, True)\n"
        "from talus.dem import distributed\n"
        "after = distributed.positions()\n"
        f"O.load({str(checkpoint)!r})\n"
        "assert O.iter == 0\n"
        "O.run(50, True)\n"
        "assert (distributed.positions() == after).all()\n"
        "print('continued', O.iter)\n"
        "O.saveTmp()\n")
    done = talus_run(script, processes=2)
    assert "continued 50" in done.stdout, done.stdout + done.stderr
    assert done.returncode != 0 and done.stderr.count("O.saveTmp (a memory slot") == 1, done.stderr


def _load_script(tmp_path, checkpoint):
    script = tmp_path / "load.py"
    script.write_text(f"O.load({str(checkpoint)!r})\nO.run(10, True)\n")
    return script


def test_bad_checkpoints_are_refused_on_every_process_with_one_message(tmp_path):
    scene("save", tmp_path / "run.h5", tmp_path / "saved.json", processes=2)
    data = (tmp_path / "run.h5").read_bytes()
    (tmp_path / "truncated.h5").write_bytes(data[: len(data) // 2])
    h5py = pytest.importorskip("h5py")
    shutil.copy(tmp_path / "run.h5", tmp_path / "other.h5")
    with h5py.File(tmp_path / "other.h5", "r+") as f:
        f.attrs["format_version"] = np.int64(99)
    for name, expected in [("truncated.h5", "is truncated or corrupted"), ("other.h5", "format version 99")]:
        done = talus_run(_load_script(tmp_path, tmp_path / name), processes=2)
        assert done.returncode != 0
        message = f"checkpoint '{tmp_path / name}': "
        assert done.stderr.count(message) == 1 and expected in done.stderr, done.stderr
        assert "failed; ending every process" not in done.stderr, done.stderr


def test_a_failed_save_leaves_the_previous_file(tmp_path):
    # A file system too small for the second save: every process's write fails at some point.
    small = tmp_path / "small"
    small.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=200k", "tmpfs", str(small)],
                      capture_output=True).returncode != 0:
        pytest.skip("cannot mount a small file system (needs root)")
    try:
        script = tmp_path / "save.py"
        script.write_text(
            "import sys\n"
            "O.materials.append(FrictMat(young=1e7, density=2600))\n"
            "for k in range(int(sys.argv[1])):\n"
            "    O.bodies.append(utils.sphere((0.1 * (k % 30), 0.1 * (k // 30), 0), 0.04))\n"
            "O.bodies.append(utils.wall(-1, axis=2, sense=1))\n"
            "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),\n"
            "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],\n"
            "                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
            "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
            "O.dt = 1e-5\n"
            "O.run(2, True)\n"
            f"O.save({str(small / 'run.h5')!r})\n")
        assert talus_run(script, 50, processes=2).returncode == 0
        before = (small / "run.h5").read_bytes()
        done = talus_run(script, 3000, processes=2)
        assert done.returncode != 0 and done.stderr.count("run.h5") == 1, done.stderr
        assert (small / "run.h5").read_bytes() == before
        assert sorted(p.name for p in small.iterdir()) == ["run.h5"]      # no temporary file left
    finally:
        # The processes mpirun ended may hold the file system a moment longer.
        for _ in range(50):
            if subprocess.run(["umount", str(small)], capture_output=True).returncode == 0:
                break
            time.sleep(0.2)
