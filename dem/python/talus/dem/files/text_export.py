"""Spheres as text, and that text as legacy VTK: Yade's ``export.textExt``, ``export.text``,
``export.text2vtk`` and ``export.text2vtkSection``, with Yade's file formats.

A text file starts with ``#format <name>`` and optional ``#`` comment lines, then one
tab-separated line per sphere (``%g`` numbers, in body id order; clump members included):

- ``x_y_z_r``: centre and radius;
- ``x_y_z_r_matId``: and the index of the material in ``O.materials``;
- ``id_x_y_z_r_matId``: the body id first;
- ``x_y_z_r_attrs``: and the values of Python expressions of ``b`` (the Body), scalars, vectors
  (3 columns) or 3x3 matrices (9 columns); the last comment line names the columns.

``text2vtk`` turns such a file into a VTK legacy POLYDATA file (a point per sphere, the radius and
each extra column as point scalars); ``text2vtkSection`` keeps the spheres a plane cuts, as the
discs of the cut (centre projected on the plane, radius of the disc, the original radius, the
plane's normal and the extra columns).
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from talus.dem.core.scenes import default_scene
from talus.dem.files import vtk_split

_FORMATS = ("x_y_z_r", "x_y_z_r_matId", "id_x_y_z_r_matId", "x_y_z_r_attrs")


def textExt(filename: str, format: str = "x_y_z_r", comment: str = "", mask: int = -1,
            attrs: Sequence[str] = (), scene=None) -> int:
    """Write the spheres of ``scene`` (default O) to ``filename`` in ``format``; returns their
    number. ``comment``: lines after the format line (with ``x_y_z_r_attrs``, its last line
    names the ``attrs`` columns, after Yade's ``# x y z r``); ``mask`` >= 0: only the spheres whose
    mask shares a bit with it (Yade's)."""
    O = default_scene()
    scene = scene or O
    if format not in _FORMATS:
        raise ValueError(f"textExt: format={format!r} is not supported; Talus writes {', '.join(_FORMATS)}")
    lines = [f"#format {format}\n", *_comment_lines(format, comment)]
    # Under mpirun each process holds its own spheres: process 0 writes them all (vtk_split).
    rows = vtk_split.owned(scene, scene.sphere_ids())
    ids = vtk_split.global_ids(scene, rows)
    if mask >= 0:
        keep = np.array([bool(scene.bodies._here(i).mask & mask) for i in ids], dtype=bool)
        rows, ids = rows[keep], ids[keep]
    cpp = scene._cpp
    table = {"id": ids, "pos": cpp.pos()[rows], "radius": cpp.radius()[rows], "material": cpp.materialIds()[rows]}
    if format == "x_y_z_r_attrs":
        values = [_attribute_values(attrs, scene.bodies._here(i)) for i in ids]
        width = len(values[0]) if values else 0
        if vtk_split.is_split(scene):   # (a process without spheres learns the width from the others)
            width = int(-scene._domain.minima([-float(width)])[0])
        table["attrs"] = np.array(values, dtype=float).reshape(len(ids), width)
    table = vtk_split.gather(scene, table, ("id",))
    if table is not None:   # (None: another process writes)
        for k, i in enumerate(table["id"]):
            columns = [*table["pos"][k], table["radius"][k]]
            if format == "id_x_y_z_r_matId":
                line = "%d\t%g\t%g\t%g\t%g\t%d\n" % (i, *columns, table["material"][k])
            else:
                line = "\t".join("%g" % c for c in columns)
                if format == "x_y_z_r_matId":
                    line += "\t%d" % table["material"][k]
                elif format == "x_y_z_r_attrs":
                    line += "".join("\t%g" % v for v in table["attrs"][k])
                line += "\n"
            lines.append(line)
        with open(filename, "w") as out:
            out.writelines(lines)
    return vtk_split.total(scene, len(ids))


def text(filename: str, mask: int = -1, scene=None) -> int:
    """``x y z r`` of each sphere (``textExt`` with format ``x_y_z_r``); returns their number."""
    return textExt(filename, "x_y_z_r", mask=mask, scene=scene)


def _comment_lines(format: str, comment: str) -> list[str]:
    if not comment:
        return []
    if format != "x_y_z_r_attrs":
        return [f"# {comment}\n"]
    # Yade joins the lines before the last without separators, then names the columns.
    *before, last = comment.split("\n")
    return ["".join(before) + f"# x y z r {last}\n"]


def _attribute_values(attrs: Sequence[str], b) -> list[float]:
    values = []
    for expression in attrs:
        value = eval(expression, {"np": np}, {"b": b})
        values += [float(v) for v in np.asarray(value, dtype=float).reshape(-1)]
    return values


def _read_text(inFileName: str) -> tuple[str, list[list[str]]]:
    """The last ``#`` line (the column names) and the words of each sphere line of a text file."""
    header, rows = "", []
    with open(inFileName) as f:
        for line in f:
            if not rows and line.startswith("#"):
                header = line
            elif line.strip():
                rows.append(line.split())
    return header, rows


def _vtk_head(comment: str, n: int) -> str:
    return f"# vtk DataFile Version 3.0.\n{comment}\nASCII\n\nDATASET POLYDATA\nPOINTS {n} double\n"


def text2vtk(inFileName: str, outFileName: str, comment: str = "comment") -> None:
    """The spheres of a ``textExt`` file (``x y z r`` and extra columns, named by its last
    comment line) as a VTK legacy file of points with point scalars ``radius`` and each column.
    Numbers are copied as written."""
    header, rows = _read_text(inFileName)
    names = header[1:].split()[4:]
    out = [_vtk_head(comment, len(rows)), *("%s %s %s\n" % tuple(r[:3]) for r in rows)]
    out.append(f"\nPOINT_DATA {len(rows)}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
    out += [f"{r[3]}\n" for r in rows]
    for k, name in enumerate(names):
        out.append(f"\nSCALARS {name} double 1\nLOOKUP_TABLE default\n")
        out += [f"{r[4 + k]}\n" for r in rows]
    with open(outFileName, "w") as f:
        f.writelines(out)


def text2vtkSection(inFileName: str, outFileName: str, point, normal=(1, 0, 0)) -> None:
    """The discs where the plane through ``point`` with ``normal`` cuts the spheres of a
    ``textExt`` file, as a VTK legacy file: points at the discs' centres, point scalars
    ``radius`` (the disc's), ``radiusOrig`` (the sphere's), vectors ``normal``, then, as Yade
    writes them, one scalar per name of the last comment line after ``x y z``: ``r`` (the
    sphere's radius again) and the file's extra columns. Yade's reader skips the first sphere
    line of the file (it is never cut); Talus's takes every sphere."""
    length = math.sqrt(sum(float(c) ** 2 for c in normal))
    if not length > 0:
        raise ValueError(f"text2vtkSection: normal={tuple(normal)} has no direction")
    n = [float(c) / length for c in normal]
    p = [float(c) for c in point]
    offset = -n[0] * p[0] - n[1] * p[1] - n[2] * p[2]        # the plane: n.x + offset = 0
    header, rows = _read_text(inFileName)
    names = header.split()[4:]      # Yade's: "#", "x", "y", "z" dropped, so "r" comes first
    discs = []
    for row in rows:
        c = [float(w) for w in row]
        # The projection of the centre on the plane, with Yade's arithmetic (same cut-off bits).
        t = (-offset - n[0] * c[0] - n[1] * c[1] - n[2] * c[2]) / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
        centre = [c[k] + t * n[k] for k in range(3)]
        distance = math.sqrt(sum((centre[k] - c[k]) ** 2 for k in range(3)))
        if distance > c[3]:
            continue
        discs.append([*centre, math.sqrt(c[3] * c[3] - distance * distance), *c[3:]])
    if discs and len(names) > len(discs[0]) - 4:
        raise ValueError(f"text2vtkSection: the last comment line of {inFileName} names {len(names)} columns "
                         f"after x y z ({' '.join(names)}), the sphere lines have {len(discs[0]) - 4}")
    out = [_vtk_head("comment", len(discs)), *("%g %g %g\n" % tuple(d[:3]) for d in discs)]
    out.append(f"\nPOINT_DATA {len(discs)}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
    out += ["%g\n" % d[3] for d in discs]
    out.append("\nSCALARS radiusOrig double 1\nLOOKUP_TABLE default\n")
    out += ["%g\n" % d[4] for d in discs]
    out.append("\nVECTORS normal double\n")
    out += ["%g %g %g\n" % tuple(n) for _ in discs]
    for k, name in enumerate(names):
        out.append(f"\nSCALARS {name} double 1\nLOOKUP_TABLE default\n")
        out += ["%s\n" % d[4 + k] for d in discs]
    with open(outFileName, "w") as f:
        f.writelines(out)


__all__ = ["textExt", "text", "text2vtk", "text2vtkSection"]
