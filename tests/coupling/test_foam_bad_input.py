"""coupling: bad input is refused before the coupled run starts, with a message naming the item:
a missing case file, a solver that does not exist, a case not
decomposed for the fluid ranks asked, gravity differing between the DEM side and the case or
the NewtonIntegrator, and a malformed case file (the solver dies on it while the DEM waits for
the handshake: every process gone within seconds). The particle outside the mesh at the start
and the viscosity mismatch are in test_foam_coupling.py.

Checked each time: the DEM process exits with the message, wrote no result, and no process
whose command line names the case is left."""
import subprocess
import sys
import time
from pathlib import Path

from foam_case import DRIVER, ENV, meshed_box, needs_solver

pytestmark = needs_solver("talusPointForceFoam")


def refused(work: Path, *extra: str, limit: float = 30) -> str:
    """Runs the driver on ``work``; asserts it fails within ``limit`` seconds leaving nothing
    behind; returns its output."""
    out = work.parent / "out.json"
    started = time.monotonic()
    run = subprocess.run([sys.executable, str(DRIVER), str(work), str(out), *extra], capture_output=True,
                         text=True, env=ENV, timeout=90)
    elapsed = time.monotonic() - started
    text = run.stdout + run.stderr
    assert run.returncode != 0 and not out.exists(), text
    assert elapsed < limit, f"took {elapsed:.1f} s"
    assert "started the fluid" not in run.stdout, text  # start() refused it
    left = subprocess.run(["pgrep", "-f", str(work)], capture_output=True, text=True).stdout.split()
    assert not left, f"processes left behind: {left}"
    return text


def test_missing_case_file_is_refused_before_the_solver_starts(tmp_path):
    work = meshed_box(tmp_path / "case")
    (work / "constant" / "g").unlink()
    assert f"FoamCoupling: case '{work}' has no constant/g" in refused(work)


def test_solver_that_does_not_exist_is_refused(tmp_path):
    text = refused(meshed_box(tmp_path / "case"), "--solver", "talusNoSuchFoam")
    assert "FoamCoupling: solver 'talusNoSuchFoam' not found" in text


def test_case_not_decomposed_for_the_fluid_ranks_is_refused(tmp_path):
    work = meshed_box(tmp_path / "case")
    text = refused(work, "--procs", "2")
    assert f"FoamCoupling: case '{work}' is not decomposed into 2 (no processor0; run decomposePar)" in text


def test_gravity_of_the_case_differing_from_the_dem_side_stops_both_sides(tmp_path):
    work = meshed_box(tmp_path / "case")
    g = work / "constant" / "g"
    g.write_text(g.read_text().replace("(0 0 -9.81)", "(0 0 -9.80665)"))
    text = refused(work)
    assert "gravity mismatch: DEM side (0 0 -9.81), case constant/g (0 0 -9.80665)" in text


def test_gravity_of_the_newton_integrator_differing_is_refused(tmp_path):
    text = refused(meshed_box(tmp_path / "case"), "--newton-gravity", "-9.8")
    assert "FoamCoupling: gravity (0.0, 0.0, -9.81) differs from the NewtonIntegrator's (0.0, 0.0, -9.8)" in text


def test_malformed_case_file_stops_every_process_within_seconds(tmp_path):
    work = meshed_box(tmp_path / "case")
    field = work / "0" / "U"
    field.write_text(field.read_text().replace("internalField", "internalField uniform (0 0;", 1))
    text = refused(work, limit=15)
    assert "FOAM FATAL" in text and "has died while the DEM waited for the fluid side's handshake" in text


def test_coupled_ids_that_are_not_live_spheres_are_refused_before_any_process_starts(tmp_path):
    import pytest

    from talus.coupling import FoamCoupling
    from talus.dem import FrictMat, NewtonIntegrator, Scene, sphere, wall
    S = Scene()
    m = S.materials.append(FrictMat())
    S.bodies.append([wall(0, axis=2, material=m), sphere((0, 0, 0.01), 1e-3, material=m),
                     sphere((0, 0, 0.02), 1e-3, material=m)])
    S.engines = [NewtonIntegrator(gravity=(0, 0, -9.81))]
    S.dt = 1e-5
    for ids, message in [([1, 5], "ids: 5 is not a body id of the scene (0 ... 2)"),
                         ([-1, 2], "ids: -1 is not a body id of the scene"),
                         ([1, 2, 1], "ids: body 1 is listed twice"),
                         ([0, 1], "ids: body 0 is a Wall, not a sphere")]:
        coupling = FoamCoupling(S, tmp_path / "no-case", rhoFluid=1000.0, nu=1e-6, ids=ids)
        with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)").replace(".", r"\.")):
            coupling.start()
        assert coupling.link is None
