"""The Gauss-point calls over 2 MPI ranks (mpi4py) equal the single-process calls, alone and under
the FEniCSx driver."""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
MPI_ENV = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMP_NUM_THREADS": "1"}


def test_two_ranks_equal_one_process(rve_file):
    pytest.importorskip("mpi4py")
    import talus
    env = {**MPI_ENV, "PYTHONPATH": str(Path(talus.__file__).resolve().parent.parent)}
    done = subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2", sys.executable,
                           HERE / "mpi_rves.py", rve_file[0]], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert re.findall(r"^points (.*)$", done.stdout, re.MULTILINE) == ["3 2"]   # the RVEs stay on their ranks
    assert float(re.findall(r"^err (\S+)$", done.stdout, re.MULTILINE)[0]) < 1e-12
    assert "errors ['', \"Gauss point 4: RVE file '/nonexistent/rve.h5' does not exist\"]" in done.stdout


def test_fenicsx_driver_with_rves_on_two_ranks(rve_file):
    pytest.importorskip("mpi4py")
    pytest.importorskip("dolfinx")
    import talus
    env = {**MPI_ENV, "PYTHONPATH": str(Path(talus.__file__).resolve().parent.parent)}
    done = subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2", sys.executable,
                           HERE / "mpi_fenicsx.py", rve_file[0]], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert float(re.findall(r"^err (\S+)$", done.stdout, re.MULTILINE)[0]) < 1e-12
