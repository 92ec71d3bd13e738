"""coupling: failures during a coupled run (issue #6). The DEM process (foam_drag_driver.py)
writes a checkpoint every 10 exchanges; then a fluid rank is killed, the DEM process is killed,
or a particle is driven out of the mesh.

Checked: every process of the run is gone within 5 s (no orphan: no process left whose command
line names the case), the surviving side names what happened, and the last DEM checkpoint
loads (O.load) with the particles inside the mesh."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path


from foam_case import DRIVER, ENV, meshed_box, needs_solver

pytestmark = needs_solver("talusVolumeAveragedFoam")


def case(tmp_path: Path) -> Path:
    return meshed_box(tmp_path / "case")


def processes_naming(path: Path) -> list[int]:
    """Pids of the processes whose command line contains ``path`` (the driver and the solver)."""
    found = subprocess.run(["pgrep", "-f", str(path)], capture_output=True, text=True)
    return [int(p) for p in found.stdout.split()]


def start(work: Path, solver: str, *extra: str) -> subprocess.Popen:
    run = subprocess.Popen([sys.executable, str(DRIVER), str(work), str(work / "out.json"), "--solver", solver,
                            "--exchanges", "1000000", "--checkpoint", str(work / "dem.h5"), *extra],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and not (work / "dem.h5").exists():
        time.sleep(0.1)
    time.sleep(0.5)  # a few checkpoints later
    return run


def solver_pid(work: Path, solver: str) -> int:
    for pid in processes_naming(work):
        program = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")[0].decode(errors="replace")
        if Path(program).name == solver:
            return pid
    raise AssertionError(f"no {solver} process for {work}")


def wait_all_gone(run: subprocess.Popen, work: Path, limit: float) -> float:
    started = time.monotonic()
    while time.monotonic() - started < limit and (run.poll() is None or processes_naming(work)):
        time.sleep(0.05)
    elapsed = time.monotonic() - started
    if run.poll() is None:
        run.kill()
    left = processes_naming(work)
    for pid in left:  # only processes of this test's own run
        os.kill(pid, signal.SIGKILL)
    assert not left, f"processes left behind: {left}"
    print(f"every process gone {elapsed:.2f} s after the failure")
    return elapsed


def checkpoint_is_intact(work: Path):
    check = ("from talus.dem import Scene; s = Scene(); s.load(%r, engines='current'); "
             "z = s.positions()[:, 2]; assert len(z) == 2 and s.time > 0 and (z < 0.01).all(); print('ok', s.time)"
             % str(work / "dem.h5"))
    done = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True, env=ENV, timeout=30)
    assert done.returncode == 0 and done.stdout.startswith("ok"), done.stdout + done.stderr


def test_killed_fluid_rank_stops_the_dem_side_within_seconds(tmp_path):
    work = case(tmp_path)
    run = start(work, "talusVolumeAveragedFoam")
    assert run.poll() is None, run.communicate()
    os.kill(solver_pid(work, "talusVolumeAveragedFoam"), signal.SIGKILL)
    elapsed = wait_all_gone(run, work, 10)
    _, err = run.communicate()
    assert elapsed < 5, err
    assert run.returncode != 0
    assert "fluid rank 0 (pid" in err and "has died while the DEM waited" in err, (run.returncode, _, err)
    checkpoint_is_intact(work)


def test_killed_dem_process_stops_the_fluid_within_seconds(tmp_path):
    work = case(tmp_path)
    run = start(work, "talusPointForceFoam")
    assert run.poll() is None, run.communicate()
    solver_pid(work, "talusPointForceFoam")
    run.kill()
    elapsed = wait_all_gone(run, work, 10)
    assert elapsed < 5
    checkpoint_is_intact(work)


def test_particle_leaving_the_mesh_stops_the_run_and_keeps_the_checkpoint(tmp_path):
    work = case(tmp_path)
    run = start(work, "talusVolumeAveragedFoam", "--leave")
    elapsed = wait_all_gone(run, work, 20)
    _, err = run.communicate()
    assert run.returncode != 0
    assert "RuntimeError: FoamCoupling: particle 1 at (" in err and "is outside the fluid mesh" in err, err
    checkpoint_is_intact(work)
