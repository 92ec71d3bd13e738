"""coupling: talus.coupling.case_builder (cfd_case, `talus case cfd`).

Checked: a held-out gas-phase case -- a 50 um glass bead settling in air (Re_p up to 0.6, Stokes
relaxation time 19 ms) -- set up with the builder in a script of under 20 lines, run on 1 and
2 fluid ranks with the volume-averaged solver: its velocity follows the integrated equation of
motion with Schiller-Naumann drag within 2 % of the final velocity, and the two runs agree to
1e-9; the files written for each solver (the convection scheme each names, PISO or PIMPLE,
pRefCell only without a pressure boundary, GAMG from GAMG_FROM_CELLS cells or GAMG_FROM_SPAN cells
along the longest side and PCG below, slabs across an axis without periodic patches, an inlet's
ramp and alphaf, a graded box, the fields' precision), an existing mesh reused, bad input refused
naming the parameter, and `talus case cfd` writing a meshed, decomposed case."""
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from foam_case import BUILD, ENV, needs_solver

pytestmark = needs_solver("talusVolumeAveragedFoam")

# The held-out case as a user writes it: the whole script (fewer than 20 lines).
GAS_SETTLING = '''\
import json, sys
from talus.coupling.case_builder import cfd_case
from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere
procs = int(sys.argv[1])                                # a 50 um glass bead settling in air
case = cfd_case(f"air_{procs}", solver="volumeaveraged", box=((-2.75e-3, -2.75e-3, 0), (2.75e-3, 2.75e-3, 0.02)),
                cell_size=5e-4, rho=1.2, nu=1.5e-5, coupling_interval=1e-3, procs=procs)
s = Scene()
s.materials.append(FrictMat(density=2500))
s.bodies.append(sphere((0, 0, 0.0175), 25e-6))
s.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.0)]
s.dt = 1e-4
coupling = case.coupling(s).start()
velocities = []
for _ in range(80):
    s.run(coupling.substeps, True)
    velocities.append(-s.velocities()[0][2])
coupling.stop()
print("VELOCITIES", json.dumps(velocities))
'''
RHO, NU, RHO_P, D, G, CM = 1.2, 1.5e-5, 2500.0, 50e-6, 9.81, 0.5


def schiller_naumann_motion(t_end: float, dt: float = 1e-5):
    """Settling velocity from rest: (m + C_m rho V) dv/dt = (m - rho V) g - 3 pi mu d v (1 + 0.15 Re^0.687), RK4."""
    volume = math.pi * D ** 3 / 6
    mass = RHO_P * volume

    def accel(v):
        drag = 3 * math.pi * RHO * NU * D * v * (1 + 0.15 * (v * D / NU) ** 0.687)
        return ((mass - RHO * volume) * G - drag) / (mass + CM * RHO * volume)
    t, v, ts, vs = 0.0, 0.0, [0.0], [0.0]
    while t < t_end - 1e-12:
        k1 = accel(v); k2 = accel(v + dt / 2 * k1); k3 = accel(v + dt / 2 * k2); k4 = accel(v + dt * k3)
        v += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t += dt
        ts.append(t); vs.append(v)
    return np.array(ts), np.array(vs)


@pytest.fixture(scope="module")
def gas_runs(tmp_path_factory):
    work = tmp_path_factory.mktemp("gas")
    script = work / "settle.py"
    script.write_text(GAS_SETTLING)
    runs = {}
    for procs in (1, 2):
        done = subprocess.run([str(BUILD / "bin" / "talus"), "run", "-j", "1", str(script), str(procs)], cwd=work,
                              env=ENV, capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-3000:]
        line = next(l for l in done.stdout.splitlines() if l.startswith("VELOCITIES"))
        runs[procs] = np.array(json.loads(line.split(None, 1)[1]))
    return runs


def test_gas_settling_script_is_short():
    assert len(GAS_SETTLING.splitlines()) < 20


def test_gas_settling_follows_schiller_naumann(gas_runs):
    v = gas_runs[1]
    t = 1e-3 * np.arange(1, len(v) + 1)
    t_ref, v_ref = schiller_naumann_motion(t[-1])
    deviation = np.max(np.abs(v - np.interp(t, t_ref, v_ref))) / v_ref[-1]
    assert v[-1] * D / NU > 0.4          # the drag is beyond Stokes's range there
    assert deviation < 0.02, f"largest deviation {deviation:.3%} of the final velocity"


def test_gas_settling_two_ranks_equal_serial(gas_runs):
    np.testing.assert_allclose(gas_runs[2], gas_runs[1], rtol=1e-9)


def read(case, name):
    return (case.path / name).read_text()


def test_point_force_case_files(tmp_path):
    from talus.coupling.case_builder import PERIODIC, Wall, cfd_case
    case = cfd_case(tmp_path / "pf", solver="pointforce", box=((0, 0, 0), (0.1, 0.1, 0.1)), cells=(4, 4, 4), rho=1000,
                    nu=1e-4, gravity=(0, 0, 0), coupling_interval=5e-4, procs=2,
                    boundaries={"y0": Wall((-0.05, 0, 0)), "x1": PERIODIC, "z0": "periodic"}, run_mesh=False)
    assert case.solver == "talusPointForceFoam" and case.cells == 64
    assert "div(phi,U) Gauss linear" in read(case, "system/fvSchemes")
    assert "div(alphaPhi,U)" not in read(case, "system/fvSchemes")
    solution = read(case, "system/fvSolution")
    assert "PISO" in solution and "PIMPLE" not in solution and "pRefCell 0;" in solution
    assert "solver PCG; preconditioner DIC; tolerance 1e-08" in solution
    mesh = read(case, "system/blockMeshDict")
    assert "x0 { type cyclic; neighbourPatch x1;" in mesh and "z1 { type cyclic; neighbourPatch z0;" in mesh
    assert "y0 { type wall;" in mesh
    assert "y0 { type fixedValue; value uniform (-0.05 0 0); }" in read(case, "0/U")
    assert "y1 { type noSlip; }" in read(case, "0/U")
    assert "coeffs { n (1 2 1); }" in read(case, "system/decomposeParDict")  # y: the only axis not periodic
    assert not (case.path / "0" / "alphaf").exists() and (case.path / "case.foam").exists()


def test_volume_averaged_case_files(tmp_path):
    from talus.coupling.case_builder import GAMG_FROM_CELLS, Inlet, Outlet, cfd_case
    side = math.ceil(GAMG_FROM_CELLS ** (1 / 3)) + 1
    case = cfd_case(tmp_path / "va", solver="talusVolumeAveragedFoam", box=((0, 0, 0), (1, 1, 2)),
                    cells=(side, side, 2 * side), rho=1000, nu=1e-6, coupling_interval=1e-4,
                    boundaries={"z0": Inlet((0, 0, 0.01), ramp=0.5), "z1": Outlet(), "x0": "periodic", "y0": "periodic"},
                    coupling_properties={"envelopeWidth": 0.003, "dragModel": "DiFelice"}, run_mesh=False)
    assert "div(alphaPhi,U) Gauss linear" in read(case, "system/fvSchemes")
    solution = read(case, "system/fvSolution")
    assert "PIMPLE" in solution and "nOuterCorrectors 1;" in solution
    assert "pRefCell" not in solution                      # the outlet fixes the pressure
    assert "solver GAMG" in solution
    assert "table ((0 (0 0 0)) (0.5 (0 0 0.01))" in read(case, "0/U")
    assert "z0 { type fixedValue; value uniform 1; }" in read(case, "0/alphaf")
    assert "z1 { type fixedValue; value uniform 0; }" in read(case, "0/p")
    assert re.search(r"envelopeWidth\s+0.003;", read(case, "constant/couplingProperties"))


@pytest.mark.parametrize("cells, solver", [
    ((5, 5, 20), "PCG"),                      # the point-force settling case's box
    ((10, 10, 150), "PCG"),                   # 15 000 cells, 150 along z
    ((5, 5, 200), "GAMG"),                    # 5 000 cells, but 200 along z
    ((28, 28, 28), "GAMG"),                   # 21 952 cells
])
def test_pressure_solver_follows_the_mesh_size_and_shape(tmp_path, cells, solver):
    from talus.coupling.case_builder import GAMG_FROM_CELLS, GAMG_FROM_SPAN, cfd_case
    assert (GAMG_FROM_CELLS, GAMG_FROM_SPAN) == (20000, 200)   # the thresholds the cases above straddle
    case = cfd_case(tmp_path / "box", box=((0, 0, 0), tuple(0.01 * n for n in cells)), cells=cells, rho=1000, nu=1e-6,
                    coupling_interval=1e-3, run_mesh=False)
    assert f"p {{ solver {solver};" in read(case, "system/fvSolution")
    assert "tolerance 1e-08; relTol 0.01;" in read(case, "system/fvSolution")
    # An existing mesh of the same shape: its span in cells from its bounding box and cell count.
    if solver == "GAMG" and cells[0] == 5:
        meshed = cfd_case(tmp_path / "meshed", box=((0, 0, 0), (0.05, 0.05, 2.0)), cells=cells, rho=1000, nu=1e-6,
                          coupling_interval=1e-3)
        again = cfd_case(tmp_path / "again", mesh=meshed.path, rho=1000, nu=1e-6, coupling_interval=1e-3,
                         run_mesh=False)
        assert "p { solver GAMG;" in read(again, "system/fvSolution")


def test_graded_box_and_write_precision(tmp_path):
    from talus.coupling.case_builder import cfd_case
    case = cfd_case(tmp_path / "graded", box=((0, 0, 0), (1, 1, 2)), cells=(4, 4, 8), grading=(1, 1, 2), rho=1, nu=1,
                    coupling_interval=1, write_precision=17)
    assert "(4 4 8) simpleGrading (1 1 2)" in read(case, "system/blockMeshDict")
    assert re.search(r"writePrecision\s+17;", read(case, "system/controlDict"))
    points = (case.path / "constant" / "polyMesh" / "points").read_text()
    z = sorted({round(float(m), 12) for m in re.findall(r"\(\S+ \S+ (\S+)\)", points)})
    assert len(z) == 9 and (z[-1] - z[-2]) / (z[1] - z[0]) == pytest.approx(2)   # the last cell twice the first
    with pytest.raises(ValueError, match="initial_velocity as a function .* ungraded box"):
        cfd_case(tmp_path / "c", box=((0, 0, 0), (1, 1, 1)), cells=(2, 2, 2), grading=(1, 2, 1), rho=1, nu=1,
                 coupling_interval=1, initial_velocity=lambda x: x, run_mesh=False)


def test_existing_mesh_and_initial_field(tmp_path):
    from talus.coupling.case_builder import cfd_case
    first = cfd_case(tmp_path / "box", box=((0, 0, 0), (3, 2, 1)), cells=(3, 2, 1), rho=1, nu=1,
                     coupling_interval=1, initial_velocity=lambda x: x * [1, 10, 100])
    internal = read(first, "0/U")
    assert "(0.5 5 50)\n(1.5 5 50)\n(2.5 5 50)\n(0.5 15 50)" in internal   # x fastest, then y
    again = cfd_case(tmp_path / "again", mesh=first.path, rho=1, nu=1, coupling_interval=1, solver="volumeaveraged",
                     boundaries={"z1": "outlet"})
    assert again.cells == 6 and set(again.patches) == {"x0", "x1", "y0", "y1", "z0", "z1"}
    assert "laplacianSchemes { default Gauss linear corrected; }" in read(again, "system/fvSchemes")
    with pytest.raises(ValueError, match="initial_velocity .* needs a box mesh"):
        cfd_case(tmp_path / "c", mesh=first.path, rho=1, nu=1, coupling_interval=1, initial_velocity=lambda x: x)


@pytest.mark.parametrize("kwargs, message", [
    (dict(solver="icoFoam"), "solver 'icoFoam'"),
    (dict(boundaries={"top": "outlet"}), "no patch named top"),
    (dict(boundaries={"z1": "outlet:abc"}), "boundary condition 'outlet:abc'"),
    (dict(nu=0), "nu must be positive"),
    (dict(procs=2, decomposition=(1, 1, 3)), "decomposition"),
    (dict(cell_size=0.1), "cells .* or its cell_size, not both"),
    (dict(grading=(1, 0, 1)), "grading .* three positive ratios"),
    (dict(write_precision=0), "write_precision"),
])
def test_bad_input(tmp_path, kwargs, message):
    from talus.coupling.case_builder import cfd_case
    arguments = dict(box=((0, 0, 0), (1, 1, 1)), cells=(2, 2, 2), rho=1, nu=1, coupling_interval=1, run_mesh=False)
    with pytest.raises(ValueError, match=message):
        cfd_case(tmp_path / "bad", **{**arguments, **kwargs})


def test_cli_writes_a_meshed_decomposed_case(tmp_path):
    out = tmp_path / "cli"
    done = subprocess.run([str(BUILD / "bin" / "talus"), "case", "cfd", "--solver", "volumeaveraged", "--box", "0", "0",
                           "0", "0.01", "0.01", "0.04", "--cell-size", "0.002", "--rho", "1000", "--nu", "1e-6",
                           "--boundary", "z0=inlet:0,0,0.001", "--boundary", "z1=outlet", "--dt", "1e-4",
                           "--procs", "2", "--coupling", "envelopeWidth=0.004", "--out", str(out)],
                          env=ENV, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "talusVolumeAveragedFoam, 500 cells, 2 fluid rank(s)" in done.stdout
    assert (out / "constant" / "polyMesh" / "owner").exists() and (out / "processor1").is_dir()
    bad = subprocess.run([str(BUILD / "bin" / "talus"), "case", "cfd", "--box", "0", "0", "0", "1", "1", "1",
                          "--cells", "2", "2", "2", "--rho", "1", "--nu", "1", "--dt", "1", "--boundary", "top=wall",
                          "--out", str(tmp_path / "bad")], env=ENV, capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "no patch named top" in bad.stderr
