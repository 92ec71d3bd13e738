"""Scripts written for Yade's mpy (``from yade import mpy as mp``) under ``mpirun -np N talus run``:
the serial answer at 2 and 3 processes (the subdomains the script assigns accepted, Zoltan's
partition used), bodies each process inserts itself gathered, commands sent to the workers
answered, and a bad mpy call refused by name, once."""
import json
import shutil
import subprocess
import sys

import numpy as np
import pytest
from talus.bench import child_environment

try:
    from talus import _distributed  # noqa: F401  (built with the mpi_dem feature only)
except ImportError:
    _distributed = None
try:
    import mpi4py  # noqa: F401
except ImportError:
    mpi4py = None
pytestmark = pytest.mark.skipif(_distributed is None or mpi4py is None or shutil.which("mpirun") is None,
                                reason="the mpi_dem feature is off, or mpirun or mpi4py is missing")


def talus_run(script, processes=None, timeout=240):
    command = [sys.executable, "-m", "talus", "run", "-j", "1", str(script)]
    if processes:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(processes), *command]
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=child_environment())


# Written as Yade's examples/mpi/testMPI_2D.py is: three blocks of spheres falling onto a box,
# each block assigned to a worker; the force on the box and every position after a merge.
MPY_SCRIPT = """
from yade import mpy as mp
import json
for sd in range(3):
    for i in range(6):
        for j in range(4):
            id = O.bodies.append(sphere((sd * 6 + i + j / 30., j, 0), 0.5))
            O.bodies[id].subdomain = min(sd + 1, mp.numThreads - 1)
WALL_ID = O.bodies.append(box(center=(9, -0.5, 0), extents=(20, 0, 2), fixed=True))
collider.verletDist = 0.5
newton.gravity = (0, -10, 0)
O.engines = [e for e in O.engines if e is not timeStepper]
O.dt = 0.001
mp.VERBOSE_OUTPUT = False
mp.REALLOCATE_FREQUENCY = 2
mp.mpirun(1)
mp.mpirun(300, mp.numThreads, True)
mp.mprint("merged", len(O.bodies))
if mp.rank == 0:
    json.dump({"force": O.forces.f(WALL_ID)[1], "positions": [list(b.state.pos) for b in O.bodies],
               "workers": mp.sendCommand("slaves", "len(O.bodies)", True)}, open(OUT, "w"))
"""


def _mpy_script(tmp_path, name, text):
    script = tmp_path / f"{name}.py"
    script.write_text(f"OUT = {str(tmp_path / (name + '.json'))!r}\n" + text)
    return script


def test_an_mpy_script_gives_the_serial_answer_at_2_and_3_processes(tmp_path):
    serial = talus_run(_mpy_script(tmp_path, "serial", MPY_SCRIPT))
    assert serial.returncode == 0, serial.stderr
    assert "one process" in serial.stdout      # mp.mpirun(np=1) says Talus spawns no workers
    a = json.loads((tmp_path / "serial.json").read_text())
    assert a["force"] < 0 and a["workers"] == []
    for n in (2, 3):
        done = talus_run(_mpy_script(tmp_path, f"split{n}", MPY_SCRIPT), processes=n)
        assert done.returncode == 0, done.stderr
        b = json.loads((tmp_path / f"split{n}.json").read_text())
        assert np.array_equal(np.asarray(a["positions"]), np.asarray(b["positions"]))
        assert b["force"] == pytest.approx(a["force"], rel=1e-12)
        # after the merge every worker holds the whole scene, and answers rank 0's command
        assert b["workers"] == [len(a["positions"])] * (n - 1)
        # mprint writes from every rank; the subdomains the script set are not used, said once
        assert done.stdout.count(f"merged {len(a['positions'])}") == n
        assert done.stdout.count("b.subdomain not used") == 1


DISTRIBUTED_INSERT = """
from yade import mpy as mp
import json
# each worker inserts its own block (with its ids), rank 0 the floor, as parallelBodyInsert3D.py
blocks = 2
for w in range(1, blocks + 1):
    if WHOLE or mp.rank == w:
        for k in range(12):
            O.bodies.insertAtId(sphere((k % 4 + 5 * w, k // 4, 0), 0.5), 12 * (w - 1) + k)
if WHOLE or mp.rank == 0:
    WALL = O.bodies.insertAtId(box(center=(8, -0.5, 0), extents=(12, 0, 2), fixed=True), 12 * blocks)
newton.gravity = (0, -10, 0)
O.dt = 0.001
O.dynDt = False
mp.DISTRIBUTED_INSERT = not WHOLE
mp.mpirun(200)
force = O.forces.f(24)[1]
mp.mergeScene()
if mp.rank == 0:
    json.dump({"force": force, "positions": [list(b.state.pos) for b in O.bodies]}, open(OUT, "w"))
"""


def test_bodies_each_process_inserts_are_gathered_before_the_split(tmp_path):
    whole = talus_run(_mpy_script(tmp_path, "whole", "WHOLE = True\n" + DISTRIBUTED_INSERT))
    assert whole.returncode == 0, whole.stderr
    done = talus_run(_mpy_script(tmp_path, "inserted", "WHOLE = False\n" + DISTRIBUTED_INSERT), processes=3)
    assert done.returncode == 0, done.stderr
    a, b = (json.loads((tmp_path / f"{name}.json").read_text()) for name in ("whole", "inserted"))
    assert len(b["positions"]) == 25 and np.array_equal(np.asarray(a["positions"]), np.asarray(b["positions"]))
    assert a["force"] < 0 and b["force"] == pytest.approx(a["force"], rel=1e-12)


@pytest.mark.parametrize("call, named, once", [
    ("mp.mpirun(-5)", "nSteps", True),
    ("mp.REALOCATE_FREQUENCY = 2", "REALOCATE_FREQUENCY", True),
    ("mp.REALLOCATE_FREQUENCY = -1", "REALLOCATE_FREQUENCY", True),
    ("mp.FLUID_COUPLING = True", "FLUID_COUPLING", True),
    ("mp.sendCommand(executors=[1, 5], command='len(O.bodies)')", "executors", True),   # rank 0 alone raises it
    ("mp.splitScene()", "splitScene", False),   # an AttributeError: each process reports its own
])
def test_a_bad_mpy_call_is_refused_by_name(tmp_path, call, named, once):
    script = tmp_path / "bad.py"
    script.write_text("from yade import mpy as mp\n"
                      "O.bodies.append(sphere((0, 0, 0), 0.5))\n" + call + "\nmp.mpirun(5)\n")
    done = talus_run(script, processes=2)
    assert done.returncode != 0
    assert named in done.stderr
    assert named in done.stderr
    if once:    # every process raised it alike (reported by rank 0), or rank 0 alone raised it
        assert done.stderr.count("Traceback") == 1


def test_a_bad_subdomain_is_refused_naming_the_body(tmp_path):
    script = tmp_path / "bad.py"
    script.write_text("O.bodies.append(sphere((0, 0, 0), 0.5))\nO.bodies[0].subdomain = -1\n")
    done = talus_run(script)
    assert done.returncode != 0 and "body 0: subdomain" in done.stderr
