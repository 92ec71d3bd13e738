"""PeriIsoCompressor and Peri3dController under mpirun: the periodic cloud of
cases/scenes/periodic_cell.py compressed by each, at 2 and 3 processes (oversubscribed), against
the serial run of the same script: the positions, the cell, the stress and every read-out of the
controller bit for bit. What they sum over bodies and contacts (PeriIsoCompressor's stress
measure and stiffness, the unbalanced force it waits for, Peri3dController's Love-Weber stress)
is summed exactly over the processes; a sum rounded in another order would move the cell, and
with it every sphere, by the last bits, which the compaction amplifies."""
import json

import numpy as np
import pytest

from test_mpi_periodic import SCENE
from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip)

STEPS = {"iso": 2200, "peri3d": 1000}
_serial = {}


def run(tmp_path, mode, processes):
    path = tmp_path / f"{mode}-{processes or 1}.json"
    done = talus_run(SCENE, 300, STEPS[mode], path, mode, processes=processes, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(path.read_text())


@pytest.mark.parametrize("processes", [2, 3])
@pytest.mark.parametrize("mode", ["iso", "peri3d"])
def test_a_periodic_cell_controller_gives_the_serial_run(tmp_path, mode, processes):
    if mode not in _serial:                                # one serial run for both process counts
        _serial[mode] = run(tmp_path, mode, None)
    serial, split = _serial[mode], run(tmp_path, mode, processes)
    assert len(split["positions"]) == STEPS[mode] // 100
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert split["cells"] == serial["cells"] and split["stress"] == serial["stress"]
    assert split["history"] == serial["history"]          # what the controller read, every 50 steps
    assert split["compacted"] == serial["compacted"] and split["unbalanced"] == serial["unbalanced"]
    cells, last = np.asarray(serial["cells"]), np.asarray(serial["positions"][-1])
    assert np.linalg.det(cells[-1]) < 0.7 * np.linalg.det(cells[0])
    # spheres crossed the cell's faces and changed process on the way
    assert (np.floor(np.linalg.solve(cells[-1], last.T).T) != 0).any(axis=1).sum() >= 5
    assert all(t["migrated_bodies"] > 0 for t in split["traffic"])
    history = serial["history"]
    if mode == "iso":
        # both stresses reached, each with the unbalanced force below maxUnbalanced: the stages
        # and the step the compressor ended at are the serial ones
        assert history["state"][-1] == 2 and serial["compacted"] is not None
        assert history["sigma"][-1] == pytest.approx([-2e5] * 3, rel=0.02)
    else:
        # sheared (xy) and the stress zz near its goal, -20 kPa, as the controller drove it
        assert cells[-1][0, 1] > 0.1
        assert history["stress"][-1][2] == pytest.approx(-2e4, rel=0.3)


PACKING = """import json, sqlite3, sys
from yade import pack
from talus.dem import distributed
seed, db = int(sys.argv[2]), sys.argv[3]
sp = pack.randomPeriPack(radius=.05, initSize=Vector3(.6, .6, .6), memoizeDb=db, seed=seed)
spheres = [[*c, r] for c, r in sp]
every = distributed.gather_objects(spheres)             # the packing each process made
stored = sqlite3.connect(db).execute("select count(*) from packings").fetchone()[0]
if distributed.rank() == 0:
    json.dump({"spheres": spheres, "alike": all(s == spheres for s in every), "stored": stored,
               "cell": list(sp.cellSize)}, open(sys.argv[1], "w"))
"""


@pytest.mark.parametrize("seed", [1, -1])
def test_random_peri_pack_compresses_split_and_gives_one_packing(tmp_path, seed):
    # randomPeriPack compresses a cloud with PeriIsoCompressor in a scene of its own, split over
    # the processes too; the packing it returns holds every sphere on every process
    # (SpherePack.fromSimulation gathers them), stored once in the database (by process 0). An
    # unseeded cloud is one random cloud for every process (makeCloud's seed drawn for all).
    script = tmp_path / "packing.py"
    script.write_text(PACKING)
    out = {}
    for n in (None, 2):
        path = tmp_path / f"{n}.json"
        done = talus_run(script, path, seed, tmp_path / f"db-{n}.sqlite", processes=n, timeout=600)
        assert done.returncode == 0, done.stderr
        out[n] = json.loads(path.read_text())
    assert out[2]["alike"] and out[2]["stored"] == 1
    assert len(out[2]["spheres"]) > 100
    if seed >= 0:
        assert out[2]["spheres"] == out[None]["spheres"] and out[2]["cell"] == out[None]["cell"]
