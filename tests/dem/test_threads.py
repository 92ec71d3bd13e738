"""Results do not depend on the number of OpenMP threads: bit-identical states after a
contact-rich deposition run with 1 and 2 threads (forces are summed per body in a fixed order)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

import talus

SCRIPT = Path(__file__).with_name("deposition_hash.py")


def run(threads, build_dir):
    env = {**os.environ, "OMP_NUM_THREADS": str(threads), "PYTHONPATH": str(build_dir / "python")}
    done = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    lines = dict(line.split(" ", 1) for line in done.stdout.strip().splitlines())
    return int(lines["contacts"]), lines["hash"]


@pytest.mark.skipif(not talus.build_info()["features"]["openmp"][0], reason="built without OpenMP")
def test_one_and_two_threads_give_identical_states(build_dir):
    contacts1, hash1 = run(1, build_dir)
    contacts2, hash2 = run(2, build_dir)
    assert contacts1 > 500          # the run really was contact-dominated
    assert (contacts1, hash1) == (contacts2, hash2)
