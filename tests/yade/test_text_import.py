"""yade.ymport.textExt and text as Yade 2023.02a (same spheres from the same files), and a
malformed file named with its line."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.dem.files.text_import import TextImportError, textExt

HERE = Path(__file__).parent


@pytest.fixture(scope="module")
def both():
    return {who: twin.run(HERE / "side_by_side" / "text_import_side_by_side.py", {}, who) for who in ("talus", "yade")}


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")
@pytest.mark.parametrize("name", ["plain", "matId", "idMatId", "attrs", "text"])
def test_spheres_as_yade(both, name):
    ours, theirs = both["talus"][name], both["yade"][name]
    assert len(theirs["pos"]) >= 1
    assert np.allclose(ours["pos"], theirs["pos"], rtol=1e-15, atol=0)
    assert np.allclose(ours["radius"], theirs["radius"], rtol=1e-15, atol=0)
    for key in ("material", "dynamic", "attrs"):
        assert ours.get(key) == theirs.get(key)


@pytest.mark.parametrize("content, message", [
    ("0 0 0 1\n0 0 0\n", r"a\.spheres, line 2: format x_y_z_r needs 4 columns, got 3"),
    ("#format x_y_z_r_matId\n0 0 0 1 soft\n", r"line 2: format x_y_z_r_matId needs numbers"),
    ("\n0 0 nan 1\n", r"line 2: non-finite"),
    ("0 0 0 -1\n", r"line 1: the radius must be positive"),
    ("#format\n", r"line 1: '#format' without a format name"),
    ("#format x_y_z\n1 2 3\n", r"line 2: format 'x_y_z' is not one of"),
])
def test_malformed_line_is_named(tmp_path, content, message):
    path = tmp_path / "a.spheres"
    path.write_text(content)
    with pytest.raises(TextImportError, match=message):
        textExt(str(path))


def test_missing_file_and_material_clash_are_named(tmp_path):
    with pytest.raises(TextImportError, match="nowhere.spheres: cannot read"):
        textExt(str(tmp_path / "nowhere.spheres"))
    path = tmp_path / "m.spheres"
    path.write_text("0 0 0 1 0\n")
    with pytest.raises(TypeError, match="material from the file"):
        textExt(str(path), "x_y_z_r_matId", material=0)
