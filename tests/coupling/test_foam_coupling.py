"""coupling: the DEM process spawns talusPointForceFoam on a tiny case (4 x 4 x 4 cells) and
exchanges two particles with it (tests/coupling/foam_drag_driver.py, its own MPI process).

Checked: on the first exchange the fluid is at rest, so the force equals the Stokes drag
-3 pi mu d u_p plus the buoyancy -rho V g to round-off (1e-12 relative); on the second the fluid
has been set in motion by the particles' reactions, so the drag is smaller; a case whose
viscosity differs from the DEM side's stops both sides with a message naming both values; a
particle outside the mesh at the start is refused by start() with its position; a fluid step
above the coupling interval is refused, one above the particle relaxation time warns; a
decomposed case on 2 ranks gives the same first-exchange forces; bodies coupled in another
order get the same forces; FoamCoupling.times holds the DEM's and the fluid ranks' times (wall
and CPU)."""
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from foam_case import DRIVER, ENV, meshed_box, needs_solver

RHO, NU, G = 1000.0, 1e-3, np.array([0.0, 0.0, -9.81])

pytestmark = needs_solver("talusPointForceFoam")


def case(tmp_path: Path, procs: int = 1) -> Path:
    return meshed_box(tmp_path / "case", procs)


def drive(work: Path, tmp_path: Path, *extra: str):
    out = tmp_path / "out.json"
    run = subprocess.run([sys.executable, str(DRIVER), str(work), str(out), *extra], capture_output=True,
                         text=True, env=ENV, timeout=90)
    return run, (json.loads(out.read_text()) if out.exists() else None)


def buoyancy(record) -> np.ndarray:
    r = np.array(record["radii"])
    return -RHO * (4 / 3 * math.pi * r ** 3)[:, None] * G


def stokes_drag(record, exchange: int) -> np.ndarray:
    """The drag in a fluid at rest, with the particles' velocities sent at that exchange."""
    v, r = np.array(record["velocities"][exchange]), np.array(record["radii"])
    return -3 * math.pi * RHO * NU * (2 * r)[:, None] * v


def test_first_exchange_is_stokes_drag_then_fluid_responds(tmp_path):
    run, record = drive(case(tmp_path), tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    expected = stokes_drag(record, 0) + buoyancy(record)
    first, second = np.array(record["forces"][0]), np.array(record["forces"][1])
    np.testing.assert_allclose(first, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())
    assert record["nCells"] == 64 and record["fluidProcs"] == 1
    assert record["substeps"] == 10 and record["dt"] == pytest.approx(1e-6)
    # The force is held over the 10 DEM sub-steps of the fluid step, from the first one on.
    dt_fluid = record["substeps"] * record["dt"]
    v0, v1 = np.array(record["velocities"][0]), np.array(record["velocities"][1])
    np.testing.assert_allclose(v1, v0 + (first / np.array(record["masses"])[:, None] + G) * dt_fluid, rtol=1e-9)
    # The reactions set the fluid in motion along the particles: the drag is now below the drag
    # the particles' new velocities would meet in a fluid at rest.
    drag2, at_rest = second - buoyancy(record), stokes_drag(record, 1)
    assert np.all(np.linalg.norm(drag2, axis=1) < 0.999 * np.linalg.norm(at_rest, axis=1))


def test_viscosity_mismatch_stops_both_sides_with_a_message(tmp_path):
    run, record = drive(case(tmp_path), tmp_path, "--nu", "2e-3")
    assert run.returncode != 0 and record is None
    text = run.stdout + run.stderr
    assert "kinematic viscosity mismatch: DEM side nu = 0.002" in text
    assert "transportProperties nu = 0.001" in text


def test_particle_outside_the_mesh_at_start_is_refused_before_the_run(tmp_path):
    run, record = drive(case(tmp_path), tmp_path, "--outside")
    assert run.returncode != 0 and record is None
    text = run.stdout + run.stderr
    assert "ValueError: FoamCoupling: particle 1 at (-0.002, 0.0021, 0.0172) is outside the fluid mesh" in text
    assert "(-0.005, -0.005, 0) - (0.005, 0.005, 0.01)); 1 particle(s) outside, nothing was run" in text
    assert "started the fluid" not in run.stdout  # start() itself refused it


def test_fluid_step_larger_than_the_coupling_interval_is_refused(tmp_path):
    run, record = drive(case(tmp_path), tmp_path, "--interval", "5e-6")
    assert run.returncode != 0 and record is None
    assert "the fluid time step 1e-05 s (system/controlDict deltaT) is larger than the coupling interval 5e-06 s" \
        in run.stdout + run.stderr


def test_fluid_step_above_the_relaxation_time_warns(tmp_path):
    run, record = drive(case(tmp_path), tmp_path, "--small")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "RuntimeWarning: FoamCoupling: the fluid step 1e-05 s exceeds the particle relaxation time 1.38889e-06 s" \
        in run.stderr


def test_two_fluid_ranks_give_the_same_first_exchange(tmp_path):
    run, record = drive(case(tmp_path, procs=2), tmp_path, "--procs", "2")
    assert run.returncode == 0, run.stdout + run.stderr
    assert record["fluidProcs"] == 2
    expected = stokes_drag(record, 0) + buoyancy(record)
    np.testing.assert_allclose(record["forces"][0], expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def test_implicit_drag_is_re_evaluated_at_every_sub_step(tmp_path):
    """implicitDrag: over the 10 DEM sub-steps the force is the exchange's plus
    beta (v_exchange - v_k), beta = 3 pi mu d, integrated as the NewtonIntegrator does."""
    run, record = drive(case(tmp_path), tmp_path, "--implicit")
    assert run.returncode == 0, run.stdout + run.stderr
    first = np.array(record["forces"][0])
    v0, v1 = np.array(record["velocities"][0]), np.array(record["velocities"][1])
    m = np.array(record["masses"])[:, None]
    beta = 3 * math.pi * RHO * NU * 2 * np.array(record["radii"])[:, None]
    v = v0.copy()
    for _ in range(record["substeps"]):
        v = v + record["dt"] * ((first + beta * (v0 - v)) / m + G)
    np.testing.assert_allclose(v1, v, rtol=1e-9)
    held = v0 + (first / m + G) * record["substeps"] * record["dt"]
    assert np.abs(v1 - held).max() > 1e-3 * np.abs(v1 - v0).max()  # not the held force


def test_bodies_coupled_in_any_order_get_the_same_forces(tmp_path):
    """ids=[1, 0] takes the index-array path of FoamCoupling (one run of ids takes a slice)."""
    run, record = drive(case(tmp_path), tmp_path)
    swapped_run, swapped = drive(meshed_box(tmp_path / "swapped"), tmp_path, "--reversed")
    assert run.returncode == 0 and swapped_run.returncode == 0, swapped_run.stdout + swapped_run.stderr
    # lastForces is per coupled body, in the order of ids.
    np.testing.assert_allclose(np.array(swapped["forces"])[:, ::-1], record["forces"], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(swapped["velocities"], record["velocities"], rtol=1e-12, atol=1e-15)


def test_times_tell_the_coupling_from_the_fluid_and_the_dem(tmp_path):
    """FoamCoupling.times: the fluid ranks report each exchange and fluid step one exchange late,
    as wall and CPU time; the DEM side counts its own coupling work apart from its waits."""
    run, record = drive(case(tmp_path), tmp_path, "--exchanges", "4")
    assert run.returncode == 0, run.stdout + run.stderr
    times = record["times"]
    assert times["exchanges"] == 4 and times["fluidReports"] == 3
    for key in ("dem", "waiting", "fluidExchange", "fluidSteps", "demCpu", "fluidExchangeCpu", "fluidStepsCpu"):
        assert times[key] > 0, key
    # A fluid step (a PISO solve) costs more than locating two particles.
    assert times["fluidStepsCpu"] > times["fluidExchangeCpu"]

