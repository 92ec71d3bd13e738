"""Yade's shape.color, highlight and wire are kept as data: written to ParaView output and kept by
checkpoints (O.save/O.load and O.saveTmp/O.loadTmp), never read by the physics."""
import numpy as np
from test_export import read_vtu

from talus.dem import Scene, VTKExporter, box, facet, sphere


def _scene():
    S = Scene()
    S.bodies.append([sphere((0, 0, 0), 1, color=(1, 0, 0)), sphere((3, 0, 0), 1),
                     facet([(0, 0, -2), (1, 0, -2), (0, 1, -2)], color=(0, 0, 1)),
                     box((0, 5, 0), (1, 1, 1), color=(0, 1, 0))])
    S.bodies[1].shape.highlight = True
    S.bodies[1].shape.wire = True
    return S


def test_colors_are_written_to_vtk(tmp_path):
    S = _scene()
    out = VTKExporter(str(tmp_path / "look"), scene=S)
    assert np.array_equal(read_vtu(out.exportSpheres())["point"]["color"], [(1, 0, 0), (0.5, 0.5, 0.5)])
    assert np.array_equal(read_vtu(out.exportFacets())["cell"]["color"], [(0, 0, 1)])
    assert np.array_equal(read_vtu(out.exportBoxes())["cell"]["color"], [(0, 1, 0)])


def test_checkpoints_keep_the_look(tmp_path):
    S = _scene()
    S.save(str(tmp_path / "look.h5"))
    S.saveTmp("look")
    T = Scene()
    T.load(str(tmp_path / "look.h5"))
    S.bodies[0].shape.color = (0, 0, 0)
    S.loadTmp("look")
    for scene in (T, S):
        assert tuple(scene.bodies[0].shape.color) == (1, 0, 0)
        assert tuple(scene.bodies[3].shape.color) == (0, 1, 0)
        assert scene.bodies[1].shape.highlight and scene.bodies[1].shape.wire
        assert not scene.bodies[0].shape.highlight
    plain = Scene()
    plain.bodies.append([sphere((0, 0, 0), 1, color=(0, 1, 1)), sphere((3, 0, 0), 1)])
    plain.load(str(tmp_path / "look.h5"))                 # loading replaces the look with the saved one
    assert tuple(plain.bodies[0].shape.color) == (1, 0, 0) and plain.bodies[1].shape.highlight
