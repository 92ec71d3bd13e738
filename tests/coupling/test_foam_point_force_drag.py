"""coupling: the drag law of talusPointForceFoam (dragModel in constant/couplingProperties; the
shared closures of foam-solvers/talusCouplingCommon/dragClosure.H).

Checked: with dragModel SchillerNaumann the first exchange (fluid at rest) returns
3 pi mu d (1 + 0.15 Re^0.687) times the slip plus the buoyancy (1e-12 relative) on the tiny case
of test_foam_coupling.py; an unknown dragModel stops the run before the first step with a message
naming the option, the name given and the valid names; the settling sphere of
cases/cfd/cfd_settling_sphere_pf.py at Re_p ~ 20 (its quick mode) ends within 2 % of the
Schiller-Naumann terminal velocity, while with dragModel Stokes it settles more than twice as fast
and the DEM side warns that the drag law is exceeded, naming dragModel."""
import importlib.util
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

from foam_case import DRIVER, ENV, REPO, meshed_box, needs_solver

RHO, NU, G = 1000.0, 1e-3, np.array([0.0, 0.0, -9.81])

pytestmark = needs_solver("talusPointForceFoam")


def case(tmp_path: Path, drag: str) -> Path:
    properties = ("FoamFile { version 2.0; format ascii; class dictionary; object couplingProperties; }\n"
                  f"dragModel {drag};\n")
    return meshed_box(tmp_path / f"case_{drag}", 1, {"constant/couplingProperties": properties})


def drive(work: Path):
    out = work / "out.json"
    run = subprocess.run([sys.executable, str(DRIVER), str(work), str(out)], capture_output=True, text=True,
                         env=ENV, timeout=90)
    return run, (json.loads(out.read_text()) if out.exists() else None)


def test_first_exchange_is_schiller_naumann_drag(tmp_path):
    run, record = drive(case(tmp_path, "SchillerNaumann"))
    assert run.returncode == 0, run.stdout + run.stderr
    v, r = np.array(record["velocities"][0]), np.array(record["radii"])
    d = 2 * r
    re = np.linalg.norm(v, axis=1) * d / NU
    correction = 1 + 0.15 * re ** 0.687
    assert np.all(correction > 1.01)  # distinguishable from Stokes drag at this tolerance
    expected = -(3 * math.pi * RHO * NU * d * correction)[:, None] * v - RHO * (math.pi * d ** 3 / 6)[:, None] * G
    np.testing.assert_allclose(record["forces"][0], expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def test_unknown_drag_model_stops_before_the_first_step_naming_the_valid_ones(tmp_path):
    run, record = drive(case(tmp_path, "Oseen"))
    assert run.returncode != 0 and record is None
    text = run.stdout + run.stderr
    assert "dragModel Oseen unknown: use Stokes, SchillerNaumann, DiFelice or ErgunWenYu" in text
    assert "couplingProperties" in text
    assert "has died while the DEM waited for the fluid side's handshake" in text


def settle_re20(tmp_path: Path, drag: str) -> dict:
    """The quick run of cases/cfd/cfd_settling_sphere_pf.py at Re_p ~ 20 with ``drag``, in its own
    process (it starts MPI)."""
    path = REPO / "cases" / "cfd" / "cfd_settling_sphere_pf.py"
    script = f"""
import importlib.util, json, sys, warnings
spec = importlib.util.spec_from_file_location("settling_pf", {str(path)!r})
m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    t, v, coupling, _ = m.settle(20, m.CHECKED_D_OVER_DX, 100, drag_model={drag!r})
json.dump(dict(v=list(v), w=m.sphere(20).terminal_velocity(), re=coupling.maxReynolds,
               limit=coupling.reynoldsLimit, warnings=[str(w.message) for w in caught]), open(sys.argv[1], "w"))
"""
    out = tmp_path / f"settle_{drag}.json"
    run = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True, text=True, env=ENV,
                         timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    return json.loads(out.read_text())


def test_settling_at_re20_reaches_the_schiller_naumann_terminal_velocity(tmp_path):
    result = settle_re20(tmp_path, "SchillerNaumann")
    assert 19 < result["re"] < 22
    assert abs(result["v"][-1] - result["w"]) < 0.02 * result["w"]
    assert result["limit"] == 2e5
    assert not [w for w in result["warnings"] if "Reynolds" in w]


def test_stokes_drag_at_re20_settles_too_fast_and_warns(tmp_path):
    result = settle_re20(tmp_path, "Stokes")
    assert result["v"][-1] > 2 * result["w"]
    assert result["limit"] == 0.5
    assert any("exceeds 0.5" in w and "dragModel" in w for w in result["warnings"]), result["warnings"]
