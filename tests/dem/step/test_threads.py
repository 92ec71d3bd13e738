"""Results do not depend on the number of OpenMP threads, nor on whether the usual engines run
as the scheduler's shared stages (dem/step/Scheduler) or one by one (Yade's sub-steps: each
engine's own run()), nor on timing: bit-identical states after a contact-rich deposition run
(forces are summed per body in a fixed order)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

import talus

SCRIPT = Path(__file__).with_name("deposition_hash.py")
PERIODIC = Path(__file__).with_name("periodic_compression_hash.py")
STEPS = 3000


def outputs(threads, build_dir, *options, script=SCRIPT):
    """The script's printed lines, as a dict."""
    env = {**os.environ, "OMP_NUM_THREADS": str(threads), "PYTHONPATH": str(build_dir / "python")}
    arguments = [str(STEPS)] if script == SCRIPT else []
    done = subprocess.run([sys.executable, str(script), *arguments, *options], capture_output=True, text=True,
                          env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    return dict(line.split(" ", 1) for line in done.stdout.strip().splitlines())


def run(threads, build_dir, *options, script=SCRIPT):
    lines = outputs(threads, build_dir, *options, script=script)
    return int(lines["contacts"]), lines["hash"], int(lines["fused"])


needs_openmp = pytest.mark.skipif(not talus.build_info()["features"]["openmp"][0], reason="built without OpenMP")


@needs_openmp
def test_one_and_two_threads_give_identical_states(build_dir):
    contacts1, hash1, fused1 = run(1, build_dir)
    contacts2, hash2, fused2 = run(2, build_dir)
    assert contacts1 > 500          # the run really was contact-dominated
    assert fused1 == fused2 == STEPS  # the usual engines ran fused
    assert (contacts1, hash1) == (contacts2, hash2)


@needs_openmp
@pytest.mark.parametrize("clumps", [False, True], ids=["spheres", "clumps"])
def test_fused_step_equals_the_engines_one_by_one(build_dir, clumps):
    extra = ["--clumps"] if clumps else []
    contacts_fused, hash_fused, fused = run(2, build_dir, *extra)
    contacts_engines, hash_engines, fused_engines = run(2, build_dir, "--engines-one-by-one", *extra)
    assert (fused, fused_engines) == (STEPS, 0)
    assert contacts_fused > 300     # contact-rich in both variants (433 with clumps)
    assert (contacts_fused, hash_fused) == (contacts_engines, hash_engines)


@needs_openmp
def test_timing_keeps_the_shared_stages_and_the_bits(build_dir):
    """O.timingEnabled times the scheduler's stages without changing how the step runs."""
    timed = outputs(2, build_dir, "--timing", "--other-engines")
    plain = outputs(2, build_dir, "--other-engines")
    assert int(timed["fused"]) == int(plain["fused"]) == STEPS
    assert (timed["contacts"], timed["hash"]) == (plain["contacts"], plain["hash"])


@needs_openmp
def test_other_engines_run_in_their_place_around_the_fused_step(build_dir):
    """A PyRunner before the usual engines, a GravityEngine between the loop and the integrator
    and a PyRunner after them that moves a sphere between steps: still fused (the integration in
    a region after the GravityEngine, the skin checked in the step), and the same bits as the
    engines one by one."""
    fused = outputs(2, build_dir, "--other-engines")
    engines = outputs(2, build_dir, "--other-engines", "--engines-one-by-one")
    assert (int(fused["fused"]), int(engines["fused"])) == (STEPS, 0)
    assert int(fused["contacts"]) > 500
    assert (fused["contacts"], fused["hash"]) == (engines["contacts"], engines["hash"])


@needs_openmp
@pytest.mark.parametrize("extra", [[], ["--clumps"], ["--other-engines"]], ids=["spheres", "clumps", "other-engines"])
def test_fused_step_tracks_energy_as_the_engines_do(build_dir, extra):
    """O.trackEnergy: still fused, and every energy term (summed per block of 256 contacts or
    bodies whoever computes them) the same bits as the engines one by one and as one thread."""
    fused = outputs(2, build_dir, "--energy", *extra)
    engines = outputs(2, build_dir, "--energy", "--engines-one-by-one", *extra)
    one_thread = outputs(1, build_dir, "--energy", *extra)
    assert (int(fused["fused"]), int(engines["fused"])) == (STEPS, 0)
    assert "plastDissip=0.0 " not in fused["energy"] and "nonviscDamp=0.0 " not in fused["energy"]
    for other in (engines, one_thread):
        assert (fused["hash"], fused["energy"]) == (other["hash"], other["energy"])


@needs_openmp
def test_fused_step_goes_on_past_a_counted_overlap(build_dir):
    """With O.overlapStops off an overlap beyond maxOverlapRatio is counted and the step goes
    on: the fused step integrates the bodies as the engines do."""
    fused = outputs(2, build_dir, "--overlap-counts")
    engines = outputs(2, build_dir, "--overlap-counts", "--engines-one-by-one")
    assert int(fused["fused"]) == STEPS and int(fused["overlapSteps"]) > 0
    assert (fused["overlapSteps"], fused["hash"]) == (engines["overlapSteps"], engines["hash"])


@pytest.mark.parametrize("extra", [[], ["--clumps"], ["--moving-wall"], ["--lifted"]],
                         ids=["spheres", "clumps", "moving-wall", "falling-onto-the-floor"])
def test_skin_check_misses_no_contact(build_dir, extra):
    """The collider re-detects only when displacements could bring a new pair into contact:
    the spheres falling together at first need none (the skin check subtracts their common
    displacement) until the floor is within the skin, and a wall that moves shares the skin
    with the spheres. The same run
    re-detecting at every step (verletDist 0) gives the same bits, so no contact came late."""
    skin = outputs(2, build_dir, *extra)
    every_step = outputs(2, build_dir, "--verlet=0", *extra)
    assert int(every_step["rebuilds"]) > 0.9 * STEPS
    assert int(skin["rebuilds"]) < 0.05 * STEPS
    assert (skin["contacts"], skin["hash"]) == (every_step["contacts"], every_step["hash"])


@needs_openmp
def test_fused_step_equals_the_engines_one_by_one_in_a_deforming_periodic_cell(build_dir):
    """The periodic gather (images across the boundary), the skin check against the cell's
    affine map and the cell's own motion, fused and one by one."""
    contacts_fused, hash_fused, fused = run(2, build_dir, script=PERIODIC)
    contacts_engines, hash_engines, fused_engines = run(2, build_dir, "--engines-one-by-one", script=PERIODIC)
    assert (fused, fused_engines) == (2000, 0)
    assert contacts_fused > 1000
    assert (contacts_fused, hash_fused) == (contacts_engines, hash_engines)


@pytest.mark.parametrize("advance", ["run", "step"])
def test_fused_step_sees_bodies_moved_between_runs(advance):
    """The fused step checks the skin ahead, for the next step of the same run(): a body moved
    from Python between runs (or single steps) must still trigger a re-detection."""
    from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                           Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                           NewtonIntegrator, Scene, sphere)
    S = Scene()
    mat = S.materials.append(FrictMat(young=1e7, density=2600))
    # 32 x 32 spheres of radius 0.01, 0.05 apart: none within the skin of another
    ids = [S.bodies.append(sphere((0.05 * i, 0.05 * j, 0), 0.01, material=mat)) for i in range(32) for j in range(32)]
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.2, gravity=(0, 0, 0))]
    S.dt = 1e-6
    S.run(5, True)
    assert len(S.contacts()) == 0
    S.positions()[ids[0]] = S.positions()[ids[1]] + (0.019, 0, 0)   # onto its neighbour, overlapping by 5 %
    if advance == "run":
        S.run(1, True)
    else:
        S.step()
    assert S.fusedSteps == 6
    assert [(c["id1"], c["id2"]) for c in S.contacts()] == [(ids[0], ids[1])]


@pytest.mark.parametrize("place", ["before", "between", "after"])
def test_a_failing_pyrunner_around_the_fused_step_resumes_as_the_engines_do(place):
    """A PyRunner raising at steps 5 and 9, before the usual engines, between the loop and the
    integrator, or after them: each error reaches the caller, the next run finishes that step from
    the engine after the PyRunner, and the 20 steps end where the engines one by one end."""
    from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                           Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                           NewtonIntegrator, PyRunner, Scene, sphere, wall)
    import numpy as np

    def run(engines_one_by_one):
        S = Scene()
        mat = S.materials.append(FrictMat(young=1e7, density=2600))
        S.bodies.append([sphere((0.05 * i, 0.05 * j, 0.05 * k), 0.026, material=mat)
                         for i in range(12) for j in range(12) for k in range(8)])
        S.bodies.append(wall(-0.03, axis=2, sense=1))

        def fail_twice():
            if S.iter in (5, 9):
                raise RuntimeError("failing on purpose")

        failing = PyRunner(command=fail_twice, iterPeriod=1)
        engines = [ForceResetter(), InsertionSortCollider(),
                   InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                   NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2)]
        at = {"before": 0, "between": 3, "after": 4}[place]
        S.engines = engines[:at] + [failing] + engines[at:]
        S.dt = 1e-4
        S.subStepping = engines_one_by_one   # Yade's sub-steps: each engine's own run() in turn
        errors = 0
        while S.iter < 20:
            try:
                if engines_one_by_one:
                    S.step()
                else:
                    S.run(20 - S.iter, wait=True)
            except RuntimeError as e:
                assert "failing on purpose" in str(e)
                errors += 1
        return S, errors

    fused, fused_errors = run(False)
    engines, engine_errors = run(True)
    assert fused_errors == engine_errors == 2
    assert fused.fusedSteps >= 18 and engines.fusedSteps == 0
    assert np.array_equal(fused.positions(), engines.positions())
