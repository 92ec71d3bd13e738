"""ymport: STL (ASCII and binary) and OpenFOAM polyMesh boundaries as facets, with errors naming
the file and the line."""
import struct

import numpy as np
import pytest

from talus.dem import Facet, FrictMat, Scene
from talus.dem.files import ymport

TETRA = np.array([[(0, 0, 0), (0, 1, 0), (1, 0, 0)], [(0, 0, 0), (1, 0, 0), (0, 0, 1)],
                  [(0, 0, 0), (0, 0, 1), (0, 1, 0)], [(1, 0, 0), (0, 1, 0), (0, 0, 1)]], dtype=float)


def ascii_stl(triangles) -> str:
    out = ["solid tetra"]
    for t in triangles:
        out += ["  facet normal 0 0 0", "    outer loop"] + [f"      vertex {x} {y} {z}" for x, y, z in t]
        out += ["    endloop", "  endfacet"]
    return "\n".join(out + ["endsolid tetra"]) + "\n"


def binary_stl(triangles) -> bytes:
    data = b"binary tetra".ljust(80, b" ") + struct.pack("<I", len(triangles))
    for t in triangles:
        data += struct.pack("<12fH", 0, 0, 0, *np.asarray(t, dtype=np.float32).ravel(), 0)
    return data


def test_stl_ascii_and_binary(tmp_path):
    (tmp_path / "a.stl").write_text(ascii_stl(TETRA))
    (tmp_path / "b.stl").write_bytes(binary_stl(TETRA))
    for name in ("a.stl", "b.stl"):
        np.testing.assert_array_equal(ymport.read_stl(str(tmp_path / name)), TETRA)
    S = Scene()
    S.materials.append(FrictMat())
    ids = S.bodies.append(ymport.stl(str(tmp_path / "b.stl"), scale=2.0, shift=(0, 0, 1)))
    assert len(ids) == 4 and all(isinstance(S.bodies[i].shape, Facet) for i in ids)
    from talus import _dem
    np.testing.assert_allclose(_dem.facet_arrays(S._cpp)["vertices"], TETRA * 2 + (0, 0, 1), atol=1e-15)


def test_stl_errors_name_file_and_line(tmp_path):
    bad = ascii_stl(TETRA).replace("vertex 1.0 0.0 0.0", "vertex 1.0 zero 0.0", 1)
    (tmp_path / "bad.stl").write_text(bad)
    line = bad.splitlines().index(next(l for l in bad.splitlines() if "zero" in l)) + 1
    with pytest.raises(ymport.MeshError, match=rf"bad.stl, line {line}: a vertex needs three finite numbers"):
        ymport.stl(str(tmp_path / "bad.stl"))
    (tmp_path / "short.stl").write_text(ascii_stl(TETRA).replace("endfacet", "", 1))
    with pytest.raises(ymport.MeshError, match=r"short.stl, line \d+: 'facet' inside a facet"):
        ymport.stl(str(tmp_path / "short.stl"))
    (tmp_path / "cut.stl").write_bytes(binary_stl(TETRA)[:-7] + bytes(100))
    with pytest.raises(ymport.MeshError, match="cut.stl: neither a binary STL"):
        ymport.stl(str(tmp_path / "cut.stl"))
    flat = TETRA.copy()
    flat[0] = [(0, 0, 0), (1, 0, 0), (2, 0, 0)]
    (tmp_path / "flat.stl").write_text(ascii_stl(flat))
    with pytest.warns(ymport.MeshWarning, match="skipped 1 degenerate"):
        assert len(ymport.stl(str(tmp_path / "flat.stl"))) == 3


HEADER = """FoamFile
{{
    version     2.0;
    format      ascii;
    class       {cls};
    object      {obj};
}}
// comment
"""


def write_cube(folder, faces_text=None):
    """The unit cube as one hex cell: 8 points, 6 boundary faces in patches 'walls' (4 sides),
    'inlet' (z = 0) and 'outlet' (z = 1)."""
    mesh = folder / "constant" / "polyMesh"
    mesh.mkdir(parents=True)
    pts = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    (mesh / "points").write_text(HEADER.format(cls="vectorField", obj="points") + f"{len(pts)}\n(\n"
                                 + "".join(f"({x} {y} {z})\n" for x, y, z in pts) + ")\n")
    faces = faces_text or ("6\n(\n4(0 4 6 2)\n4(1 3 7 5)\n4(0 1 5 4)\n4(2 6 7 3)\n"
                           "4(0 2 3 1)\n4(4 5 7 6)\n)\n")
    (mesh / "faces").write_text(HEADER.format(cls="faceList", obj="faces") + faces)
    (mesh / "boundary").write_text(HEADER.format(cls="polyBoundaryMesh", obj="boundary") + """3
(
    walls { type wall; inGroups 1(wall); nFaces 4; startFace 0; }
    inlet { type patch; nFaces 1; startFace 4; }
    outlet
    {
        type patch;
        nFaces 1;
        startFace 5;
    }
)
""")
    return mesh


def test_polymesh_patches(tmp_path):
    write_cube(tmp_path)
    triangles, groups = ymport.read_polymesh(str(tmp_path))
    assert len(triangles) == 12 and list(groups) == ["walls", "inlet", "outlet"]
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    outward = triangles.mean(axis=1) - 0.5
    assert np.all(np.einsum("ij,ij->i", normals, outward) > 0)     # out of the fluid domain
    specs = ymport.polyMesh(str(tmp_path), patches=["inlet", "outlet"])
    z = np.array([s.vertices for s in specs])[:, :, 2]
    assert len(specs) == 4 and set(z.ravel()) == {0.0, 1.0}
    with pytest.raises(ymport.MeshError, match="no patch 'top' \\(patches: walls, inlet, outlet\\)"):
        ymport.polyMesh(str(tmp_path), patches=["top"])


def test_polymesh_errors_name_file_and_line(tmp_path):
    mesh = write_cube(tmp_path / "a", faces_text="6\n(\n4(0 4 6 2)\n4(1 3 7 5)\n4(0 1 x 4)\n")
    with pytest.raises(ymport.MeshError, match=r"faces, line 13: expected a point label, found 'x'"):
        ymport.polyMesh(str(tmp_path / "a"))
    mesh = write_cube(tmp_path / "b", faces_text="7\n(\n4(0 4 6 2)\n4(1 3 7 5)\n4(0 1 5 4)\n4(2 6 7 3)\n"
                                                 "4(0 2 3 1)\n4(4 5 7 6)\n)\n")
    with pytest.raises(ymport.MeshError, match=r"faces, line 9: the list announces 7 entries but has 6"):
        ymport.polyMesh(str(tmp_path / "b"))
    (mesh / "points").write_text((mesh / "points").read_text().replace("ascii", "binary"))
    with pytest.raises(ymport.MeshError, match="points, line .*format binary is not supported"):
        ymport.polyMesh(str(tmp_path / "b"))
    with pytest.raises(ymport.MeshError, match="cannot read"):
        ymport.polyMesh(str(tmp_path / "nowhere"))


def outward(triangles, centre):
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    return np.einsum("ij,ij->i", normals, triangles.mean(axis=1) - centre)


def test_blockmeshdict_of_a_built_case(tmp_path):
    """The settling-sphere box as the CFD case builder writes it: 6 block faces, each its own
    patch, two triangles each, normals out of the fluid."""
    case_builder = pytest.importorskip("talus.coupling.case_builder")
    case_builder.cfd_case(tmp_path / "box", box=((-0.0225, -0.0225, 0), (0.0225, 0.0225, 0.09)), cells=(9, 9, 18),
                          rho=1000, nu=1e-3, coupling_interval=2e-5, run_mesh=False)
    triangles, groups = ymport.read_blockmeshdict(str(tmp_path / "box"))
    assert len(triangles) == 12 and list(groups) == ["x0", "x1", "y0", "y1", "z0", "z1"]
    assert all(len(faces) == 2 for faces in groups.values())
    assert np.allclose(triangles.reshape(-1, 3).min(axis=0), [-0.0225, -0.0225, 0])
    assert np.allclose(triangles.reshape(-1, 3).max(axis=0), [0.0225, 0.0225, 0.09])
    assert np.all(outward(triangles, [0, 0, 0.045]) > 0)
    area = 0.5 * np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1)
    assert area.sum() == pytest.approx(2 * 0.045 * 0.045 + 4 * 0.045 * 0.09, rel=1e-12)
    assert area[groups["z0"]].sum() == pytest.approx(0.045 * 0.045, rel=1e-12)


BLOCKS = HEADER.format(cls="dictionary", obj="blockMeshDict") + """
convertToMeters 0.001;
vertices ( (0 0 0) (100 0 0) (100 100 0) (0 100 0) (0 0 100) (100 0 100) (100 100 100) (0 100 100)
           (0 0 200) (100 0 200) (100 100 200) (0 100 200) );
blocks ( hex (0 1 2 3 4 5 6 7) (4 4 4) simpleGrading (1 1 1)
         hex (4 5 6 7 8 9 10 11) lower (4 4 4) simpleGrading (1 1 ((0.5 0.5 2) (0.5 0.5 0.5))) );
edges ( );
boundary
(
    sides { type wall; faces ( (2 3 6 7) (0 1 5 4) (4 7 3 0) (5 1 2 6) (6 7 11 10) (4 5 9 8) (7 4 8 11) (5 6 10 9) ); }
    bottom { type patch; faces ( (0 1 2 3) ); }
    top { type patch; faces ( (8 9 10 11) ); }
);
mergePatchPairs ( );
"""


def test_blockmeshdict_faces_in_any_order_come_out_outward(tmp_path):
    """Faces listed with their vertices in any order (as Yade's OpenFOAM example does, and as
    blockMesh accepts) take the block's outward order; two blocks, convertToMeters."""
    path = tmp_path / "blockMeshDict"
    path.write_text(BLOCKS)
    triangles, groups = ymport.read_blockmeshdict(str(path))
    assert [len(groups[p]) for p in ("sides", "bottom", "top")] == [16, 2, 2]
    assert np.all(outward(triangles, [0.05, 0.05, 0.1]) > 0)
    specs = ymport.blockMeshDict(str(path), patches=["top"])
    assert len(specs) == 2 and np.allclose(np.array([s.vertices for s in specs])[:, :, 2], 0.2)


def test_blockmeshdict_errors_name_file_and_line(tmp_path):
    path = tmp_path / "blockMeshDict"
    path.write_text(BLOCKS.replace("(8 9 10 11)", "(8 9 10 2)"))
    with pytest.raises(ymport.MeshError, match=r"blockMeshDict, line 20: face \(8, 9, 10, 2\) of patch 'top' is not a face of any block"):
        ymport.read_blockmeshdict(str(path))
    path.write_text(BLOCKS.replace("convertToMeters 0.001;", "convertToMeters $scale;"))
    with pytest.raises(ymport.MeshError, match=r"line 10: '\$scale': macros are not supported"):
        ymport.read_blockmeshdict(str(path))
    path.write_text(BLOCKS.replace("edges ( );", "edges ( arc 0 1 (50 -10 0) );"))
    with pytest.raises(ymport.MeshError, match=r"line 15: curved edges are not supported"):
        ymport.read_blockmeshdict(str(path))
    path.write_text(BLOCKS)
    with pytest.raises(ymport.MeshError, match="no patch 'inlet' \\(patches: sides, bottom, top\\)"):
        ymport.blockMeshDict(str(path), patches=["inlet"])
