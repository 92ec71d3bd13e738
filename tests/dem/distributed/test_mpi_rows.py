"""The particle exchange interface of a script under `mpirun -np N talus run` (2 and 3 processes
against one): a process's per-body arrays hold its own rows, `shares.rows(s, ids)`
(talus.dem.split.shares) maps the script's ids to them, so `velocities()[rows(s, ids)] = 0` stops
the same bodies as in one process; `shares.total` and `largest` make a process's share the whole
scene's; `shares.once` runs a call on process 0 and gives its result to all (an error there raised everywhere); a case's
records and charts (talus.results) are written by process 0 alone. The scene: the fluidised bed's
idiom in a scene of its own (spheres quenched as they fall onto a floor, then let go)."""
import json

import numpy as np
import pytest

from test_mpi_run import pytestmark  # noqa: F401  (the same skip: mpi_dem feature and mpirun)
from test_mpi_scripts import run_script

SCRIPT = """
import json, os, sys, tempfile
import numpy as np
import talus.results
from talus import results
from talus.dem import distributed
from talus.dem.core.scene import Scene
from talus.dem.split import shares
out = sys.argv[1]
report = lambda what: sys.stderr.write("WROTE %s ON %d\\n" % (what, distributed.rank()))
if distributed.rank() != 0:     # a record or chart written by another process than 0 is reported
    talus.results.write_atomically = lambda path, *a, **k: report(path)
class Figure:
    def savefig(self, path, **options):
        if distributed.rank() != 0:
            report(path)
        open(path, "w").write("chart")
s = Scene()
s.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
s.bodies.append(utils.wall(0, axis=2, sense=1))
jitter = np.random.default_rng(3).uniform(-0.02, 0.02, size=(240, 3))
lattice = [(0.1 + 0.15 * i, 0.1 + 0.15 * j, 0.06 + 0.15 * k) for k in range(8) for j in range(5) for i in range(6)]
ids = s.bodies.append([utils.sphere(tuple(np.add(x, d)), 0.04) for x, d in zip(lattice, jitter)])
s.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.1)]
s.dt = 0.7 * PWaveTimeStep(s)
before = shares.rows(s, ids)            # before the split: every process holds every body
result = {"rows_before": [int(r) for r in before]}
quenched = ids[::3]
lift, held = [], []
for k in range(20):
    s.run(25, True)
    s.velocities()[shares.rows(s, quenched)] = 0.0      # the same spheres stopped in one process and split
    rows = shares.rows(s, ids)
    held.append(len(rows))
    lift.append(shares.total(float(np.sum(s.forces()[rows][:, 2]))))
    v_z, count = shares.total([np.sum(s.velocities()[rows][:, 2]), len(rows)])
    assert count == len(ids), count
top = shares.largest(float(np.max(s.positions()[shares.rows(s, ids)][:, 2], initial=-np.inf)))
result.update(positions=distributed.positions(s).tolist(), lift=lift, top=top, held=held,
              quenched_speed=shares.largest(float(np.abs(s.velocities()[shares.rows(s, quenched)]).max(initial=0.0))))
# one folder for the run, made by process 0, its path on every process
result["folders"] = distributed.gather_objects(shares.once(tempfile.mkdtemp, prefix="talus_test_once_"))
shares.once(os.rmdir, result["folders"][0])     # removed once
try:
    shares.once(lambda: 1 / 0)
except Exception as e:
    result["error"] = f"{type(e).__name__}: {e}"
case = results.Case("test.mpi-rows", quick=True, folder=out)
case.record("top", top, "none", 10.0)
case.save_chart(Figure())
if distributed.rank() == 0:
    open(out + "/result.json", "w").write(json.dumps(result))
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    return run_script(tmp_path_factory.mktemp("rows"), SCRIPT)


@pytest.mark.parametrize("processes", [2, 3])
def test_rows_of_ids_act_on_the_same_bodies_as_in_one_process(runs, processes):
    (_, serial), (_, split) = runs[None], runs[processes]
    # before the split the rows are the ids, in one process and on every process
    assert serial["rows_before"] == split["rows_before"] == list(range(1, 241))
    # each process held a share of the spheres (in one process: all of them)
    assert set(serial["held"]) == {240} and max(split["held"]) < 240
    # quenching through the rows stops the same spheres: the serial positions, bit for bit
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert serial["quenched_speed"] == split["quenched_speed"] == 0.0
    # the shares summed: the floor's push on the spheres within round-off, the highest sphere exactly
    assert split["lift"] == pytest.approx(serial["lift"], rel=1e-12, abs=1e-12 * max(map(abs, serial["lift"])))
    assert max(serial["lift"]) > 0 and split["top"] == serial["top"]


@pytest.mark.parametrize("processes", [2, 3])
def test_once_runs_on_process_0_and_shares_its_result(runs, processes):
    (_, serial), (_, split) = runs[None], runs[processes]
    folders = split["folders"]
    assert len(folders) == processes and len(set(folders)) == 1 and "talus_test_once_" in folders[0]
    assert serial["error"] == "ZeroDivisionError: division by zero"
    assert split["error"] == "CollectiveError: ZeroDivisionError on process 0: division by zero"


@pytest.mark.parametrize("processes", [2, 3])
def test_records_and_charts_are_written_once(runs, processes):
    where, _ = runs[processes]
    record = json.loads((where / "test.mpi-rows.json").read_text())
    assert record["name"] == "test.mpi-rows" and record["pass"]
    assert (where / "test.mpi-rows.png").read_text() == "chart"
