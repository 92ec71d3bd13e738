"""Results do not depend on the number of OpenMP threads, nor on whether the usual engines run
fused in one parallel region (FusedStep) or one by one: bit-identical states after a
contact-rich deposition run (forces are summed per body in a fixed order)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

import talus

SCRIPT = Path(__file__).with_name("deposition_hash.py")
PERIODIC = Path(__file__).with_name("periodic_compression_hash.py")
STEPS = 3000


def run(threads, build_dir, *options, script=SCRIPT):
    env = {**os.environ, "OMP_NUM_THREADS": str(threads), "PYTHONPATH": str(build_dir / "python")}
    arguments = [str(STEPS)] if script == SCRIPT else []
    done = subprocess.run([sys.executable, str(script), *arguments, *options], capture_output=True, text=True,
                          env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    lines = dict(line.split(" ", 1) for line in done.stdout.strip().splitlines())
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
def test_fused_step_equals_the_engines_one_by_one_in_a_deforming_periodic_cell(build_dir):
    """The periodic gather (images across the boundary), the skin check against the cell's
    affine map and the cell's own motion, fused and one by one."""
    contacts_fused, hash_fused, fused = run(2, build_dir, script=PERIODIC)
    contacts_engines, hash_engines, fused_engines = run(2, build_dir, "--engines-one-by-one", script=PERIODIC)
    assert (fused, fused_engines) == (2000, 0)
    assert contacts_fused > 1000
    assert (contacts_fused, hash_fused) == (contacts_engines, hash_engines)
