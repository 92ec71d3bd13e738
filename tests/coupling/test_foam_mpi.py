"""coupling: the DEM decomposed under mpirun and the fluid over its own ranks exchange
many-to-many (each DEM process its own particles, with the fluid ranks whose boxes hold some).

Checked on a short run of cases/scenes/fluidised_column.py (144 spheres falling through an upward
flow, talusVolumeAveragedFoam, 10 fluid steps): 2 DEM processes + 2 fluid ranks give the 1 + 2
run's positions bit for bit (the fluid orders the particles of all senders by index, so it
computes the same numbers) and the 1 + 1 run's within 1e-12; every process holds part of the
particles (none all of them); the bed lies below the upper fluid rank's box, so one DEM process
exchanges with one fluid rank only while the other (rank 0, which sends the commands) exchanges
with both — no process waits for a message nobody sends. The point-force solver (talusPointForceFoam)
goes through the same exchange: 2 + 2 gives its 1 + 2 run bit for bit. A fluid refusing the
handshake is reported once, and every process exits. The coupling's per-particle records
(ParticleRecords) follow particles that change process, alone and in a coupled run whose
spheres, thrown down, cross from one DEM process to the other (still 1 + 2's bits).

A process of the decomposed run that dies (kill -9 mid-run) stops every process
of the run, DEM and fluid, within seconds, with a message naming it.

The run is cases/scenes/fluidised_column.py on 2 DEM processes (mpirun's primary job) and 2 fluid
ranks (the child job FoamCoupling spawns). A fluid rank that dies is named by every DEM process's
liveness check (FoamCoupling: "fluid rank N (pid P) ... has died"); a DEM process that dies is
named by mpirun ("process rank N", its primary job), which ends the spawned fluid ranks with it."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from foam_case import REPO, needs_solver
from talus import bench

sys.path.insert(0, str(REPO / "cases" / "cfd"))
import cfd_mpi_parity as parity  # noqa: E402

try:
    from talus import _distributed  # noqa: F401  (built with the mpi_dem feature only)
except ImportError:
    _distributed = None

pytestmark = [needs_solver("talusVolumeAveragedFoam"),
              pytest.mark.skipif(_distributed is None or shutil.which("mpirun") is None,
                                 reason="the mpi_dem feature is off or mpirun is missing")]

STEPS, LAYERS = 10, 4


def test_two_dem_processes_and_two_fluid_ranks_give_the_one_process_run(tmp_path):
    runs = {(d, f): parity.run(d, f, STEPS, LAYERS, tmp_path) for d, f in [(1, 1), (1, 2), (2, 2)]}
    split = runs[2, 2]
    assert split["exchanges"] == STEPS
    assert np.array_equal(np.asarray(split["positions"]), np.asarray(runs[1, 2]["positions"]))
    # each process's forces summed apart, then over the processes: the same up to that sum's rounding
    assert split["lift"] == pytest.approx(runs[1, 2]["lift"], rel=1e-14)
    assert parity.difference(split, runs[1, 1]).max() < 1e-12
    # the flow and the particles changed over the run (the runs are not trivially the same)
    assert abs(split["lift"][-1] - split["lift"][0]) > 0.05 * abs(split["lift"][0])
    processes = split["processes"]
    spheres = 36 * LAYERS
    assert [p["particles"] > 0 for p in processes] == [True, True]
    assert sum(p["particles"] for p in processes) == spheres
    assert [p["fluid_ranks"] for p in processes] == [2, 1]


def test_particles_changing_process_take_their_coupling_state_along(tmp_path):
    # thrown down, the spheres cross the boundary between the DEM processes; the records of the
    # force applied and of the implicit drag go with them, so the run stays 1 + 2's bit for bit
    runs = {(d, f): parity.run(d, f, 20, 8, tmp_path, drop=-1.0) for d, f in [(1, 2), (2, 2)]}
    assert np.array_equal(np.asarray(runs[2, 2]["positions"]), np.asarray(runs[1, 2]["positions"]))
    assert sum(p["handed_over"] for p in runs[2, 2]["processes"]) > 0


def test_the_point_force_solver_exchanges_the_same_way(tmp_path):
    runs = {(d, f): parity.run(d, f, STEPS, LAYERS, tmp_path, "pointforce") for d, f in [(1, 2), (2, 2)]}
    assert np.array_equal(np.asarray(runs[2, 2]["positions"]), np.asarray(runs[1, 2]["positions"]))
    assert runs[2, 2]["lift"] == pytest.approx(runs[1, 2]["lift"], rel=1e-14)
    assert [p["fluid_ranks"] for p in runs[2, 2]["processes"]] == [2, 1]


def test_a_refused_handshake_is_reported_once_and_every_process_exits(tmp_path):
    # a fluid density the case does not have: every DEM process learns the fluid's refusal
    scene = tmp_path / "scene.py"
    scene.write_text(parity.SCENE.read_text().replace("rhoFluid=RHO,", "rhoFluid=999.0,"))
    case = parity.fluid_case(tmp_path / "case", 2)
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", sys.executable, "-m", "talus", "run",
               "-j", "1", str(scene), str(case.path), "2", "5", str(tmp_path / "out.json"), "4"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120, env=bench.child_environment())
    assert done.returncode != 0
    assert done.stderr.count("fluid density mismatch: DEM side rhoFluid = 999") == 1, done.stderr


def test_coupling_records_follow_their_particles_to_their_new_process(tmp_path):
    driver = Path(__file__).with_name("records_driver.py")
    done = subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", sys.executable, str(driver),
                           str(tmp_path)], capture_output=True, text=True, timeout=60, env=bench.child_environment())
    assert done.returncode == 0, done.stderr
    held = [json.loads((tmp_path / f"records-{rank}.json").read_text()) for rank in (0, 1)]
    # each keeps its own, takes the particle that came over, and has zeros for the new one
    assert held[0]["values"] == [[0, 0], [10, 100], [40, 400]] and held[0]["sent"] == 1
    assert held[1]["values"] == [[20, 200], [30, 300], [0, 0]] and held[1]["sent"] == 1


def processes_of(case: Path) -> dict[str, dict[int, int]]:
    """The run's processes on this machine: {"dem": {rank: pid}, "fluid": {rank: pid}}."""
    found = {"dem": {}, "fluid": {}}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline") as f:
                command = f.read().split("\0")
            with open(f"/proc/{entry}/environ") as f:
                rank = [e.split("=")[1] for e in f.read().split("\0") if e.startswith("OMPI_COMM_WORLD_RANK=")]
            with open(f"/proc/{entry}/stat") as f:
                zombie = f.read().rsplit(")", 1)[1].split()[0] == "Z"
        except OSError:     # ended meanwhile, or not ours to read
            continue
        if not rank or zombie or str(case) not in " ".join(command):
            continue
        side = "fluid" if command[0].endswith("Foam") else "dem"
        found[side][int(rank[0])] = int(entry)
    return found


@pytest.mark.parametrize("side", ["dem", "fluid"])
def test_a_process_killed_mid_run_stops_every_process_of_both_sides_naming_it(tmp_path, side):
    case = parity.fluid_case(tmp_path / "case", 2)
    talus = [sys.executable, "-m", "talus", "run", "-j", "1", str(parity.SCENE), str(case.path), "2", "10000000",
             str(tmp_path / "out.json"), "4", case.solver]
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--mca", "btl_tcp_if_include", "lo",
               "--mca", "oob_tcp_if_include", "lo", "-np", "2", *talus]
    run = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           env=bench.child_environment(), start_new_session=True)
    try:
        deadline = time.monotonic() + 180
        while True:     # every process running, the exchanges under way
            found = processes_of(case.path)
            if len(found["dem"]) == 2 and len(found["fluid"]) == 2:
                break
            assert run.poll() is None, run.communicate()
            assert time.monotonic() < deadline, "the coupled run did not start"
            time.sleep(0.2)
        time.sleep(3)   # the handshake done, exchanging
        victim = found[side][1]
        killed = time.monotonic()
        os.kill(victim, signal.SIGKILL)
        out, err = run.communicate(timeout=30)
        ended = time.monotonic() - killed
    finally:
        if run.poll() is None:      # left running by a failure above: end the run's whole session
            os.killpg(run.pid, signal.SIGKILL)
            run.communicate()
    print(f"every process ended {ended:.2f} s after {side} rank 1 was killed")
    assert run.returncode != 0 and ended < 30
    time.sleep(1)
    assert processes_of(case.path) == {"dem": {}, "fluid": {}}
    if side == "fluid":
        assert f"FoamCoupling: fluid rank 1 (pid {victim}) of " in err and "has died" in err
    else:
        assert "Primary job" in err and "process rank 1 with PID" in err and "exited on signal 9" in err
