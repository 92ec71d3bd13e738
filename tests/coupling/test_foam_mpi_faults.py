"""coupling: a process of a decomposed CFD-DEM run that dies (kill -9 mid-run) stops every process
of the run, DEM and fluid, within seconds, with a message naming it.

The run is cases/scenes/fluidised_column.py on 2 DEM processes (mpirun's primary job) and 2 fluid
ranks (the child job FoamCoupling spawns). A fluid rank that dies is named by every DEM process's
liveness check (FoamCoupling: "fluid rank N (pid P) ... has died"); a DEM process that dies is
named by mpirun ("process rank N", its primary job), which ends the spawned fluid ranks with it."""
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

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
