"""Clumps, boxes and the engines reading the summed force of a wall under mpirun, each against
the serial run of the same script at 2 and 3 processes (oversubscribed on this machine): a clump
and its members owned by one process and moved whole, boxes and walls held by every process, a
TriaxialStressController moving the walls of a box by the force on each (summed exactly over
the processes), the measurements that sum over bodies; and what stays refused by name."""
import json
from pathlib import Path

import numpy as np
import pytest

from test_mpi_run import pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)
from test_mpi_scope import serial_and_split

SCENES = Path(__file__).resolve().parents[3] / "cases" / "scenes"


@pytest.mark.parametrize("processes", [2, 3])
def test_clumps_falling_onto_a_box_give_the_serial_positions(tmp_path, processes):
    serial, split = serial_and_split(tmp_path, SCENES / "clump_deposition.py", 200, 1000, processes=processes)
    # every body (clumps, their members, free spheres) at every 100 steps, bit for bit
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    # the clumps fell onto the floor and the box, whose forces are summed over the processes
    assert split["floor_force"][2] == pytest.approx(serial["floor_force"][2], rel=1e-12) and serial["floor_force"][2] < 0
    assert split["box_force"][2] == pytest.approx(serial["box_force"][2], rel=1e-12) and serial["box_force"][2] < 0
    # a clump counted once with its members (not each member again)
    assert split["kinetic"] == pytest.approx(serial["kinetic"], rel=1e-12)
    assert split["unbalanced"] == pytest.approx(serial["unbalanced"], rel=1e-12)
    # the energy terms (a clump's kinetic energy with its inertia, the gravity's work on it, ...)
    largest = max(abs(v) for v in serial["energy"].values())
    assert all(abs(split["energy"][k] - v) <= 1e-12 * largest for k, v in serial["energy"].items())
    assert serial["energy"]["gravWork"] < 0 and serial["energy"]["plastDissip"] > 0
    # bodies (clumps with their members) changed process on the way down
    assert sum(t["migrated_bodies"] for t in split["traffic"]) > 0


@pytest.mark.parametrize("processes", [2, 3])
def test_a_triaxial_compaction_in_a_box_of_walls_gives_the_serial_positions(tmp_path, processes):
    serial, split = serial_and_split(tmp_path, SCENES / "triax_box.py", 300, 1000, processes=processes)
    assert np.array_equal(np.asarray(serial["positions"]), np.asarray(split["positions"]))
    # the walls' stresses, the porosity and the mean stress the controller read: the same bits
    assert split["stress"] == serial["stress"] and split["porosity"] == serial["porosity"]
    assert split["meanStress"] == serial["meanStress"] and serial["meanStress"] == pytest.approx(-20000, rel=0.01)
    assert split["dt"] == serial["dt"]


CLUMPS = ("O.materials.append(FrictMat(young=1e7, density=2600))\n"
          "for k in range(12):\n"
          "    O.bodies.appendClumped([utils.sphere((0.2 * k, 0, 0), 0.04), utils.sphere((0.2 * k + 0.05, 0, 0), 0.03)])\n"
          "O.bodies.append(utils.wall(-0.0399, axis=2, sense=1))\n"   # touching the larger members
          "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),\n"
          "             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],\n"
          "                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),\n"
          "             NewtonIntegrator(gravity=(0, 0, -9.81))]\n"
          "O.dt = 1e-5\n")


def _run(tmp_path, body, processes=2):
    script = tmp_path / "script.py"
    script.write_text(CLUMPS + body)
    return talus_run(script, processes=processes)


def test_a_clump_read_on_its_owner_names_its_members_by_their_ids(tmp_path):
    # Clump k is body 3k + 2 with members 3k and 3k + 1: under mpirun its shape and its members'
    # clumpId give the ids the script built (not the process's rows).
    body = ("O.run(10, True)\n"
            "seen = 0\n"
            "for k in range(12):\n"      # read by id on every process: a snapshot where not owned
            "    c, member, other = O.bodies[3 * k + 2], O.bodies[3 * k], O.bodies[3 * k + 1]\n"
            "    assert member.clumpId == 3 * k + 2 and other.isClumpMember and c.isClump\n"
            "    if type(c).__name__ == 'RemoteBody':\n"
            "        continue\n"
            "    assert sorted(c.shape.members) == [3 * k, 3 * k + 1], (k, c.shape.members)\n"
            "    seen += 1\n"
            "from talus.dem import distributed\n"
            "import sys\n"
            "sys.stderr.write('SEEN %d\\n' % seen)\n")
    done = _run(tmp_path, body)
    assert done.returncode == 0, done.stderr
    seen = [int(line.split()[1]) for line in done.stderr.splitlines() if line.startswith("SEEN ")]
    assert sorted(seen) == sorted(seen) and sum(seen) == 12 and min(seen) > 0


def test_the_measurements_over_bodies_are_the_whole_scenes(tmp_path):
    # momentum, angular momentum, the spheres' volume and mass, sumForces on the wall, the body
    # with the most kinetic energy and totalForceInVolume: the serial run's on every process
    # (within round-off)
    body = ("O.run(20, True)\n"     # the clumps still on the wall
            "import json, sys\n"
            "from talus.dem import distributed\n"
            "values = {'momentum': list(utils.momentum()), 'angular': list(utils.angularMomentum((0.1, 0.2, 0))),\n"
            "          'volume': utils.getSpheresVolume(), 'mass': utils.getSpheresMass(),\n"
            "          'wall': utils.sumForces([36], (0, 0, 1)), 'kinetic': list(utils.kineticEnergy(findMaxId=True)),\n"
            "          'inVolume': [*utils.totalForceInVolume()[0], utils.totalForceInVolume()[1]]}\n"
            "if distributed.rank() == 0:\n"
            "    open(sys.argv[1], 'w').write(json.dumps(values))\n")
    script = tmp_path / "script.py"
    script.write_text(CLUMPS + "O.bodies.append(utils.sphere((0.3, 0.1, 0.3), 0.05))\n" + body)
    out = {}
    for processes in (None, 2):
        done = talus_run(script, tmp_path / f"values-{processes}.json", processes=processes)
        assert done.returncode == 0, done.stderr
        out[processes] = json.loads((tmp_path / f"values-{processes}.json").read_text())
    serial, split = out[None], out[2]
    for key in ("momentum", "angular", "inVolume"):
        assert np.allclose(split[key], serial[key], rtol=1e-12, atol=1e-14 * np.abs(serial[key]).max()), key
    for key in ("volume", "mass", "wall"):
        assert split[key] == pytest.approx(serial[key], rel=1e-12) and serial[key] != 0, key
    assert split["kinetic"][0] == pytest.approx(serial["kinetic"][0], rel=1e-12)
    assert split["kinetic"][1] == serial["kinetic"][1] >= 0


@pytest.mark.parametrize("processes", [2, 3])
def test_clumps_and_members_erased_as_in_one_process(tmp_path, processes):
    # Yade's rules: a clump erased frees its members, or erases them with eraseClumpMembers; a
    # member erased leaves its clump, which keeps its mass and goes with its last member. Every
    # process erases alike, whichever holds the clump (owned, a ghost, or not at all).
    body = ("import json, sys\n"
            "import numpy as np\n"
            "from talus.dem import distributed\n"
            "O.run(10, True)\n"
            "mass = O.bodies.gather([11])[0].state.mass\n"
            "done = [O.bodies.erase(2), O.bodies.erase(3), O.bodies.erase(4), O.bodies.erase(5),\n"
            "        O.bodies.erase(8, eraseClumpMembers=True), O.bodies.erase(9), O.bodies.erase(6)]\n"
            "samples = []\n"
            "for k in range(3):\n"
            "    O.run(100, True)\n"
            "    p = distributed.positions()\n"
            "    p[[2, 3, 4, 5, 6, 7, 8, 9]] = np.nan\n"
            "    samples.append(p.tolist())\n"
            "checked = 0\n"      # on the process owning each body: members freed, a clump left with one
            "for i in (0, 1, 11):\n"
            "    b = O.bodies[i]\n"
            "    if type(b).__name__ == 'RemoteBody':\n"
            "        continue\n"
            "    if i < 2:\n"
            "        assert b.clumpId == -1 and not b.isClumpMember, (i, b.clumpId)\n"
            "    else:\n"
            "        assert list(b.shape.members) == [10] and b.state.mass == mass, (b.shape.members, b.state.mass)\n"
            "    checked += 1\n"
            "checked = sum(p['checked'] for p in distributed.per_process({'checked': checked}))\n"
            "values = {'done': done, 'positions': samples, 'checked': checked, 'count': len(O.bodies)}\n"
            "if distributed.rank() == 0:\n"
            "    open(sys.argv[1], 'w').write(json.dumps(values))\n")
    script = tmp_path / "script.py"
    script.write_text(CLUMPS + body)
    out = {}
    for n in (None, processes):
        done = talus_run(script, tmp_path / f"values-{n}.json", processes=n)
        assert done.returncode == 0, done.stderr
        out[n] = json.loads((tmp_path / f"values-{n}.json").read_text())
    serial, split = out[None], out[processes]
    assert serial["done"] == split["done"] == [True, True, True, False, True, True, False]
    assert np.array_equal(np.asarray(serial["positions"], float), np.asarray(split["positions"], float), equal_nan=True)
    assert serial["count"] == split["count"] == 37 and serial["checked"] == split["checked"] == 3


@pytest.mark.parametrize("body, named", [
    ("O.bodies.append(utils.box((0, 0, -2), (1, 1, 0.1)))\nO.run(10, True)\n", "Box moved by forces"),
    ("O.run(10, True)\nO.bodies.clump([5, 8])\n", "O.bodies.clump after the scene was split"),
    ("O.run(10, True)\nO.bodies.releaseFromClump(0, 2)\n", "O.bodies.releaseFromClump after the scene was split"),
])
def test_what_is_not_distributed_with_clumps_and_boxes_is_refused_by_name_once(tmp_path, body, named):
    done = _run(tmp_path, body)
    assert done.returncode != 0
    assert done.stderr.count(named) == 1, done.stderr      # reported by process 0 only
    assert "in one process" in done.stderr, done.stderr


def test_a_servo_controlled_plate_of_facets_moves_as_in_one_process(tmp_path):
    # Yade's PIDController.py, small (the plate starting lower, to press within the run): a plate
    # of two facets pressed down on a layer of spheres by a ServoPIDController (the plate's force
    # summed exactly over the processes), turning.
    script = tmp_path / "servo.py"
    script.write_text(
        "import json, sys\n"
        "from talus.dem import distributed\n"
        "mat = O.materials.append(ViscElMat(frictionAngle=0.3, density=2000, tc=1e-3, en=0.3, et=0.3))\n"
        "O.bodies.append([facet([(-1, -1, 0), (1, -1, 0), (1, 1, 0)], material=mat),\n"
        "                 facet([(-1, -1, 0), (1, 1, 0), (-1, 1, 0)], material=mat)])\n"
        "plate = O.bodies.append([facet([(-1, -1, 0.201), (1, -1, 0.201), (1, 1, 0.201)], material=mat),\n"
        "                         facet([(-1, -1, 0.201), (1, 1, 0.201), (-1, 1, 0.201)], material=mat)])\n"
        "O.bodies.append([sphere((0.3 * i - 0.6, 0.3 * j - 0.6, 0.1), 0.1, material=mat) for i in range(5) for j in range(5)])\n"
        "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),\n"
        "    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],\n"
        "                    [Law2_ScGeom_ViscElPhys_Basic()]),\n"
        "    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),\n"
        "    ServoPIDController(axis=(0, 0, 1), maxVelocity=0.5, iterPeriod=20, ids=plate, target=2e4, kP=1e-5, kI=2e-6,\n"
        "                       kD=1e-6, label='servo')\n"
        "    + RotationEngine(rotationAxis=(0, 0, 1), angularVelocity=0.5, rotateAroundZero=True, zeroPoint=(0, 0, 0))]\n"
        "O.dt = 2e-5\n"
        "O.run(3000, True)\n"
        "result = {'positions': distributed.positions().tolist(), 'current': list(servo.current), 'vel': servo.curVel}\n"
        "if distributed.rank() == 0:\n"
        "    open(sys.argv[1], 'w').write(json.dumps(result))\n")
    out = {}
    for processes in (None, 2):
        done = talus_run(script, tmp_path / f"servo-{processes}.json", processes=processes)
        assert done.returncode == 0, done.stderr
        out[processes] = json.loads((tmp_path / f"servo-{processes}.json").read_text())
    assert out[2] == out[None] and out[None]["current"][2] != 0     # the plate pressed on the spheres, bit for bit


def test_yades_triaxial_test_moves_its_walls_as_in_one_process(tmp_path):
    # Yade's TriaxialTest preprocessor (walls, GlobalStiffnessTimeStepper, a
    # TriaxialCompressionEngine compacting isotropically, then loading at a strain rate once the
    # packing is stable), a seeded cloud (radiusMean: the cloud that takes the seed)
    script = tmp_path / "triaxial_test.py"
    script.write_text(
        "import json, sys\n"
        "from talus.dem import distributed\n"
        "TriaxialTest(numberOfGrains=400, noFiles=True, sigmaIsoCompaction=-60e3, sigmaLateralConfinement=-60e3,\n"
        "             StabilityCriterion=0.05, seed=3, radiusMean=0.04).load()\n"
        "triax = O.engines[4]\n"
        "states = []\n"
        "O.engines = O.engines + [PyRunner(command='states.append(triax.currentState)', iterPeriod=100)]\n"
        "O.run(3000, True)\n"
        "out = {'positions': distributed.positions().tolist(), 'states': states, 'strain': list(triax.strain),\n"
        "       'stress': [list(triax.stress(k)) for k in range(6)], 'dt': O.dt}\n"
        "if distributed.rank() == 0:\n"
        "    open(sys.argv[1], 'w').write(json.dumps(out))\n")
    out = {}
    for processes in (None, 2):
        done = talus_run(script, tmp_path / f"triaxial-{processes}.json", processes=processes, timeout=300)
        assert done.returncode == 0, done.stderr
        out[processes] = json.loads((tmp_path / f"triaxial-{processes}.json").read_text())
    assert out[2] == out[None]                         # positions, walls' stresses, strain, time step: the same bits
    states = out[None]["states"]
    assert states[0] == 1 and states[-1] == 3          # isotropic compaction, then the loading
    assert out[None]["strain"][1] < -0.01              # the top and bottom walls moved in


def test_a_scene_that_differs_between_the_processes_is_refused_naming_the_seed(tmp_path):
    # random numbers drawn without a seed make another packing on each process: the split would
    # mix them (makeCloud without a seed draws one cloud for all: test_mpi_periodic_controllers.py)
    script = tmp_path / "unseeded.py"
    script.write_text("import random\n"
                      "for k in range(100):\n"
                      "    O.bodies.append(sphere((random.random(), random.random(), random.random()), 0.02))\n"
                      "O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]), NewtonIntegrator()]\n"
                      "O.dt = 1e-5\n"
                      "O.run(10, True)\n")
    done = talus_run(script, processes=2)
    assert done.returncode != 0
    assert done.stderr.count("the scene differs between the processes") == 1 and "seed" in done.stderr, done.stderr
