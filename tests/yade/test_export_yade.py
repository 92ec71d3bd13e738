"""yade.export as Yade 2023.02a: exportFacetsAsMesh, exportPeriodicCell, VTKRecorder's
'pericell', textExt/text (same text), text2vtk and text2vtkSection (same files)."""
from pathlib import Path

import numpy as np
import pytest

from talus.dem import Scene, sphere
from talus.dem.files import export
from talus import twin
from talus.dem.files import text_export

HERE = Path(__file__).parent


@pytest.fixture(scope="module")
def both():
    return {who: twin.run(HERE / "side_by_side" / "export_side_by_side.py", {}, who) for who in ("talus", "yade")}


def geometry(vtk: dict) -> tuple[np.ndarray, list]:
    return np.array(vtk["points"]), vtk["cells"]


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
@pytest.mark.parametrize("what", ["mesh", "cell", "pericell"])
def test_vtk_geometry_as_yade(both, what):
    (ours, our_cells), (theirs, their_cells) = geometry(both["talus"][what]), geometry(both["yade"][what])
    assert our_cells == their_cells
    assert len(ours) == len(theirs) > 0
    # Yade's legacy files have %g numbers (6 digits), its recorder's Float32.
    assert np.allclose(ours, theirs, rtol=2e-6, atol=1e-5 * np.abs(theirs).max())


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
def test_text_files_as_yade(both):
    ours, theirs = both["talus"]["texts"], both["yade"]["texts"]
    assert theirs["x_y_z_r"][0] == 12 and "SCALARS r double" in theirs["attrs-section.vtk"]
    assert theirs["plain-section.vtk"].count("\n") > 20      # the plane cuts some spheres
    assert ours == theirs


def test_bad_arguments_are_named(tmp_path):
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 1))
    with pytest.raises(ValueError, match="format='liggghts_in'"):
        text_export.textExt(str(tmp_path / "a.txt"), format="liggghts_in", scene=S)
    assert text_export.text(str(tmp_path / "a.txt"), mask=2, scene=S) == 0     # its mask is 1
    text_export.text(str(tmp_path / "a.txt"), scene=S)
    with pytest.raises(ValueError, match="normal"):
        text_export.text2vtkSection(str(tmp_path / "a.txt"), str(tmp_path / "a.vtk"), (0, 0, 0), normal=(0, 0, 0))
    vtk = export.VTKExporter(str(tmp_path / "x"), scene=S)
    with pytest.raises(ValueError, match="connectivityTable"):
        vtk.exportFacetsAsMesh()
    with pytest.warns(export.VTKWarning, match="not periodic"):
        assert vtk.exportPeriodicCell() is None
    with pytest.raises(ValueError, match="not periodic"):
        export.write_periodic_cell(S, str(tmp_path / "c.vtu"))
