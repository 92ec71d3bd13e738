"""What runs distributed beyond spheres, walls and the linear law, each against the serial run of
the same script, bit for bit, at 2 and 3 processes (oversubscribed on this machine): the contact
laws with contact state (migrating with their contacts), facets held by every process and moved
by kinematic engines, gravity and force engines, and bodies erased as they leave a silo; and the
rule of O.bodies.erase under mpirun (every process erases the same bodies)."""
import json
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)

SCENES = Path(__file__).resolve().parents[3] / "cases" / "scenes"


def serial_and_split(tmp_path, scene, *args, processes):
    """The scene's JSON output in one process and under mpirun with `processes`."""
    out = {}
    for n in (None, processes):
        path = tmp_path / f"run-{n or 1}.json"
        done = talus_run(scene, *args[:2], path, *args[2:], processes=n)
        assert done.returncode == 0, done.stderr
        out[n or 1] = json.loads(path.read_text())
    return out[1], out[processes]


def same_sum(split, serial):
    """A force summed over the processes: each process's share in the serial order, the shares
    grouped as the partition has them, which rebalancing moves (round-off, not the same bits)."""
    return split == pytest.approx(serial, rel=1e-12)


def assert_same_positions(a, b):
    # NaN where a body was erased: the same bodies erased at the same samples
    assert np.array_equal(np.asarray(a["positions"], float), np.asarray(b["positions"], float), equal_nan=True)


@pytest.mark.parametrize("processes", [2, 3])
@pytest.mark.parametrize("law", ["hertz", "viscoelastic", "cohesive"])
def test_contact_laws_with_state_give_the_serial_positions(tmp_path, law, processes):
    serial, split = serial_and_split(tmp_path, SCENES / "deposition.py", 200, 1000, law, processes=processes)
    assert_same_positions(serial, split)
    assert same_sum(split["floor_force"], serial["floor_force"]) and serial["floor_force"] < 0
    # Spheres changed process with their contacts (and the contacts' state) on the way down.
    assert sum(t["migrated_contacts"] for t in split["traffic"]) > 0


@pytest.mark.parametrize("processes", [2, 3])
def test_a_silo_of_facets_erasing_the_spheres_that_leave(tmp_path, processes):
    serial, split = serial_and_split(tmp_path, SCENES / "silo_discharge.py", 400, 1000, processes=processes)
    assert_same_positions(serial, split)
    assert split["left"] == serial["left"] and serial["left"][-1][1] < 400 - 20   # spheres left through the orifice
    assert same_sum(split["floor_force"], serial["floor_force"]) and serial["floor_force"] < 0  # facets, processes


@pytest.mark.parametrize("processes", [2, 3])
def test_kinematic_gravity_and_force_engines_on_replicated_boundaries(tmp_path, processes):
    serial, split = serial_and_split(tmp_path, SCENES / "moving_boundaries.py", 300, 1000, processes=processes)
    assert_same_positions(serial, split)
    assert same_sum(split["floor_force"], serial["floor_force"]) and serial["floor_force"] < 0
    assert same_sum(split["pusher_force"], serial["pusher_force"]) and serial["pusher_force"] != 0
    # the paddle (the last two bodies) turned about the box's centre
    paddle = np.asarray(serial["positions"])[:, -2:, :2]
    assert np.abs(paddle[-1] - paddle[0]).max() > 0.05


def _cloud(tmp_path, body, before=""):
    script = tmp_path / "script.py"
    script.write_text(
        "from talus.dem import distributed\n"
        "O.materials.append(FrictMat(young=1e7, density=2600))\n"
        "for k in range(20):\n"
        "    O.bodies.append(utils.sphere((0.1 * k, 0, 0), 0.04))\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),\n"
        "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],\n"
        "                             [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
        "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
        "O.dt = 1e-5\n" + before +
        "O.run(10, True)\n" + body)
    return script


def test_an_erased_body_is_gone_on_every_process(tmp_path):
    # Every process erases body 3 (owned by one of them): then it reads as None everywhere (before
    # and after the next re-detection drops its rows), and a second erase says it was erased
    # already, on every process.
    body = ("first, again = O.bodies.erase(3), O.bodies.erase(3)\n"
            "before = O.bodies[3] is None\n"
            "O.run(10, True)\n"
            f"with open({str(tmp_path)!r} + '/result' + str(distributed.rank()), 'w') as out:\n"
            "    out.write(repr([first, again, before, O.bodies[3] is None, len(O.bodies)]))\n")
    done = talus_run(_cloud(tmp_path, body), processes=2)
    assert done.returncode == 0, done.stderr
    for rank in (0, 1):
        assert (tmp_path / f"result{rank}").read_text() == "[True, False, True, True, 20]"


def test_erasing_on_one_process_only_is_named_with_the_rule(tmp_path):
    body = "if distributed.rank() == 0:\n    O.bodies.erase(3)\nO.run(10, True)\n"
    done = talus_run(_cloud(tmp_path, body), processes=2)
    assert done.returncode != 0
    assert done.stderr.count("erased different bodies") == 1, done.stderr
    assert "same ids" in done.stderr, done.stderr


def test_a_force_engine_on_a_wall_is_refused_by_name(tmp_path):
    # Every process holds the wall: each would add the force, and the summed O.forces.f would
    # count it once per process.
    before = ("w = O.bodies.append(utils.wall(-1, axis=2, sense=1))\n"
              "O.engines = O.engines + [ForceEngine(force=(0, 0, 1), ids=[w])]\n")
    done = talus_run(_cloud(tmp_path, "", before), processes=2)
    assert done.returncode != 0
    assert done.stderr.count("ForceEngine on body 20, a Wall") == 1, done.stderr


def test_appending_a_body_after_the_split_is_refused_by_name(tmp_path):
    done = talus_run(_cloud(tmp_path, "O.bodies.append(utils.sphere((0, 0, 1), 0.04))\n"), processes=2)
    assert done.returncode != 0
    assert done.stderr.count("O.bodies.append after the scene was split (at its first step under mpirun) is not "
                             "distributed yet") == 1, done.stderr
