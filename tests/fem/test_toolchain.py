"""The finite element stacks fem/ drives work on this machine: dolfinx (serial and 2 MPI ranks)
and escript both solve a Poisson problem whose P2 solution is exact."""
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

import talus

HERE = Path(__file__).parent
MPI_ENV = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def nodal_error(cmd, tmp_path):
    done = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path, env=MPI_ENV, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    return float(re.findall(r"^err (\S+)$", done.stdout, re.MULTILINE)[-1])


needs_fenicsx = pytest.mark.skipif(not talus.build_info()["features"].get("fenicsx", (False,))[0],
                                   reason="this build has no FEniCSx (see `talus info`)")


@needs_fenicsx
def test_dolfinx_serial(tmp_path):
    assert nodal_error(["/usr/bin/python3", HERE / "poisson_dolfinx.py"], tmp_path) < 1e-12


@needs_fenicsx
def test_dolfinx_two_ranks(tmp_path):
    cmd = ["mpirun", "--oversubscribe", "-n", "2", "/usr/bin/python3", HERE / "poisson_dolfinx.py"]
    assert nodal_error(cmd, tmp_path) < 1e-12


@pytest.mark.skipif(shutil.which("run-escript") is None, reason="escript is not installed")
def test_escript(tmp_path):
    # escript's default iterative solver stops at a relative tolerance of 1e-8.
    assert nodal_error(["run-escript", HERE / "poisson_escript.py"], tmp_path) < 1e-7
