"""Rebalancing under mpirun: the processes measure their compute time between re-detections, and
when the slowest's over the mean passes talus.dem.distributed.rebalanceThreshold, Zoltan
partitions again with each body weighted by its measured cost. The regions change, the positions
do not (the serial bits); timing.stats() reports every process's load and the rebalances; a
threshold below 1 is refused on every process."""
import json
from pathlib import Path

import numpy as np

from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)

SILO = Path(__file__).resolve().parents[3] / "cases" / "scenes" / "silo_discharge.py"


def silo(tmp_path, name, *options, processes=None):
    path = tmp_path / f"{name}.json"
    done = talus_run(SILO, 400, 1500, path, "side=6", *options, processes=processes, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(path.read_text())


def test_rebalancing_moves_the_regions_not_the_bodies(tmp_path):
    serial = silo(tmp_path, "serial")
    # A threshold of 1 rebalances at (nearly) every re-detection: the most the regions can move.
    always = silo(tmp_path, "always", "rebalance=1", processes=3)
    never = silo(tmp_path, "never", "rebalance=none", processes=3)
    for split in (always, never):
        assert np.array_equal(np.asarray(serial["positions"], float), np.asarray(split["positions"], float),
                              equal_nan=True)
        assert split["left"] == serial["left"]
    assert serial["left"][-1][1] < 400 - 50                          # the silo emptied on the way
    measured = always["balance"]["intervals"]
    assert len(measured) > 10 and all(steps > 0 and imbalance >= 1 for _, steps, imbalance, _ in measured)
    assert always["balance"]["rebalances"] == sum(rebalanced for *_, rebalanced in measured) > len(measured) // 2
    assert never["balance"]["rebalances"] == 0 and never["balance"]["threshold"] == float("inf")
    # The regions followed the spheres down: the process owning the top of the silo kept some of
    # them, while without rebalancing it lost most.
    spheres = [[p["spheres"] for p in run["balance"]["processes"]] for run in (always, never)]
    assert sum(spheres[0]) == sum(spheres[1]) == serial["left"][-1][1]
    assert max(spheres[0]) / np.mean(spheres[0]) < max(spheres[1]) / np.mean(spheres[1])
    # The fitted costs are positive; each process's compute seconds were counted.
    assert always["balance"]["per_body_seconds"] > 0 and always["balance"]["per_contact_seconds"] >= 0
    assert all(p["compute_seconds"] > 0 for p in always["balance"]["processes"])


def test_timing_stats_reports_every_process_load(tmp_path):
    script = tmp_path / "stats.py"
    script.write_text(
        "from talus.dem.analysis import timing\n"
        "O.materials.append(FrictMat(young=1e7, density=2600))\n"
        "for k in range(40):\n"
        "    O.bodies.append(utils.sphere((0.1 * (k % 10), 0.1 * (k // 10), 0), 0.04))\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],\n"
        "                             [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
        "O.dt = 1e-3\n"
        "O.timingEnabled = True\n"
        "O.run(300, True)\n"
        "timing.stats()\n")
    done = talus_run(script, processes=2)
    assert done.returncode == 0, done.stderr
    rows = [line.split() for line in done.stdout.splitlines()]
    load = [r for r in rows if len(r) == 5 and r[0] in ("0", "1") and r[4].endswith("us")]
    assert [r[0] for r in load] == ["0", "1"]                         # printed once, by process 0
    assert sum(int(r[1]) for r in load) == 40 and all(float(r[4][:-2]) > 0 for r in load)
    assert "rebalances: " in done.stdout and "(above 1.1)" in done.stdout
    # In one process: the engines' table alone.
    serial = talus_run(script)
    assert serial.returncode == 0 and "InteractionLoop" in serial.stdout and "rebalances" not in serial.stdout


def test_a_threshold_below_one_is_refused_on_every_process(tmp_path):
    script = tmp_path / "bad.py"
    script.write_text(
        "from talus.dem import distributed\n"
        "distributed.rebalanceThreshold = 0.9\n"
        "O.materials.append(FrictMat(young=1e7, density=2600))\n"
        "for k in range(10):\n"
        "    O.bodies.append(utils.sphere((0.1 * k, 0, 0), 0.04))\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],\n"
        "                             [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator()]\n"
        "O.dt = 1e-5\n"
        "O.run(5, True)\n")
    done = talus_run(script, processes=2)
    assert done.returncode != 0
    assert "rebalanceThreshold 0.9 is below 1" in done.stderr + done.stdout
