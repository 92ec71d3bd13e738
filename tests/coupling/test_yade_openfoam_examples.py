"""Yade's OpenFOAM examples (examples/openfoam) with Talus: the case dictionaries read as Yade's
solvers read them, the decomposeParDict bridged to v1912, and example_icoFoamYade run for a few
coupling steps through its own scriptYade.py (`from yadeimport import *`, Yade's FoamCoupling
interface) with the launcher icoFoamYade on 2 fluid ranks. Skipped without Yade's examples,
OpenFOAM or mpiexec."""
import importlib.util
import json
import shutil
import sys
from pathlib import Path

import pytest

from foam_case import BUILD, needs_solver

EXAMPLES = Path("/usr/share/doc/yade/examples/openfoam")
CASE_SCRIPT = Path(__file__).resolve().parents[2] / "cases" / "cfd" / "cfd_yade_openfoam_examples.py"

pytestmark = [
    needs_solver("icoFoamYade"),
    pytest.mark.skipif(not EXAMPLES.is_dir(), reason="Yade's examples/openfoam not installed (apt-get install yade)"),
    pytest.mark.skipif(shutil.which("blockMesh") is None or shutil.which("mpiexec") is None,
                       reason="OpenFOAM's blockMesh or mpiexec missing"),
]


def _case_module():
    sys.path.insert(0, str(BUILD / "python"))
    spec = importlib.util.spec_from_file_location("cfd_yade_openfoam_examples", CASE_SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_case_settings_of_both_examples():
    from talus.coupling.foam_case import case_settings
    ico = case_settings(EXAMPLES / "example_icoFoamYade")
    assert (ico["rhoFluid"], ico["nu"], ico["application"], ico["deltaT"], ico["endTime"]) == \
        (1000.0, 1e-4, "icoFoamYade", 5e-4, 0.034)
    pimple = case_settings(EXAMPLES / "example_pimpleFoamYade")
    assert (pimple["rhoFluid"], pimple["nu"], pimple["application"], pimple["gravity"]) == \
        (1000.0, 1e-6, "pimpleFoamYade", (0.0, 0.0, 0.0))


def test_ico_example_runs_a_few_coupling_steps(tmp_path):
    case = _case_module()
    work = case.prepare(EXAMPLES / "example_icoFoamYade", tmp_path / "ico", quick_steps=3)
    bridged = (work / "system" / "decomposeParDict.v1912").read_text()
    assert "optional" not in bridged and "simple" in bridged and "(1 2 1)" in bridged  # slabs across y
    run = case.run_script(work, "scriptYade.py", BUILD, timeout=300)     # the script as shipped
    assert run["returncode"] == 0, run["output_tail"]
    ok, info = case.check("icoFoamYade", run, expected_steps=3)
    assert ok, info
    assert info["fluid_procs"] == 2 and info["exchanges"] == 3
    assert (work / "processor1" / "log.talusPointForceFoam").exists() or (work / "processor0").is_dir()
