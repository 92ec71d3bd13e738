"""Periodic cells under mpirun, each against the serial run of the same script at 2 and 3
processes (oversubscribed on this machine): a periodic triaxial compaction (PeriTriaxController,
dynCell, reading the stress every step) and a cell compressed and sheared by O.cell.velGrad give
the serial positions, cell and stress bit for bit, bodies having changed process across the
cell's faces; spheres settling onto a floor (a wall, two facets, a box) in a fixed and in a
sheared cell give the serial positions bit for bit; a cell resized by the script (on every
process) goes on as in one process; a cell changed on one process only stops every process,
naming the rule (PeriIsoCompressor and Peri3dController: test_mpi_periodic_controllers.py)."""
import json
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip)

SCENES = Path(__file__).resolve().parents[3] / "cases" / "scenes"
SCENE = SCENES / "periodic_cell.py"


def run(tmp_path, mode, processes, env=None):
    path = tmp_path / f"{mode}-{processes or 1}.json"
    done = talus_run(SCENE, 300, 1000, path, mode, processes=processes, env=env)
    assert done.returncode == 0, done.stderr
    return json.loads(path.read_text())


@pytest.mark.parametrize("processes", [2, 3])
@pytest.mark.parametrize("mode", ["triax", "shear"])
def test_a_deforming_periodic_cell_gives_the_serial_run(tmp_path, mode, processes):
    serial, split = run(tmp_path, mode, None), run(tmp_path, mode, processes)
    assert len(split["positions"]) == 10
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert split["cells"] == serial["cells"] and split["stress"] == serial["stress"]
    assert split["history"] == serial["history"]             # what PeriTriaxController read (triax)
    # The cell deformed (shrunk; sheared by velGrad), and spheres crossed its faces: their
    # unwrapped positions lie outside it, and they changed process on the way.
    cells, last = np.asarray(serial["cells"]), np.asarray(serial["positions"][-1])
    assert np.linalg.det(cells[-1]) < 0.8 * np.linalg.det(cells[0])
    assert mode == "triax" or cells[-1][0, 2] > 0.3
    assert (np.floor(np.linalg.solve(cells[-1], last.T).T) != 0).any(axis=1).sum() >= 5
    assert all(t["migrated_bodies"] > 0 for t in split["traffic"])
    assert -serial["stress"][0][0] > 1e3                   # compacted: the spheres touch


def test_hsfc_regions_in_the_reduced_coordinates_too(tmp_path):
    serial = run(tmp_path, "shear", None)
    split = run(tmp_path, "shear", 3, env={"TALUS_PARTITION": "HSFC"})
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert split["cells"] == serial["cells"] and split["stress"] == serial["stress"]


_serial_floors = {}


def floor_run(tmp_path, floor, cell, processes):
    path = tmp_path / f"{floor}-{cell}-{processes or 1}.json"
    done = talus_run(SCENES / "periodic_floor.py", 300, 1000, path, floor, cell, processes=processes, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(path.read_text())


@pytest.mark.parametrize("processes", [2, 3])
@pytest.mark.parametrize("cell", ["fixed", "shear"])
@pytest.mark.parametrize("floor", ["wall", "facet", "box"])
def test_a_floor_in_a_periodic_cell_gives_the_serial_run(tmp_path, floor, cell, processes):
    if (floor, cell) not in _serial_floors:                # one serial run for both process counts
        _serial_floors[floor, cell] = floor_run(tmp_path, floor, cell, None)
    serial, split = _serial_floors[floor, cell], floor_run(tmp_path, floor, cell, processes)
    assert len(split["positions"]) == 10
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    assert split["cells"] == serial["cells"]
    # Every process re-detected at the serial steps, no more.
    assert [t["rebuilds"] for t in split["traffic"]] == [serial["rebuilds"]] * processes
    # The spheres reached the floor (settling, it carries over a third of their weight, 0.7 kg
    # each), its force summed over the processes within round-off of the serial sum.
    assert -serial["floor_force"][2] > 300 * 0.7 * 9.81 / 3
    assert split["floor_force"] == pytest.approx(serial["floor_force"], rel=1e-12, abs=1e-9)
    if cell == "shear":
        # The cell sheared and the spheres carried along x crossed its faces, changing process.
        cells, last = np.asarray(serial["cells"]), np.asarray(serial["positions"][-1])
        assert cells[-1][0, 2] > 1.0
        assert (np.floor(np.linalg.solve(cells[-1], last[:300].T).T[:, 0]) != 0).sum() >= 5
        assert all(t["migrated_bodies"] > 0 for t in split["traffic"])


def _periodic_script(tmp_path, body):
    script = tmp_path / "script.py"
    script.write_text(
        "from yade import pack\n"
        "O.periodic = True\n"
        "O.cell.hSize = Matrix3(1, 0, 0, 0, 1, 0, 0, 0, 1)\n"
        "O.materials.append(FrictMat(young=1e7, density=2600))\n"
        "cloud = pack.SpherePack()\n"
        "cloud.makeCloud((0, 0, 0), (1, 1, 1), rMean=0.05, periodic=True, num=100, seed=1)\n"
        "cloud.toSimulation()\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],\n"
        "                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator()]\n"
        "O.dt = 1e-5\n" + body)
    return script


def test_a_cell_changed_on_one_process_only_stops_every_process(tmp_path):
    body = ("from talus.dem import distributed\n"
            "O.run(10, True)\n"
            "if distributed.rank() == 1:\n"
            "    O.cell.hSize = Matrix3(1.01, 0, 0, 0, 1, 0, 0, 0, 1)\n"
            "O.run(10, True)\n")
    done = talus_run(_periodic_script(tmp_path, body), processes=2)
    assert done.returncode != 0
    assert done.stderr.count("the periodic cell (O.cell.hSize) differs between the processes") == 1, done.stderr


def test_a_cell_resized_by_the_script_goes_on_as_in_one_process(tmp_path):
    # O.cell.hSize set between two runs moves no body: not a motion beyond the ghost layer
    body = ("import json, sys\n"
            "from talus.dem import distributed\n"
            "O.run(10, True)\n"
            "O.cell.hSize = Matrix3(1.3, 0, 0, 0, 1, 0, 0, 0, 0.8)\n"
            "O.run(10, True)\n"
            "p = distributed.positions().tolist()\n"
            "if distributed.rank() == 0:\n"
            "    json.dump(p, open(sys.argv[1], 'w'))\n")
    script, out = _periodic_script(tmp_path, body), {}
    for n in (None, 2):
        path = tmp_path / f"{n}.json"
        done = talus_run(script, path, processes=n)
        assert done.returncode == 0, done.stderr
        out[n] = json.loads(path.read_text())
    assert out[None] == out[2]
