"""foam-solvers: talusCaseInfo, built by wmake against Debian's OpenFOAM v1912, reads the stock
cavity case serially and decomposed over two MPI ranks and prints one JSON object on stdout."""
import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("TALUS_BUILD_DIR", REPO / "build")).resolve()
CASE_INFO = BUILD / "bin" / "talusCaseInfo"
CAVITY = "incompressible/icoFoam/cavity/cavity"
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}

pytestmark = pytest.mark.skipif(
    not CASE_INFO.exists(),
    reason=f"{CASE_INFO} not built (foam-solvers component off: see the configure summary)")


def openfoam_src():
    """The prepared OpenFOAM sources the build used (its CMake cache), else the default."""
    cache = BUILD / "CMakeCache.txt"
    if cache.exists():
        for line in cache.read_text().splitlines():
            if line.startswith("TALUS_OPENFOAM_SRC:"):
                return Path(line.split("=", 1)[1])
    return Path(os.environ.get("TALUS_OPENFOAM_SRC", "/opt/talus/openfoam-v1912"))


def cavity_tutorial():
    """The stock cavity case: Debian's openfoam-examples package, or the prepared sources."""
    for root in (Path("/usr/share/doc/openfoam-examples/examples"),
                 Path("/usr/share/openfoam/tutorials"), openfoam_src() / "tutorials"):
        if (root / CAVITY / "system" / "blockMeshDict").exists():
            return root / CAVITY
    pytest.skip("no cavity tutorial (apt-get install openfoam-examples, or prepare the sources)")


def foam(command, case):
    """Run a shell command in the case with Debian's OpenFOAM environment; returns stdout."""
    # The bashrc complains on stderr about helper scripts Debian does not ship: harmless.
    done = subprocess.run(["bash", "-c", f"source /usr/share/openfoam/etc/bashrc 2>/dev/null; {command}"],
                          cwd=case, capture_output=True, text=True, timeout=60,
                          env={**os.environ, **MPI_ENV})
    assert done.returncode == 0, f"{command} exited {done.returncode}:\n{done.stdout}\n{done.stderr}"
    return done.stdout


def check_cavity(info, n_procs):
    assert info["openfoam"] == "v1912"
    assert info["nCells"] == 400
    assert info["nPoints"] == 21 * 21 * 2
    lo, hi = info["bounds"]
    assert lo == pytest.approx([0, 0, 0]) and hi == pytest.approx([0.1, 0.1, 0.01])
    patches = {p["name"]: p for p in info["patches"]}
    assert set(patches) == {"movingWall", "fixedWalls", "frontAndBack"}
    assert patches["movingWall"]["type"] == "wall" and patches["movingWall"]["nFaces"] == 20
    assert patches["fixedWalls"]["nFaces"] == 60
    assert patches["frontAndBack"]["type"] == "empty" and patches["frontAndBack"]["nFaces"] == 800
    assert info["nProcs"] == n_procs


def test_cavity_serial_and_parallel(tmp_path):
    case = tmp_path / "cavity"
    shutil.copytree(cavity_tutorial(), case)
    foam("blockMesh", case)

    # stdout is exactly one JSON object: json.loads rejects anything around it.
    check_cavity(json.loads(foam(f"{CASE_INFO} -case {case}", tmp_path)), n_procs=1)

    (case / "system" / "decomposeParDict").write_text(
        "FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
        "numberOfSubdomains 2;\nmethod simple;\ncoeffs { n (2 1 1); }\n")
    foam("decomposePar -force", case)
    out = foam(f"mpirun --oversubscribe -n 2 {CASE_INFO} -parallel", case)
    check_cavity(json.loads(out), n_procs=2)
