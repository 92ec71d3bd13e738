"""coupling: a coupled case leaves what ParaView opens (fluid fields and particles both open in
ParaView): cases/cfd/cfd_shear_flow.py with --vtk keeps the OpenFOAM case folder
(mesh, fields every 10 fluid steps, case.foam for ParaView's OpenFOAM reader) and the spheres
written by the DEM at the same steps (VTK/particles-spheres.pvd).

Checked: the fluid's time folders hold U and p, the .pvd lists one sphere file per fluid write
at the same time (1e-12), and each file has the 1000 spheres with their radii and velocities."""
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from foam_case import ENV, REPO, needs_solver

pytestmark = needs_solver("talusPointForceFoam")


def test_shear_flow_case_writes_fluid_fields_and_spheres_at_the_same_times(tmp_path):
    out = tmp_path / "paraview"
    script = f"""
import importlib.util, sys
spec = importlib.util.spec_from_file_location("shear", {str(REPO / "cases" / "cfd" / "cfd_shear_flow.py")!r})
m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)
m.run(1, 10, 20, m.Path(sys.argv[1]))
"""
    run = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True, text=True, env=ENV,
                         timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    assert (out / "case.foam").exists() and (out / "constant" / "polyMesh" / "owner").exists()
    fluid_times = sorted(float(p.name) for p in out.iterdir() if re.fullmatch(r"[0-9.e-]+", p.name) and p.name != "0")
    assert fluid_times == pytest.approx([0.005, 0.01], rel=1e-12)
    for t in fluid_times:
        folder = out / f"{t:g}"
        assert (folder / "U").exists() and (folder / "p").exists()
    series = ET.parse(out / "VTK" / "particles-spheres.pvd").getroot()
    entries = [(float(d.get("timestep")), d.get("file")) for d in series.iter("DataSet")]
    assert [t for t, _ in entries] == pytest.approx(fluid_times, rel=1e-12)
    for _, name in entries:
        grid = ET.parse(out / "VTK" / name).getroot()
        piece = next(grid.iter("Piece"))
        assert piece.get("NumberOfPoints") == "1000"
        arrays = {a.get("Name") for a in piece.iter("DataArray")}
        assert {"radius", "velocity"} <= arrays
