"""`mpirun -np 2 talus run script.py` of a script written for one process: the serial run's
positions bit for bit, what is not distributed refused by name on every process (reported
once, no process left waiting), a partition method Zoltan lacks refused naming the valid ones,
and a body owned by the other process refused naming the rule."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import talus

SCENE = Path(__file__).resolve().parents[3] / "cases" / "scenes" / "deposition.py"

try:
    from talus import _distributed  # noqa: F401  (built with the mpi_dem feature only)
except ImportError:
    _distributed = None
pytestmark = pytest.mark.skipif(_distributed is None or shutil.which("mpirun") is None,
                                reason="the mpi_dem feature is off or mpirun is missing")


def talus_run(script, *args, processes=None, env=None, timeout=60):
    command = [sys.executable, "-m", "talus", "run", "-j", "1", str(script), *map(str, args)]
    if processes:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(processes), *command]
    # the processes mpirun starts find the package the tests import, wherever it was built
    package_root = str(Path(talus.__file__).resolve().parents[1])
    path = os.pathsep.join(filter(None, [package_root, os.environ.get("PYTHONPATH")]))
    environment = {**os.environ, "OMP_NUM_THREADS": "1", "PYTHONPATH": path, **(env or {})}
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=environment)


def json_of_runs(folder, name, text, counts=(None, 2, 3), timeout=60):
    """The script `text` (which writes a JSON file named by its first argument) run alone
    (None) and under mpirun at each count: the JSON of each run, by count."""
    script = folder / f"{name}.py"
    script.write_text(text)
    out = {}
    for processes in counts:
        path = folder / f"{name}-{processes}.json"
        done = talus_run(script, path, processes=processes, timeout=timeout)
        assert done.returncode == 0, done.stderr
        out[processes] = json.loads(path.read_text())
    return out


@pytest.mark.parametrize("method", ["RCB", "HSFC"])
def test_two_processes_give_the_serial_positions_bit_for_bit(tmp_path, method):
    serial, split = tmp_path / "serial.json", tmp_path / "split.json"
    assert talus_run(SCENE, 200, 400, serial).returncode == 0
    done = talus_run(SCENE, 200, 400, split, processes=2, env={"TALUS_PARTITION": method})
    assert done.returncode == 0, done.stderr
    a, b = json.loads(serial.read_text()), json.loads(split.read_text())
    assert len(b["positions"]) == 4 and np.array_equal(np.asarray(a["positions"]), np.asarray(b["positions"]))
    # Each process sent ghost updates every step (and after the script's PyRunners, which may
    # have written into the bodies), and the spheres touched the floor by then.
    updates = [t["updates"] for t in b["traffic"]]
    assert updates[0] == updates[1] and 400 <= updates[0] <= 410, updates
    assert all(t["update_bytes"] > 0 for t in b["traffic"])
    assert a["floor_force"] < 0 and b["floor_force"] == pytest.approx(a["floor_force"], rel=1e-12)
    # print from process 0 only: each sample's line once
    assert done.stdout.count("\n100 ") + done.stdout.startswith("100 ") == 1


def _script(tmp_path, body):
    script = tmp_path / "script.py"
    script.write_text(
        "O.materials.append(FrictMat(young=1e7, density=2600))\n"
        "for k in range(20):\n"
        "    O.bodies.append(utils.sphere((0.1 * k, 0, 0), 0.04))\n"
        "O.bodies.append(utils.wall(-1, axis=2, sense=1))\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],\n"
        "                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
        "O.dt = 1e-5\n" + body)
    return script


@pytest.mark.parametrize("body, named", [
    ("O.bodies.append(utils.box((0, 0, -1), (1, 1, 0.1)))\nO.run(10, True)\n", "Box"),
    ("O.engines = O.engines + [HdapsGravityEngine()]\nO.run(10, True)\n", "HdapsGravityEngine"),
])
def test_what_is_not_distributed_is_refused_by_name_once(tmp_path, body, named):
    assert_refused_by_name_once(talus_run(_script(tmp_path, body), processes=2), named)


def assert_refused_by_name_once(done, named):
    """A run under mpirun stopped, the refusal naming `named` reported by process 0 only."""
    assert done.returncode != 0
    assert done.stderr.count(named) == 1, done.stderr
    assert "not distributed yet" in done.stderr or "in one process" in done.stderr, done.stderr


def test_an_unknown_partition_method_is_refused_naming_the_valid_ones(tmp_path):
    done = talus_run(_script(tmp_path, "O.run(10, True)\n"), processes=2, env={"TALUS_PARTITION": "PHG"})
    assert done.returncode != 0
    assert done.stderr.count("'PHG'") == 1 and "RCB, HSFC" in done.stderr, done.stderr


def test_a_body_read_by_id_gives_its_own_id_and_state_on_every_process(tmp_path):
    # Every process reads every body by id (collective): b.id is the id the script gave (not
    # the process's row), and the state is that body's (sphere k starts at x = 0.1 k), the body
    # itself on its owner, a snapshot elsewhere.
    body = ("O.run(10, True)\n"
            "seen = []\n"
            "for k in range(20):\n"
            "    b = O.bodies[k]\n"
            "    assert b.id == k and abs(b.state.pos[0] - 0.1 * k) < 1e-9, (k, b.id, b.state.pos)\n"
            "    if type(b).__name__ != 'RemoteBody':\n"
            "        seen.append(k)\n"
            "import sys\n"
            "sys.stderr.write('OWNED %s\\n' % seen)\n")
    done = talus_run(_script(tmp_path, body), processes=2)
    assert done.returncode == 0, done.stderr
    owned = [eval(line[6:]) for line in done.stderr.splitlines() if line.startswith("OWNED ")]
    assert len(owned) == 2 and sorted(owned[0] + owned[1]) == list(range(20)) and min(map(len, owned)) > 0


def test_a_body_moved_beyond_the_ghost_layer_is_named_with_the_step(tmp_path):
    # A sphere moved 5 m up between two runs (a teleport): its owner names it.
    body = ("O.run(10, True)\n"
            "b = O.bodies[3]\n"
            "b.state.pos = b.state.pos + Vector3(0, 0, 5)\n"
            "O.run(10, True)\n")
    done = talus_run(_script(tmp_path, body), processes=2)
    assert done.returncode != 0
    assert done.stderr.count("beyond the ghost layer") == 1 and "step 10: body " in done.stderr, done.stderr


def test_each_process_keeps_only_its_spheres_the_walls_and_its_ghosts(tmp_path):
    # After the split, of the scene every process built whole only its own spheres, the walls
    # and the ghosts are left; the halo's time is reported with its traffic.
    body = ("O.run(10, True)\n"
            "from talus.dem import distributed\n"
            "d = distributed.domain(O)\n"
            "rows = len(O.positions())\n"
            "mine = sum(1 for r in range(rows) if d.owns(r)) - 1\n"          # less the wall
            "table = distributed.per_process({'rows': rows, 'mine': mine})\n"
            "traffic = distributed.traffic()\n"
            "import json\n"
            "print('RESULT', json.dumps({'table': table, 'traffic': traffic}))\n")
    done = talus_run(_script(tmp_path, body), processes=2)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout.split("RESULT", 1)[1])
    assert sum(p["mine"] for p in result["table"]) == 20
    for p in result["table"]:
        ghosts = p["rows"] - p["mine"] - 1
        assert 0 < ghosts < p["mine"] and p["rows"] < 21, result
    for t in result["traffic"]:
        assert t["updates"] == 10 and t["update_seconds"] > 0 and t["split_seconds"] > 0
        assert 0 <= t["wait_cpu_seconds"] <= t["update_seconds"] + t["reduction_seconds"] + 0.1


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="one CPU: bound or not, the same set")
@pytest.mark.parametrize("binding", [None, "core"])
def test_processes_are_unbound_unless_a_binding_is_asked_for(tmp_path, binding):
    # Open MPI binds 2 processes to a core each by default; talus run gives them every CPU back,
    # threads included, but keeps a binding the user asked for with --bind-to.
    script = tmp_path / "cpus.py"
    script.write_text(
        "import json, os\n"
        "threads = {int(t): sorted(os.sched_getaffinity(int(t))) for t in os.listdir('/proc/self/task')}\n"
        "rank = os.environ['OMPI_COMM_WORLD_RANK']\n"
        f"open(os.path.join({str(tmp_path)!r}, 'cpus' + rank + '.json'), 'w').write(json.dumps(threads))\n")
    env = {"OMPI_MCA_hwloc_base_binding_policy": binding} if binding else {}
    done = talus_run(script, processes=2, env=env)
    assert done.returncode == 0, done.stderr
    everything = sorted(os.sched_getaffinity(0))
    for rank in (0, 1):
        sets = json.loads((tmp_path / f"cpus{rank}.json").read_text()).values()
        if binding:
            assert all(len(cpus) == 1 for cpus in sets)
        else:
            assert all(cpus == everything for cpus in sets)
