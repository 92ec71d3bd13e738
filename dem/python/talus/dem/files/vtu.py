"""VTK XML unstructured grids (``.vtu``) written with numpy alone, for talus.dem.files.export (spheres,
facets, walls, contacts, cell) and the Potential Blocks' and Potential Particles' own writers."""

from __future__ import annotations

import base64
from xml.sax.saxutils import quoteattr

import numpy as np

_VTK_TYPES = {np.dtype(np.float64): "Float64", np.dtype(np.float32): "Float32", np.dtype(np.int64): "Int64",
              np.dtype(np.int32): "Int32", np.dtype(np.uint8): "UInt8"}


def _data_array(array: np.ndarray, name: str | None, indent: str) -> str:
    array = np.ascontiguousarray(array)
    if array.dtype.byteorder == ">":
        array = array.astype(array.dtype.newbyteorder("<"))
    components = 1 if array.ndim == 1 else int(np.prod(array.shape[1:]))
    raw = array.tobytes()
    payload = base64.b64encode(np.uint64(len(raw)).tobytes() + raw).decode("ascii")
    attrs = f'type="{_VTK_TYPES[array.dtype]}"'
    if name is not None:
        attrs += f" Name={quoteattr(name)}"
    if components != 1:
        attrs += f' NumberOfComponents="{components}"'
    return f'{indent}<DataArray {attrs} format="binary">{payload}</DataArray>\n'


def vtu_bytes(points: np.ndarray, connectivity: np.ndarray, offsets: np.ndarray, types: np.ndarray,
              point_data: dict | None = None, cell_data: dict | None = None, time: float | None = None) -> bytes:
    """The text of a ``.vtu`` file: an unstructured grid of ``points`` (n, 3) and cells given
    by VTK's connectivity, end offsets and cell types, with named point and cell arrays."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    out = ['<?xml version="1.0"?>\n',
           '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">\n',
           "  <UnstructuredGrid>\n"]
    if time is not None:
        out += ["    <FieldData>\n",
                _data_array(np.array([time], dtype=np.float64), "TimeValue", "      ").replace(
                    "<DataArray ", '<DataArray NumberOfTuples="1" ', 1),
                "    </FieldData>\n"]
    out.append(f'    <Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(types)}">\n')
    for tag, data in (("PointData", point_data or {}), ("CellData", cell_data or {})):
        out.append(f"      <{tag}>\n")
        for name, array in data.items():
            out.append(_data_array(np.asarray(array), name, "        "))
        out.append(f"      </{tag}>\n")
    out += ["      <Points>\n", _data_array(points, None, "        "), "      </Points>\n",
            "      <Cells>\n",
            _data_array(np.asarray(connectivity, dtype=np.int64), "connectivity", "        "),
            _data_array(np.asarray(offsets, dtype=np.int64), "offsets", "        "),
            _data_array(np.asarray(types, dtype=np.uint8), "types", "        "),
            "      </Cells>\n", "    </Piece>\n", "  </UnstructuredGrid>\n", "</VTKFile>\n"]
    return "".join(out).encode("ascii")
