"""Clumps in a periodic cell under mpirun, against the serial run of the same script at 2 and 3
processes (oversubscribed on this machine): a clump and its members owned by the process of the
clump's centre and ghosted whole through the cell's images, in a cell compacted by
PeriTriaxController or compressed and sheared by O.cell.velGrad: the serial positions, cell and
stress bit for bit, clumps having crossed the cell's faces and changed process; clumps grown by
growParticles placed alike wherever they go after."""
import json
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)

SCENE = Path(__file__).resolve().parents[3] / "cases" / "scenes" / "periodic_clumps.py"


def run(tmp_path, mode, processes, env=None, *options):
    path = tmp_path / f"{mode}-{processes or 1}.json"
    done = talus_run(SCENE, 300, 1000, path, mode, *options, processes=processes, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(path.read_text())


def assert_same_run(serial, split):
    assert len(split["positions"]) == 10
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert split["cells"] == serial["cells"] and split["stress"] == serial["stress"]
    largest = max(abs(v) for v in serial["energy"].values())
    assert all(abs(split["energy"][k] - v) <= 1e-12 * largest for k, v in serial["energy"].items())


@pytest.mark.parametrize("processes", [2, 3])
@pytest.mark.parametrize("mode", ["triax", "shear"])
def test_clumps_in_a_deforming_periodic_cell_give_the_serial_run(tmp_path, mode, processes):
    serial, split = run(tmp_path, mode, None), run(tmp_path, mode, processes)
    assert_same_run(serial, split)
    # The cell shrank (and sheared), the clumps touched, and bodies (members sticking out of the
    # cell among them) lie beyond its faces: their unwrapped positions outside it.
    cells, last = np.asarray(serial["cells"]), np.asarray(serial["positions"][-1])
    assert np.linalg.det(cells[-1]) < 0.75 * np.linalg.det(cells[0])
    assert mode == "triax" or cells[-1][0, 2] > 0.2
    assert serial["energy"]["plastDissip"] > 0 and serial["stress"][0][0] < 0
    assert (np.floor(np.linalg.solve(cells[-1], last.T).T) != 0).any(axis=1).sum() >= 10
    assert sum(t["migrated_bodies"] for t in split["traffic"]) > 0


def test_hsfc_regions_grown_to_hold_the_members(tmp_path):
    assert_same_run(run(tmp_path, "shear", None), run(tmp_path, "shear", 3, env={"TALUS_PARTITION": "HSFC"}))


# RCB's two halves move little with the shear (a dozen bodies change process, more when the
# measured load sets off a rebalancing); HSFC moves most clumps at each re-detection; `rebalance`
# partitions again at every re-detection, so that grown bodies land where no copy of them was.
@pytest.mark.parametrize("processes, method, moved, options", [(2, "RCB", 1, ()), (3, "HSFC", 100, ()),
                                                              (3, "RCB", 1, ("rebalance",))])
def test_clumps_grown_are_placed_alike_wherever_they_go(tmp_path, processes, method, moved, options):
    # Every process scales the member offsets of every growing clump in its table, held there or
    # not, so a clump placed after the growth by a process that did not hold it is the serial one.
    serial = run(tmp_path, "shear", None, None, "grow")
    split = run(tmp_path, "shear", processes, {"TALUS_PARTITION": method}, "grow", *options)
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert split["cells"] == serial["cells"] and split["stress"] == serial["stress"]
    assert serial["energy"]["growthWork"] != 0 and sum(t["migrated_bodies"] for t in split["traffic"]) >= moved
    # the growth's energy memory (per body) followed the bodies' rows at the re-detection it set off
    assert split["energy"]["growthWork"] == pytest.approx(serial["energy"]["growthWork"], rel=1e-12)
