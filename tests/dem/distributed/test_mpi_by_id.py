"""`O.bodies[id]` under `mpirun -np N talus run` (talus.dem.split.by_id): a body owned by another
process is read on every process (the owner answers, the others get a snapshot), writes through it
take effect on its owner and its ghosts, and the serial results come out bit for bit: Yade's
examples NumericalDampingGravity.py and ViscElMatchMaker.py (which read bodies by id in their
PyRunners) unchanged, and a pile whose bodies a script reads and writes by id. Code that only some
processes run must not read by id: the disagreement is named on every process, never a hang."""
import json
import time
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import _script, json_of_runs, pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)

EXAMPLES = Path("/usr/share/doc/yade/examples")

# Appended to an example: what it computed, from process 0 (every body's position, the plot's rows).
RESULT = """
import json, sys
from talus.dem import distributed
O.run({steps}, True)
result = {{"positions": distributed.positions().tolist(), "plot": {{k: list(map(float, v)) for k, v in plot.data.items()}}}}
if distributed.rank() == 0:
    json.dump(result, open(sys.argv[1], "w"))
"""


@pytest.mark.skipif(not EXAMPLES.is_dir(), reason="Yade's examples are not installed")
@pytest.mark.parametrize("example, steps", [("NumericalDampingGravity.py", 1500), ("ViscElMatchMaker.py", 0)])
def test_yade_examples_reading_bodies_by_id_give_the_serial_bits(tmp_path, example, steps):
    script = tmp_path / example
    script.write_text((EXAMPLES / example).read_text() + RESULT.format(steps=steps))
    out = {}
    for processes in (None, 2):
        path = tmp_path / f"result-{processes}.json"
        done = talus_run(script, path, processes=processes, timeout=600)
        assert done.returncode == 0, done.stderr
        out[processes] = json.loads(path.read_text())
    serial, split = out[None], out[2]
    assert serial == split
    rows = next(iter(serial["plot"].values()))
    assert len(rows) >= 700 and len(serial["positions"]) >= 2


# A pile of spheres falling into a box of walls; the script reads and writes bodies by id, in a
# PyRunner and between runs (at 2 and 3 processes the bodies read are owned by several of them).
PILE = """
import json, sys, time
import numpy as np
from yade import pack
from talus.dem import distributed
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (1, 1, 1.5), rMean=0.05, rRelFuzz=0.3, num=300, seed=4)
cloud.toSimulation()
O.bodies.append(utils.aabbWalls([(0, 0, 0), (1, 1, 1.5)], thickness=0))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3),
             PyRunner(command="read()", iterPeriod=1), PyRunner(command="kick()", iterPeriod=150)]
O.dt = 0.5 * PWaveTimeStep()
heights, cpu = [], [0.0]


def read():     # ten bodies by id every step
    start = time.process_time()
    heights.append(sum(O.bodies[i].state.pos[2] for i in range(0, 300, 30)))
    cpu[0] += time.process_time() - start


def kick():     # writes in a PyRunner
    b = O.bodies[40 + O.iter // 150]
    b.state.vel = b.state.vel + Vector3(0.5, 0, 1)
    b.state.angVel = (0, 20, 0)


O.run(200, True)
samples = []
b = O.bodies[7]
b.state.vel = (1, -1, 2)
O.bodies[8].state.pos = O.bodies[8].state.pos + Vector3(0, 0, 0.002)
O.bodies[9].dynamic = False
O.bodies[10].state.blockedDOFs = "xyzXYZ"
O.bodies[11].shape.color = (1, 0, 0)
O.bodies[12].state.isDamped = False
O.bodies[13].state.vel[2] = 3       # in place: Yade's vel is a reference
O.bodies.erase(14)
erased = O.bodies[14] is None
# what the ghost update does not carry, on the body and its copies at once: body 15 heavier (its
# contacts' stiffness does not change with it, the integration does), body 16 through the other
# spheres but not the walls
O.bodies[15].state.mass = 8 * O.bodies[15].state.mass
for w in range(300, 306):
    O.bodies[w].mask = 3
O.bodies[16].mask = 2
for k in range(4):
    O.run(200, True)
    p = distributed.positions()
    p[14] = np.nan      # (erased)
    samples.append(p.tolist())
wall = O.bodies[300]
read_back = [list(O.bodies[7].state.vel), O.bodies[9].dynamic, O.bodies[10].state.blockedDOFs,
             list(O.bodies[11].shape.color), O.bodies[12].state.isDamped, O.bodies[3].id, list(wall.state.pos),
             O.bodies[15].state.mass, O.bodies[16].mask]
result = {"samples": samples, "heights": heights, "erased": erased, "read_back": read_back,
          "cpu": distributed.per_process({"cpu": cpu[0]}), "calls": len(heights) * 10}
if distributed.rank() == 0:
    json.dump(result, open(sys.argv[1], "w"))
"""


@pytest.fixture(scope="module")
def pile(tmp_path_factory):
    return json_of_runs(tmp_path_factory.mktemp("by_id"), "pile", PILE, timeout=600)


@pytest.mark.parametrize("processes", [2, 3])
def test_reads_and_writes_by_id_give_the_serial_bits(pile, processes):
    serial, split = pile[None], pile[processes]
    assert serial["heights"] == split["heights"] and len(serial["heights"]) == 999
    assert np.array_equal(np.asarray(serial["samples"], float), np.asarray(split["samples"], float), equal_nan=True)
    assert serial["read_back"] == split["read_back"] and serial["erased"] and split["erased"]
    assert serial["read_back"][1:5] == [False, "xyzXYZ", [1, 0, 0], False]


def test_a_read_by_id_costs_little(pile):
    # Ten bodies read by id every step of 1000: the slowest process's CPU seconds in them, per read.
    split = pile[2]
    per_read = max(p["cpu"] for p in split["cpu"]) / split["calls"]
    assert per_read < 1e-3, per_read


def _split_script(tmp_path, body):
    """test_mpi_run's 20 spheres and a wall, split by a first run, then `body`."""
    return _script(tmp_path, "from talus.dem import distributed\nfrom talus.dem.split import by_id\n"
                             "O.run(10, True)\n" + body)


@pytest.mark.parametrize("body, place", [
    # in a PyRunner, on process 0 only: met at the end of the others' command
    ("O.engines = O.engines + [PyRunner(command='if distributed.rank() == 0: O.bodies[3].state.pos', iterPeriod=5)]\n"
     "O.run(20, True)\n", "ended a PyRunner's command"),
    # between two runs, on process 1 only: met when the others start the next run
    ("if distributed.rank() == 1:\n    O.bodies[3].state.vel = (1, 0, 0)\nO.run(10, True)\n", "started O.run or O.step"),
    # the last line, on process 0 only: met at the end of the others' script
    ("if distributed.rank() == 0:\n    print(O.bodies[3].state.pos)\n", "reached the end of the script"),
    # different ids on different processes
    ("O.bodies[3 + distributed.rank()].state.pos\n", "read O.bodies[4]"),
])
def test_a_read_by_id_on_some_processes_only_is_named_on_every_one(tmp_path, body, place):
    done = talus_run(_split_script(tmp_path, body), processes=2, timeout=120)
    assert done.returncode != 0
    assert "are at different places of the script" in done.stderr and place in done.stderr, done.stderr
    assert "O.bodies[id] of a sphere or clump is collective" in done.stderr, done.stderr


def test_a_read_by_id_left_alone_ends_the_run_naming_the_rule(tmp_path):
    # Process 0 reads a body while process 1 went on into a reduction: process 0 cannot tell the
    # others, and after `patience` seconds ends the run naming the rule instead of waiting forever.
    body = ("by_id.patience = 3\n"
            "if distributed.rank() == 0:\n    O.bodies[3].state.pos\n"
            "unbalancedForce()\n")
    start = time.monotonic()
    done = talus_run(_split_script(tmp_path, body), processes=2, timeout=120)
    assert done.returncode != 0 and time.monotonic() - start < 60
    assert "process 0 read O.bodies[3] and the other processes did not come to it" in done.stderr, done.stderr
    assert "O.bodies[id] of a sphere or clump is collective" in done.stderr, done.stderr


def test_a_write_by_id_reaches_the_copies_at_once(tmp_path):
    # What the ghost update does not carry (mass, inertia, dynamic, mask, blockedDOFs) is written
    # on every process holding a copy of the body, at the write: a copy's mask decides the pairs
    # its process's collider makes, its mass a new contact's stiffness (visco-elastic laws).
    body = """
import json
from talus.dem.core.bodies import Body
d = distributed.domain(O)
ghosts = [i for r, i in enumerate(d.globalIds(list(range(len(O.positions()))))) if not d.owns(r)]
k = min(min(g) for g in distributed.gather_objects(ghosts) if g)
b = O.bodies[k]
b.state.mass, b.state.inertia, b.dynamic, b.mask, b.state.blockedDOFs = 5.0, (1, 2, 3), False, 2, 'xZ'
row = d.rowOf(k)
copy = Body(O, row, k) if row >= 0 else None
seen = None if copy is None else [d.owns(row), copy.state.mass, list(copy.state.inertia), copy.dynamic, copy.mask,
                                  copy.state.blockedDOFs]
every = distributed.gather_objects(seen)
if distributed.rank() == 0:
    print('RESULT', json.dumps(every))
"""
    done = talus_run(_split_script(tmp_path, body), processes=2)
    assert done.returncode == 0, done.stderr
    held = [h for h in json.loads(done.stdout.split("RESULT", 1)[1]) if h is not None]
    assert sorted(h[0] for h in held) == [False, True], held       # the owner and a copy
    assert all(h[1:] == [5.0, [1.0, 2.0, 3.0], False, 2, "xZ"] for h in held), held
