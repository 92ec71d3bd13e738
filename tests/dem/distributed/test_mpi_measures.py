"""What a script measures under `mpirun -np N talus run` is the whole scene's, as in one process:
O.energy (every term, each body and contact counted once; within round-off, the processes' shares
being added in another order), getStress, getStressAndTangent (both forms), bodyStressTensors,
avgNumInteractions, fabricTensor, porosity, aabbExtrema, PWaveTimeStep, the step
GlobalStiffnessTimeStepper sets, and O.bodies.gather (collective). The scene: spheres settling
in a box whose side wall moves in (imposed work), some spheres with a blocked DOF moved by the
script along it."""

import json

import numpy as np
import pytest

from test_mpi_run import json_of_runs, pytestmark, talus_run  # noqa: F401  (the same skip: mpi_dem feature and mpirun)


SCRIPT = """
import json, math, sys
import numpy as np
from yade import pack
from talus.dem import distributed
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (1, 1, 1.5), rMean=0.04, rRelFuzz=0.3, num=300, seed=1)
cloud.toSimulation()
for axis in range(3):
    O.bodies.append(utils.wall(0, axis=axis, sense=1))
    if axis < 2:
        O.bodies.append(utils.wall(1, axis=axis, sense=-1))
energies = []
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                             [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             GlobalStiffnessTimeStepper(timeStepUpdateInterval=50, timestepSafetyCoefficient=0.5),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
             PyRunner(command='energies.append(dict(O.energy))', iterPeriod=100),
             PyRunner(command='drive()', iterPeriod=1)]


def drive():  # the spheres blocked along x move as the script says, at a speed changing every step
    for k in range(0, 300, 7):
        v = O.bodies[k].state.vel
        O.bodies[k].state.vel = (0.02 * math.sin(300 * O.time + k), v[1], v[2])



O.dt = 0.7 * PWaveTimeStep()
O.trackEnergy = True
O.bodies[301].state.vel = (-0.05, 0, 0)      # the side wall at x = 1 moves in
for k in range(0, 300, 7):
    O.bodies[k].state.blockedDOFs = "x"
O.run(600, True)
stress, tangent = getStressAndTangent(volume=1.5)
gathered = O.bodies.gather([0, 299, 150, 302, -1, 7])
out = {"energy": energies, "total": O.energy.total(), "dt": O.dt, "pwave": PWaveTimeStep(),
       "stress": np.asarray(getStress(1.5)).tolist(), "tangent": np.asarray(tangent).tolist(),
       "yade": np.asarray(getStressAndTangent(1.5, form="yade")[1]).tolist(),
       "bodyStress": [np.asarray(m).tolist() for m in bodyStressTensors()],
       "coordination": avgNumInteractions(), "fabric": np.asarray(fabricTensor()).tolist(), "porosity": porosity(),
       "aabb": np.asarray(aabbExtrema()).tolist(), "centres": np.asarray(aabbExtrema(0.1, True)).tolist(),
       "gather": [[b.id, b.dynamic, b.radius, *b.state.pos, *b.state.vel, *b.state.angVel, b.state.ori.w,
                   b.state.ori.x, b.state.ori.y, b.state.ori.z, b.state.mass, *b.state.inertia] for b in gathered],
       "positions": distributed.positions().tolist()}
errors = []
for call in (lambda: O.bodies.gather([distributed.rank()]), lambda: O.saveTmp(),
             lambda: O.bodies.gather([5, 1000])):
    try:
        call()
        errors.append(None)
    except (RuntimeError, IndexError) as e:
        errors.append(str(e))
out["errors"] = errors
if distributed.rank() == 0:
    open(sys.argv[1], "w").write(json.dumps(out))
"""

EXACT = ("dt", "pwave", "bodyStress", "aabb", "centres", "gather", "positions")
SUMS = ("stress", "tangent", "yade", "coordination", "fabric", "porosity")


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("measures")
    out = json_of_runs(folder, "measures", SCRIPT)
    # HSFC partitions again at every re-detection, weighted by the measured loads: bodies land on
    # processes that held no copy of them, and their energy memory (the blocked DOFs' last
    # motion) must go with them.
    done = talus_run(folder / "measures.py", folder / "hsfc.json", processes=3, env={"TALUS_PARTITION": "HSFC"},
                     timeout=60)
    assert done.returncode == 0, done.stderr
    out["3-HSFC"] = json.loads((folder / "hsfc.json").read_text())
    return out


@pytest.mark.parametrize("processes", [2, 3, "3-HSFC"])
def test_energy_is_the_serial_runs_within_round_off(runs, processes):
    serial, split = runs[None], runs[processes]
    assert len(serial["energy"]) == len(split["energy"]) == 5
    last = serial["energy"][-1]
    # every term is at work: gravity, damping, friction, the moving wall and the blocked DOFs
    assert all(abs(last[k]) > 1e-3 for k in ("kinetic", "elastPotential", "gravWork", "nonviscDamp",
                                             "plastDissip", "kinematicWork"))
    for a, b in zip(serial["energy"], split["energy"]):
        assert a.keys() == b.keys()
        flowed = sum(abs(v) for v in a.values())
        for key in a:
            assert b[key] == pytest.approx(a[key], rel=1e-13, abs=1e-14 * flowed), key
    assert split["total"] == pytest.approx(serial["total"], abs=1e-14 * sum(abs(v) for v in last.values()))


@pytest.mark.parametrize("processes", [2, 3])
def test_stresses_extrema_time_steps_and_gathered_bodies_are_the_serial_runs(runs, processes):
    serial, split = runs[None], runs[processes]
    for key in EXACT:     # per body, or extrema: the same numbers
        assert np.array_equal(np.asarray(serial[key], dtype=float), np.asarray(split[key], dtype=float)), key
    for key in SUMS:      # sums over contacts and bodies, the processes' shares added
        a, b = np.asarray(serial[key], dtype=float), np.asarray(split[key], dtype=float)
        assert np.allclose(b, a, rtol=1e-12, atol=1e-12 * np.abs(a).max()), key
    assert np.abs(serial["stress"]).max() > 1 and serial["coordination"] > 0
    assert sum(np.abs(m).max() > 0 for m in serial["bodyStress"]) > 10
    assert serial["dt"] != serial["pwave"] * 0.7          # the stepper set the step
    # The gathered bodies are the asked ones, in that order (-1: the last).
    assert [row[0] for row in split["gather"]] == [0, 299, 150, 302, 304, 7]


def test_a_gather_with_different_ids_and_what_is_not_distributed_are_refused_on_every_process(runs):
    # (each process caught its error and went on: every process raised it)
    assert runs[None]["errors"][:2] == [None, None]
    for processes in (2, 3):
        different, refused, missing = runs[processes]["errors"]
        assert "asked for different bodies" in different and "collective" in different
        assert "O.saveTmp" in refused and "not distributed yet" in refused
        assert "no body with id 1000" in missing and "no body with id 1000" in runs[None]["errors"][2]
