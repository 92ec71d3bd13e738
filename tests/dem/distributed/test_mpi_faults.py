"""Faults of a run under mpirun: a process that dies (kill -9 mid-run) stops every process of the run
within seconds with a message naming it. (A body moving further than the ghost layer in one step:
test_mpi_run.py's test_a_body_moved_beyond_the_ghost_layer_is_named_with_the_step.)"""
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from talus.bench import child_environment

pytestmark = pytest.mark.skipif(shutil.which("mpirun") is None, reason="needs mpirun")
try:
    from talus import _distributed  # noqa: F401
except ImportError:
    pytestmark = pytest.mark.skip(reason="built without the mpi_dem feature")

#: Spheres settling on a floor for as long as it takes; every process writes its pid once stepping.
ENDLESS = """\
import os
from yade import pack
from talus.dem import distributed
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (1, 1, 2), rMean=0.04, rRelFuzz=0.3, num=400, seed=1)
cloud.toSimulation()
O.bodies.append(utils.wall(0, axis=2, sense=1))


def stepping():
    with open(os.path.join({folder!r}, f"{{distributed.rank()}}.pid"), "w") as f:
        f.write(str(os.getpid()))


O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
             PyRunner(command="stepping()", iterPeriod=10, nDo=1)]
O.dt = 0.7 * PWaveTimeStep()
O.run(10**9, True)
"""


def alive(pid: int) -> bool:
    """Whether process `pid` still runs (a zombie left for its parent to reap counts as ended)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


@pytest.mark.parametrize("victim", [0, 1])
def test_a_process_killed_mid_run_stops_every_process_naming_it(tmp_path, victim):
    script = tmp_path / "endless.py"
    script.write_text(ENDLESS.format(folder=str(tmp_path)))
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2",
               sys.executable, "-m", "talus", "run", "-j", "1", str(script)]
    run = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           env=child_environment(), start_new_session=True)
    try:
        pidfiles = [tmp_path / f"{rank}.pid" for rank in range(2)]
        deadline = time.monotonic() + 120
        while not all(p.exists() and p.read_text() for p in pidfiles):
            assert run.poll() is None, run.communicate()
            assert time.monotonic() < deadline, "the run did not start stepping"
            time.sleep(0.1)
        pids = [int(p.read_text()) for p in pidfiles]
        killed = time.monotonic()
        os.kill(pids[victim], signal.SIGKILL)
        out, err = run.communicate(timeout=30)
        ended = time.monotonic() - killed
        print(f"every process ended {ended:.2f} s after process {victim} was killed")
    finally:
        if run.poll() is None:      # left running by a failure above: end the run's whole session
            os.killpg(run.pid, signal.SIGKILL)
            run.communicate()
    assert run.returncode != 0
    assert ended < 30
    assert not any(alive(pid) for pid in pids)
    # Open MPI's mpirun names the process that died and the signal (its pid it gives as 0).
    assert f"process rank {victim} with PID" in err and "exited on signal 9" in err

