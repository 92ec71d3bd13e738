"""ParaView output (VTK XML .vtu and .pvd, read back with a small parser of our own and, when
installed, with ParaView's pvpython) and the progress line."""
import base64
import io as stdio
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from talus import _dem
from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       PWaveTimeStep, Scene, facet, sphere, wall)
from talus.dem.files import export, io
from talus.dem.analysis import progress

LINEAR = ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])
TYPES = {"Float64": np.float64, "Float32": np.float32, "Int64": np.int64, "Int32": np.int32, "UInt8": np.uint8}


def decode(element) -> np.ndarray:
    """A DataArray with format="binary": base64 of a UInt64 byte count followed by the data."""
    assert element.get("format") == "binary"
    raw = base64.b64decode(element.text or "", validate=True)
    size = int(np.frombuffer(raw[:8], dtype="<u8")[0])
    assert len(raw) == 8 + size, "byte count header does not match the data"
    data = np.frombuffer(raw[8:], dtype=np.dtype(TYPES[element.get("type")]).newbyteorder("<"))
    components = int(element.get("NumberOfComponents", "1"))
    assert data.size % components == 0
    return data.reshape(-1, components) if components > 1 else data


def read_vtu(path) -> dict:
    root = ET.parse(path).getroot()
    assert root.tag == "VTKFile" and root.get("type") == "UnstructuredGrid"
    assert root.get("byte_order") == "LittleEndian" and root.get("header_type") == "UInt64"
    (grid,) = root
    (piece,) = grid.findall("Piece")
    out = {"points_count": int(piece.get("NumberOfPoints")), "cells_count": int(piece.get("NumberOfCells"))}
    out["time"] = float(decode(grid.find("FieldData/DataArray[@Name='TimeValue']"))[0])
    out["points"] = decode(piece.find("Points/DataArray")).reshape(-1, 3)
    for name in ("connectivity", "offsets", "types"):
        out[name] = decode(piece.find(f"Cells/DataArray[@Name='{name}']"))
    out["point"] = {a.get("Name"): decode(a) for a in piece.find("PointData")}
    out["cell"] = {a.get("Name"): decode(a) for a in piece.find("CellData")}
    # Consistency VTK relies on.
    assert len(out["points"]) == out["points_count"]
    assert len(out["types"]) == len(out["offsets"]) == out["cells_count"]
    assert (len(out["connectivity"]) == (out["offsets"][-1] if len(out["offsets"]) else 0))
    assert np.all(np.diff(np.r_[0, out["offsets"]]) > 0)
    assert np.all((out["connectivity"] >= 0) & (out["connectivity"] < max(out["points_count"], 1)))
    for a in out["point"].values():
        assert len(a) == out["points_count"]
    for a in out["cell"].values():
        assert len(a) == out["cells_count"]
    return out


def read_pvd(path) -> list[tuple[float, str]]:
    root = ET.parse(path).getroot()
    assert root.tag == "VTKFile" and root.get("type") == "Collection"
    return [(float(d.get("timestep")), d.get("file")) for d in root.find("Collection")]


def scene_with_everything() -> Scene:
    S = Scene()
    S.materials.append(FrictMat(young=1e6, density=2600))
    S.bodies.append([facet([(-1, -1, 0), (2, -1, 0), (2, 2, 0)]), facet([(-1, -1, 0), (2, 2, 0), (-1, 2, 0)]),
                     wall(0, axis=0, sense=1), wall(1, axis=1, sense=-1)])
    # A 4 x 4 x 4 stack of touching spheres, pressed slightly on the floor and two walls.
    rng = np.random.default_rng(3)
    grid = np.stack(np.meshgrid(np.arange(4), np.arange(4), np.arange(4), indexing="ij"), -1).reshape(-1, 3)
    centres = 0.085 + 0.18 * grid + rng.uniform(-0.002, 0.002, grid.shape)
    centres[:, 1] = 1 - centres[:, 1]
    S.bodies.append([sphere(c, 0.09) for c in centres])
    S.bodies.erase(10)
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4)]
    S.dt = 0.3 * PWaveTimeStep(S)
    S.run(40)
    return S


@pytest.fixture(scope="module")
def scene():
    return scene_with_everything()


def sphere_ids(S):
    return np.flatnonzero((_dem.shape_codes(S._cpp) == 0) & (S._cpp.alive() != 0))


def test_live_ids_pick_one_shape_and_skip_erased_bodies(scene):
    codes, alive = _dem.shape_codes(scene._cpp), scene._cpp.alive()
    for code, shape in enumerate(("Sphere", "Wall", "Facet")):
        assert np.array_equal(_dem.live_ids(scene._cpp, shape), np.flatnonzero((codes == code) & (alive != 0)))
    assert np.array_equal(scene.sphere_ids(), sphere_ids(scene)) and 10 not in scene.sphere_ids()
    with pytest.raises(ValueError, match="unknown shape 'Sphrere'"):
        _dem.live_ids(scene._cpp, "Sphrere")


def test_spheres(tmp_path, scene):
    n = export.write_spheres(scene, tmp_path / "s.vtu")
    v = read_vtu(tmp_path / "s.vtu")
    ids = sphere_ids(scene)
    assert n == v["points_count"] == v["cells_count"] == len(ids) == 63       # the erased one is left out
    assert set(v["point"]) == {"radius", "velocity", "angVel", "force", "torque", "id", "materialId", "mass", "color", "nonfinite"}
    assert np.array_equal(v["points"], scene.positions()[ids])
    assert np.array_equal(v["point"]["velocity"], scene.velocities()[ids])
    assert np.array_equal(v["point"]["id"], ids) and np.all(v["point"]["radius"] == 0.09)
    assert np.all(v["types"] == export.VTK_VERTEX) and not v["point"]["nonfinite"].any()
    assert v["time"] == scene.time


def test_facets_and_walls(tmp_path, scene):
    assert export.write_facets(scene, tmp_path / "f.vtu") == 2
    f = read_vtu(tmp_path / "f.vtu")
    assert f["points_count"] == 6 and np.all(f["types"] == export.VTK_TRIANGLE)
    assert np.allclose(f["points"][:3], [(-1, -1, 0), (2, -1, 0), (2, 2, 0)], atol=1e-12)
    assert np.allclose(np.abs(f["cell"]["normal"]), [(0, 0, 1)] * 2)
    assert export.write_walls(scene, tmp_path / "w.vtu", size=3.0) == 2
    w = read_vtu(tmp_path / "w.vtu")
    assert w["points_count"] == 8 and np.all(w["types"] == export.VTK_QUAD)
    assert np.all(w["points"][:4, 0] == 0) and np.all(w["points"][4:, 1] == 1)
    assert np.ptp(w["points"][:4, 1]) == pytest.approx(3.0)
    assert list(w["cell"]["axis"]) == [0, 1]


def test_contact_network(tmp_path, scene):
    n = export.write_contacts(scene, tmp_path / "c.vtu")
    c = read_vtu(tmp_path / "c.vtu")
    real = scene.contacts()
    assert n == c["cells_count"] == len(real) == scene._cpp.realContactCount() > 20
    assert np.all(c["types"] == export.VTK_LINE) and np.all(c["cell"]["real"] == 1)
    assert np.allclose(c["cell"]["forceN"], [np.linalg.norm(r["normalForce"]) for r in real], rtol=1e-15)
    pos = scene.positions()
    ends = c["points"].reshape(-1, 2, 3)
    for k, r in enumerate(real):
        assert np.array_equal(ends[k, 1], pos[r["id2"]])
        start = pos[r["id1"]] if c["cell"]["kind"][k] == 0 else r["contactPoint"]
        assert np.array_equal(ends[k, 0], start)
    kinds = set(c["cell"]["kind"])
    assert kinds == {0, 1, 2}, "sphere, wall and facet contacts all drawn"
    everything = export.write_contacts(scene, tmp_path / "all.vtu", real_only=False)
    assert everything == scene._cpp.contactCount() >= n
    assert read_vtu(tmp_path / "all.vtu")["cell"]["real"].sum() == n


def test_periodic_contact_is_drawn_to_the_image(tmp_path):
    S = Scene()
    S.periodic = True
    S.cell.setBox((1, 1, 1))
    S.bodies.append([sphere((0.03, 0.5, 0.5), 0.05), sphere((0.95, 0.5, 0.5), 0.05)])
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *LINEAR), NewtonIntegrator()]
    S.dt = 1e-9
    S.step()
    assert export.write_contacts(S, tmp_path / "p.vtu") == 1
    a, b = read_vtu(tmp_path / "p.vtu")["points"]
    assert np.linalg.norm(b - a) == pytest.approx(0.08, rel=1e-6)   # across the boundary, not 0.92


def test_empty_scene_gives_valid_files(tmp_path):
    S = Scene()
    for write in (export.write_spheres, export.write_facets, export.write_walls, export.write_contacts):
        assert write(S, tmp_path / f"{write.__name__}.vtu") == 0
        v = read_vtu(tmp_path / f"{write.__name__}.vtu")
        assert v["points_count"] == v["cells_count"] == 0


def test_non_finite_values_are_written_and_flagged(tmp_path):
    S = scene_with_everything()
    ids = sphere_ids(S)
    S.velocities()[ids[3]] = np.nan
    with pytest.warns(export.VTKWarning, match=rf"1 spheres with non-finite values \(ids {ids[3]}\)"):
        export.write_spheres(S, tmp_path / "nan.vtu")
    v = read_vtu(tmp_path / "nan.vtu")
    assert np.isnan(v["point"]["velocity"][3]).all() and list(np.flatnonzero(v["point"]["nonfinite"])) == [3]


def test_vtk_recorder_series_and_restart(tmp_path):
    S = scene_with_everything()
    prefix = tmp_path / "out" / "run-"
    S.engines = [*S.engines, export.VTKRecorder(fileName=str(prefix), recorders=["all", "velocity"], iterPeriod=20,
                                                label="vtk")]
    S.run(61)
    for kind in ("spheres", "facets", "walls", "intrs"):
        series = read_pvd(f"{prefix}{kind}.pvd")
        assert [f for _, f in series] == [f"run-{kind}.{i}.vtu" for i in (40, 60, 80, 100)]
        times = [t for t, _ in series]
        assert times == sorted(times)
        for _, f in series:
            read_vtu(tmp_path / "out" / f)
    assert [p.name for p in (tmp_path / "out").iterdir() if ".tmp-" in p.name] == []
    if io.available():                    # the series goes on after a restart
        io.save(S, tmp_path / "ck.h5")
        T = Scene()
        io.load(T, tmp_path / "ck.h5")
        T.run(20)
        assert [f for _, f in read_pvd(f"{prefix}intrs.pvd")][-2:] == ["run-intrs.100.vtu", "run-intrs.120.vtu"]
        assert len(read_pvd(f"{prefix}intrs.pvd")) == 5
    with pytest.raises(ValueError, match="unknown recorder 'stress'"):
        export.VTKRecorder(fileName=str(prefix), recorders=["spheres", "stress"])


def test_vtk_exporter(tmp_path, scene):
    vtk = export.VTKExporter(str(tmp_path / "snap"), scene=scene)
    path = vtk.exportSpheres(what={"speed": "np.linalg.norm(b.state.vel)"})
    assert path.endswith("snap-spheres-0.vtu")
    v = read_vtu(path)
    assert np.allclose(v["point"]["speed"], np.linalg.norm(scene.velocities()[sphere_ids(scene)], axis=1))
    assert vtk.exportSpheres().endswith("snap-spheres-1.vtu")
    assert vtk.exportInteractions().endswith("snap-intrs-0.vtu")
    read_vtu(vtk.exportFacets(numLabel=7))
    walls = read_vtu(vtk.exportWalls(size=3.0))
    assert walls["points_count"] == 8 and np.all(walls["types"] == export.VTK_QUAD)
    assert vtk.exportBoxes().endswith("snap-boxes-0.vtu")   # the scene has none: a valid, empty file
    assert read_vtu(str(tmp_path / "snap-boxes-0.vtu"))["cells_count"] == 0


def test_failed_write_leaves_no_temporary(tmp_path, scene):
    (tmp_path / "taken.vtu").mkdir()
    with pytest.raises(OSError):
        export.write_spheres(scene, tmp_path / "taken.vtu")
    assert [p.name for p in tmp_path.iterdir()] == ["taken.vtu"]


@pytest.mark.skipif(shutil.which("pvpython") is None, reason="ParaView (pvpython) not installed")
def test_paraview_reads_the_files(tmp_path, scene):
    export.write_spheres(scene, tmp_path / "s.vtu")
    export.write_contacts(scene, tmp_path / "c.vtu")
    export.write_spheres(Scene(), tmp_path / "e.vtu")
    script = f"""
from paraview.simple import XMLUnstructuredGridReader
for name in ("s", "c", "e"):
    r = XMLUnstructuredGridReader(FileName=[r"{tmp_path}/" + name + ".vtu"])
    r.UpdatePipeline()
    info = r.GetDataInformation()
    print(name, info.GetNumberOfPoints(), info.GetNumberOfCells())
"""
    done = subprocess.run(["pvpython", "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    lines = dict(line.split(" ", 1) for line in done.stdout.strip().splitlines())
    n = len(sphere_ids(scene))
    assert lines["s"] == f"{n} {n}" and lines["e"] == "0 0"
    assert lines["c"].split()[1] == str(scene._cpp.realContactCount())


# ------------------------------------------------------------------------------------------------
# Progress line.

def test_progress_run_is_an_ordinary_run():
    A, B = scene_with_everything(), scene_with_everything()
    out = stdio.StringIO()
    progress.run(A, 150, interval=0.0, stream=out)
    B.run(150)
    assert np.array_equal(A.positions(), B.positions()) and A.iter == B.iter
    lines = out.getvalue().splitlines()
    assert lines and "\r" not in out.getvalue()            # not a terminal: plain lines
    assert lines[-1].startswith(f"iter {A.iter}/{A.iter} (100%)") and lines[-1].endswith("done")
    assert all("steps/s" in line and "t=" in line and "ETA" in line for line in lines)


def test_progress_on_a_terminal_rewrites_the_line():
    class Tty(stdio.StringIO):
        def isatty(self):
            return True
    out = Tty()
    p = progress.Progress(target=100, interval=0.0, stream=out)
    p.update(0, 0.0)
    p.update(50, 0.5)
    p.finish(100, 1.0, 100)
    text = out.getvalue()
    assert text.startswith("\riter 50/100 (50%)") and text.count("\r") == 2 and text.endswith("done\n")


def test_progress_reporter_engine(capsys):
    S = scene_with_everything()
    S.engines = [*S.engines, progress.ProgressReporter(target=S.iter + 200, interval=0.0)]
    S.run(200)
    err = capsys.readouterr().err
    assert "steps/s" in err and f"/{S.iter} (" in err


def test_format_line():
    assert progress.format_line(1200, 1.2e-3, 100.0, 5000) == "iter 1200/5000 (24%)  t=0.0012 s  100 steps/s  ETA 0:00:38"
    assert progress.format_line(5, 0.0, 0.0) == "iter 5  t=0 s  - steps/s"


def test_boxes_as_hexahedra(tmp_path):
    import math
    from talus.dem import box
    S = Scene()
    S.materials.append(FrictMat())
    q = (math.cos(math.pi / 8), 0, 0, math.sin(math.pi / 8))      # 45 degrees about z
    S.bodies.append([box((1, 2, 3), (0.5, 0.25, 0.125), orientation=q, fixed=True), box((0, 0, 0), (1, 1, 1))])
    assert export.write_boxes(S, str(tmp_path / "b.vtu")) == 2
    v = read_vtu(tmp_path / "b.vtu")
    assert list(v["types"]) == [12, 12] and list(v["cell"]["id"]) == [0, 1]
    p = v["points"][:8] - (1, 2, 3)
    c, s = math.cos(math.pi / 4), math.sin(math.pi / 4)
    local = np.c_[c * p[:, 0] + s * p[:, 1], -s * p[:, 0] + c * p[:, 1], p[:, 2]]   # back to the box frame
    np.testing.assert_allclose(np.abs(local), np.tile((0.5, 0.25, 0.125), (8, 1)), atol=1e-14)
    # VTK's hexahedron order: bottom face counter-clockwise, then the top face above it
    np.testing.assert_allclose(np.sign(local[:4, 2]), -1)
    np.testing.assert_allclose(local[4:, :2], local[:4, :2], atol=1e-14)
