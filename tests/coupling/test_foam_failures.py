"""coupling: failures during a coupled run. The DEM process (foam_drag_driver.py) writes a
checkpoint every 10 exchanges; then a fluid rank is killed, the DEM process is killed, stalls
between two exchanges or is stopped (SIGSTOP) for longer than the timeout, or a particle is
driven out of the mesh.

Checked: every process of the run is gone within 5 s (no orphan: no process left whose command
line names the case, nor any process the DEM process started: Open MPI's daemon included), the
sides name what happened, and the last DEM checkpoint loads (O.load) with the particles inside
the mesh."""
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


def descendants(pid: int) -> list[int]:
    """The processes started by ``pid`` and by them (Open MPI's daemon, the fluid ranks)."""
    children = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    found, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def alive(pids: list[int]) -> list[int]:
    return [p for p in pids if Path(f"/proc/{p}").exists()
            and Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"]


def wait_all_gone(run: subprocess.Popen, work: Path, limit: float, started_by_run: list[int] | None = None) -> float:
    """Seconds until the run, the processes naming its case and those it started are gone
    (`started_by_run`: found before the run was killed, when its children were still its own)."""
    started = time.monotonic()
    if started_by_run is None:
        started_by_run = descendants(run.pid)
    while time.monotonic() - started < limit and (run.poll() is None or processes_naming(work)
                                                  or alive(started_by_run)):
        time.sleep(0.05)
    elapsed = time.monotonic() - started
    if run.poll() is None:
        run.kill()
    left = sorted(set(processes_naming(work) + alive(started_by_run)))
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
    started_by_run = descendants(run.pid)
    run.kill()
    elapsed = wait_all_gone(run, work, 10, started_by_run)
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


TIMEOUT = 3.0  # FoamCoupling timeout of the stall tests [s]


def test_stalled_dem_process_is_stopped_on_both_sides(tmp_path):
    """The DEM process sleeps between two exchanges: the fluid times out, the DEM process's
    watchdog stops it too, each naming the timeout, within seconds of it."""
    work = case(tmp_path)
    run = start(work, "talusPointForceFoam", "--timeout", str(TIMEOUT), "--stall-after", "30")
    elapsed = wait_all_gone(run, work, TIMEOUT + 15)
    out, err = run.communicate()
    assert "DEM process stalls" in out, out + err
    assert elapsed < TIMEOUT + 5, err
    assert run.returncode != 0
    assert "talusPointForceFoam: timed out: the DEM process sent nothing for 3 s" in err, err
    assert "FoamCoupling: the fluid solver" in err and "timed out: this DEM process sent it nothing for" in err, err
    assert "has died" not in err, err


def test_stopped_dem_process_is_stopped_on_both_sides(tmp_path):
    """The DEM process is stopped (SIGSTOP) for good: the fluid times out and wakes it (SIGCONT),
    and the DEM process ends naming the fluid's timeout, not a dead fluid rank."""
    work = case(tmp_path)
    run = start(work, "talusPointForceFoam", "--timeout", str(TIMEOUT))
    assert run.poll() is None, run.communicate()
    started_by_run = descendants(run.pid)
    os.kill(run.pid, signal.SIGSTOP)
    elapsed = wait_all_gone(run, work, TIMEOUT + 15)
    _, err = run.communicate()
    assert not alive(started_by_run)
    assert elapsed < TIMEOUT + 5, err
    assert "talusPointForceFoam: timed out: the DEM process sent nothing for 3 s" in err, err
    assert "FoamCoupling: the fluid solver" in err and "timed out" in err and "FoamCoupling timeout" in err, err
    assert "has died" not in err, err
