"""What the OpenFOAM coupling tests share: the build tree, the DEM driver, the MPI/OpenFOAM
environment, the skip mark for builds without the solvers, and the tiny 4 x 4 x 4 case."""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("TALUS_BUILD_DIR", REPO / "build")).resolve()
DRIVER = Path(__file__).with_name("foam_drag_driver.py")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", WM_PROJECT_DIR="/usr/share/openfoam",
           PYTHONPATH=str(BUILD / "python"))


def needs_solver(name: str):
    """Skip a test module when the coupling component or the solver ``name`` was not built."""
    return pytest.mark.skipif(
        not (BUILD / "bin" / name).exists() or not (BUILD / "python" / "talus" / "coupling").exists(),
        reason="coupling or foam-solvers component off (see the configure summary)")


def meshed_box(work: Path, procs: int = 1, files: dict[str, str] | None = None) -> Path:
    """Copy the tiny case to ``work``, add ``files`` (path relative to the case: text), mesh it
    and decompose it for ``procs`` > 1 fluid ranks."""
    shutil.copytree(Path(__file__).with_name("foam_box"), work)
    for name, text in (files or {}).items():
        (work / name).write_text(text)
    for tool in ["blockMesh"] + (["decomposePar"] if procs > 1 else []):
        subprocess.run([tool, "-case", str(work)], check=True, capture_output=True, env=ENV, timeout=60)
    return work
