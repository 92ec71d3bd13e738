"""coupling: talusVolumeAveragedFoam on the tiny case of test_foam_coupling.py (4 x 4 x 4 cells,
two particles; tests/coupling/foam_drag_driver.py is the DEM process) and a short settling run.

Checked: with the cell-local envelope, the first exchange (fluid at rest) returns exactly the
Schiller-Naumann drag with the hindrance factor of the particle's cell, (1 - V_p / V_cell)^-2.65,
plus the buoyancy (1e-12 relative), and with dragModel ErgunWenYu, DiFelice or Stokes those closures
(an unknown dragModel stops the run before the first step, naming the valid ones); with the Gaussian envelope, a case decomposed on 2 fluid
ranks (the envelopes cross the processor boundary) gives the serial forces, to 1e-12 on the
first exchange and 1e-6 of the largest force over 3 exchanges (the pressure solver's tolerance); a sphere settling at Re_p ~ 5 reaches the Schiller-Naumann terminal velocity
within 2 %; an unknown envelope stops the run before the first step with OpenFOAM's message; a
fluid step below the Stokes relaxation time but above m/beta with the hindered drag warns; envelopeCutoff
3 sigma / delta gives the default's forces (1e-12), 1 (a cut at delta) others, 0 stops the run before the first
step."""
import importlib.util
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from foam_case import DRIVER, ENV, REPO, meshed_box, needs_solver

RHO, NU, G = 1000.0, 1e-3, np.array([0.0, 0.0, -9.81])

pytestmark = needs_solver("talusVolumeAveragedFoam")


def case(tmp_path: Path, envelope: str, procs: int = 1, drag: str | None = None, cutoff: float | None = None) -> Path:
    properties = ("FoamFile { version 2.0; format ascii; class dictionary; object couplingProperties; }\n"
                  f"envelope {envelope};\n" + ("" if drag is None else f"dragModel {drag};\n")
                  + ("" if cutoff is None else f"envelopeCutoff {cutoff!r};\n"))
    return meshed_box(tmp_path / f"case_{envelope}_{procs}_{drag}_{cutoff}", procs,
                      {"constant/couplingProperties": properties})


def drive(work: Path, *extra: str):
    out = work / "out.json"
    run = subprocess.run([sys.executable, str(DRIVER), str(work), str(out), "--solver", "talusVolumeAveragedFoam",
                          *extra], capture_output=True, text=True, env=ENV, timeout=90)
    return run, (json.loads(out.read_text()) if out.exists() else None)


def test_cell_envelope_first_exchange_is_schiller_naumann_with_hindrance(tmp_path):
    run, record = drive(case(tmp_path, "cell"))
    assert run.returncode == 0, run.stdout + run.stderr
    v, r = np.array(record["velocities"][0]), np.array(record["radii"])
    d = 2 * r
    vp = math.pi * d ** 3 / 6
    alpha = 1 - vp / 0.0025 ** 3                 # each particle alone in its 2.5 mm cell
    re = np.linalg.norm(v, axis=1) * d / NU
    k = 18 * RHO * NU / d ** 2 * (1 + 0.15 * re ** 0.687) * alpha ** -2.65
    expected = -(vp * k)[:, None] * v - RHO * vp[:, None] * G
    np.testing.assert_allclose(record["forces"][0], expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def ergun_wen_yu(alpha, w, d):
    if alpha < 0.8:
        return 150 * RHO * NU * (1 - alpha) / (alpha * d ** 2) + 1.75 * RHO * w / d
    return 18 * RHO * NU / d ** 2 * (1 + 0.15 * (alpha * w * d / NU) ** 0.687) * alpha ** -2.65


def di_felice(alpha, w, d):
    re = alpha * w * d / NU
    chi = 3.7 - 0.65 * math.exp(-(1.5 - math.log10(re)) ** 2 / 2)
    return 0.75 * (0.63 + 4.8 / math.sqrt(re)) ** 2 * RHO * w * alpha ** (2 - chi) / d


def stokes_hindered(alpha, w, d):
    return 18 * RHO * NU / d ** 2 * alpha ** -2.65


@pytest.mark.parametrize("model, closure", [("ErgunWenYu", ergun_wen_yu), ("DiFelice", di_felice),
                                            ("Stokes", stokes_hindered)])
def test_cell_envelope_first_exchange_follows_the_selected_drag_closure(tmp_path, model, closure):
    run, record = drive(case(tmp_path, "cell", drag=model))
    assert run.returncode == 0, run.stdout + run.stderr
    v, r = np.array(record["velocities"][0]), np.array(record["radii"])
    d = 2 * r
    vp = math.pi * d ** 3 / 6
    alpha = 1 - vp / 0.0025 ** 3
    k = np.array([closure(a, w, di) for a, w, di in zip(alpha, np.linalg.norm(v, axis=1), d)])
    expected = -(vp * k)[:, None] * v - RHO * vp[:, None] * G
    np.testing.assert_allclose(record["forces"][0], expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def test_unknown_drag_model_stops_before_the_first_step(tmp_path):
    run, record = drive(case(tmp_path, "cell", drag="Oseen"))
    assert run.returncode != 0 and record is None
    assert "dragModel Oseen unknown: use Stokes, SchillerNaumann, DiFelice or ErgunWenYu" in run.stdout + run.stderr


def test_gaussian_envelope_two_fluid_ranks_equal_serial(tmp_path):
    serial_run, serial = drive(case(tmp_path, "gaussian"), "--exchanges", "3")
    parallel_run, parallel = drive(case(tmp_path, "gaussian", procs=2), "--exchanges", "3", "--procs", "2")
    assert serial_run.returncode == 0, serial_run.stdout + serial_run.stderr
    assert parallel_run.returncode == 0, parallel_run.stdout + parallel_run.stderr
    assert parallel["fluidProcs"] == 2
    f1, f2 = np.array(serial["forces"]), np.array(parallel["forces"])
    # The first exchange differs by the order of the sums only; later ones also by the
    # decomposed pressure solve (its tolerance): 6e-8 of the largest force, measured.
    np.testing.assert_allclose(f2[0], f1[0], rtol=1e-12, atol=1e-12 * np.abs(f1).max())
    np.testing.assert_allclose(f2, f1, rtol=1e-6, atol=1e-6 * np.abs(f1).max())
    # The fluid moved between the exchanges (not a trivially repeated answer).
    assert np.abs(f1[2] - f1[0]).max() > 1e-3 * np.abs(f1[0]).max()


def test_unknown_envelope_stops_before_the_first_step(tmp_path):
    run, record = drive(case(tmp_path, "tophat"))
    assert run.returncode != 0 and record is None
    text = run.stdout + run.stderr
    assert "envelope tophat unknown: use gaussian or cell" in text
    assert "has died while the DEM waited for the fluid side's handshake" in text


def test_envelope_cutoff_defaults_to_three_sigma_and_is_read(tmp_path):
    _, default = drive(case(tmp_path, "gaussian"), "--exchanges", "3")
    _, three_sigma = drive(case(tmp_path, "gaussian", cutoff=3 / (2 * math.sqrt(2 * math.log(2)))), "--exchanges", "3")
    _, delta = drive(case(tmp_path, "gaussian", cutoff=1.0), "--exchanges", "3")
    f0, f3, f1 = (np.array(r["forces"]) for r in (default, three_sigma, delta))
    np.testing.assert_allclose(f3, f0, rtol=1e-12, atol=1e-12 * np.abs(f0).max())
    assert np.abs(f1 - f0).max() > 1e-6 * np.abs(f0).max()  # cut at delta: fewer cells, other weights
    run, record = drive(case(tmp_path, "gaussian", cutoff=0.0))
    assert run.returncode != 0 and record is None
    assert "envelopeWidth and envelopeCutoff must be positive" in run.stdout + run.stderr


def test_settling_sphere_reaches_schiller_naumann_terminal_velocity(tmp_path):
    spec = importlib.util.spec_from_file_location("settling_va", REPO / "cases" / "cfd" / "cfd_settling_sphere_va.py")
    script = f"""
import importlib.util, json, sys
spec = importlib.util.spec_from_file_location("settling_va", {str(spec.origin)!r})
m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)
t, v, coupling, _ = m.settle(1, 0.02, 150, "gaussian")
json.dump(dict(v=list(v), w=m.SPHERE.terminal_velocity(), re=coupling.maxReynolds), open(sys.argv[1], "w"))
"""
    out = tmp_path / "settle.json"
    run = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True, text=True, env=ENV,
                         timeout=90)
    assert run.returncode == 0, run.stdout + run.stderr
    result = json.loads(out.read_text())
    assert 4 < result["re"] < 6
    assert abs(result["v"][-1] - result["w"]) < 0.02 * result["w"]


def test_fluid_step_above_the_hindered_relaxation_time_warns(tmp_path):
    # rho_p = 190: Stokes tau = rho_p d^2 / (18 mu) = 1.06e-5 s above the fluid step 1e-5 s (no
    # warning at start), but the drag with hindrance and Schiller-Naumann (x 1.12) makes
    # m / beta = 9.4e-6 s for the 1 mm sphere.
    run, record = drive(case(tmp_path, "cell"), "--density", "190")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "exceeds the particle relaxation time" not in run.stderr
    assert "RuntimeWarning: FoamCoupling: the fluid step 1e-05 s exceeds the relaxation time m/beta = 9.4" in run.stderr
    assert "s of body 0 with the drag of the first exchange (hindrance included)" in run.stderr
