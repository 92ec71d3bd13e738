"""Import of triangle meshes as facets (Yade's ``ymport``): STL files, I-DEAS universal files
(``unv``, from Salome and FEM codes) and OpenFOAM boundaries (a polyMesh, or the blocks of a
blockMeshDict), the walls of a CFD-DEM coupling.

    from talus.dem import ymport
    O.bodies.append(ymport.stl("hopper.stl", scale=1e-3))
    O.bodies.append(ymport.polyMesh("case", patches=["walls", "inlet"]))
    O.bodies.append(ymport.blockMeshDict("case/system/blockMeshDict", patches=["walls"]))

A malformed file raises ``MeshError`` naming the file and the line. Degenerate triangles
(collinear vertices, as left by CAD exporters) are skipped with a ``MeshWarning``.
"""

from __future__ import annotations

import gzip
import os
import re
import struct
import warnings
from typing import Iterable, Sequence

import numpy as np

from talus.dem.core.bodies import BodySpec, facet

__all__ = ["MeshError", "MeshWarning", "stl", "polyMesh", "blockMeshDict", "unv", "read_stl", "read_polymesh",
           "read_blockmeshdict", "read_unv"]


class MeshError(ValueError):
    """A mesh file could not be read (the message names the file and the line)."""


class MeshWarning(UserWarning):
    """Something of a mesh was left out (degenerate triangles)."""


def _transform(triangles: np.ndarray, scale: float, shift) -> np.ndarray:
    shift = np.asarray(shift, dtype=float).reshape(3)
    return triangles * float(scale) + shift


def _facets(triangles: np.ndarray, source: str, material, **kw) -> list[BodySpec]:
    """Facets of the non-degenerate triangles (n, 3, 3)."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    perimeter = (np.linalg.norm(b - a, axis=1) + np.linalg.norm(c - b, axis=1) + np.linalg.norm(a - c, axis=1))
    keep = area2 > 1e-12 * perimeter ** 2
    if not keep.all():
        warnings.warn(f"{source}: skipped {int((~keep).sum())} degenerate triangle(s) (collinear vertices)",
                      MeshWarning, stacklevel=3)
    return [facet(t, material=material, **kw) for t in triangles[keep]]


# ------------------------------------------------------------------------------------------------
# STL

def read_stl(file: str) -> np.ndarray:
    """Triangles (n, 3, 3) of an ASCII or binary STL file."""
    with open(file, "rb") as f:
        data = f.read()
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if len(data) == 84 + 50 * count:     # binary: 80-byte header, count, 50 bytes a triangle
            record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
            triangles = np.frombuffer(data, dtype=record, count=count, offset=84)["v"].astype(np.float64)
            if not np.all(np.isfinite(triangles)):
                bad = int(np.flatnonzero(~np.isfinite(triangles).all(axis=(1, 2)))[0])
                raise MeshError(f"{file}: triangle {bad} (binary STL) has non-finite coordinates")
            return triangles
    try:
        text = data.decode("ascii")
    except UnicodeDecodeError:
        raise MeshError(f"{file}: neither a binary STL (size {len(data)} bytes does not match its triangle "
                        f"count) nor an ASCII one (non-ASCII bytes)") from None
    return _read_ascii_stl(file, text)


def _read_ascii_stl(file: str, text: str) -> np.ndarray:
    lines = text.splitlines()
    triangles, current = [], None
    started = False
    for number, line in enumerate(lines, 1):
        words = line.split()
        if not words:
            continue
        key = words[0].lower()
        where = f"{file}, line {number}"
        if key == "solid":
            started = True
        elif not started:
            raise MeshError(f"{where}: an ASCII STL starts with 'solid', found {line.strip()!r}")
        elif key == "facet":
            if current is not None:
                raise MeshError(f"{where}: 'facet' inside a facet (missing 'endfacet')")
            current = []
        elif key == "vertex":
            if current is None:
                raise MeshError(f"{where}: 'vertex' outside a facet")
            try:
                xyz = [float(w) for w in words[1:]]
            except ValueError:
                xyz = []
            if len(xyz) != 3 or not all(np.isfinite(xyz)):
                raise MeshError(f"{where}: a vertex needs three finite numbers, got {line.strip()!r}")
            current.append(xyz)
        elif key == "endfacet":
            if current is None or len(current) != 3:
                raise MeshError(f"{where}: a facet needs exactly 3 vertices, got "
                                f"{0 if current is None else len(current)}")
            triangles.append(current)
            current = None
        elif key in ("outer", "endloop", "endsolid"):
            pass
        else:
            raise MeshError(f"{where}: unexpected {words[0]!r} in an ASCII STL")
    if current is not None:
        raise MeshError(f"{file}, line {len(lines)}: the file ends inside a facet")
    if not started:
        raise MeshError(f"{file}: empty file")
    return np.array(triangles, dtype=np.float64).reshape(-1, 3, 3)


def stl(file: str, material=-1, scale: float = 1.0, shift=(0.0, 0.0, 0.0), **kw) -> list[BodySpec]:
    """Facets of an ASCII or binary STL file (Yade's ymport.stl), scaled then shifted. Append
    them to ``O.bodies``."""
    return _facets(_transform(read_stl(file), scale, shift), file, material)


# ------------------------------------------------------------------------------------------------
# OpenFOAM polyMesh

_TOKEN = re.compile(r"\s+|//[^\n]*|/\*.*?\*/|[(){};]|[^\s(){};]+", re.S)


class _Tokens:
    """Tokens of an OpenFOAM dictionary file with their line numbers (comments dropped)."""

    def __init__(self, path: str, text: str):
        self.path = path
        self.items: list[tuple[str, int]] = []
        line = 1
        for m in _TOKEN.finditer(text):
            t = m.group()
            if not (t.isspace() or t.startswith("//") or t.startswith("/*")):
                self.items.append((t, line))
            line += t.count("\n")
        self.k = 0
        self.last_line = line

    def error(self, message: str, line: int | None = None) -> MeshError:
        if line is None:
            line = self.items[self.k][1] if self.k < len(self.items) else self.last_line
        return MeshError(f"{self.path}, line {line}: {message}")

    def peek(self) -> str | None:
        return self.items[self.k][0] if self.k < len(self.items) else None

    def next(self, what: str) -> str:
        if self.k >= len(self.items):
            raise self.error(f"unexpected end of file, expected {what}")
        t = self.items[self.k][0]
        self.k += 1
        return t

    def expect(self, token: str):
        t = self.next(repr(token))
        if t != token:
            raise self.error(f"expected {token!r}, found {t!r}", self.items[self.k - 1][1])

    def number(self, kind=float, what: str = "a number"):
        t = self.next(what)
        try:
            return kind(t)
        except ValueError:
            raise self.error(f"expected {what}, found {t!r}", self.items[self.k - 1][1]) from None

    def dictionary(self) -> dict:
        """{ key value; ... } with nested dictionaries; values as token lists."""
        self.expect("{")
        out = {}
        while self.peek() != "}":
            key = self.next("a key or '}'")
            if self.peek() == "{":
                out[key] = self.dictionary()
                continue
            value = []
            while self.peek() != ";":
                value.append(self.next("';'"))
            self.expect(";")
            out[key] = value
        self.expect("}")
        return out


def _open_foam(path: str) -> _Tokens:
    """Tokens of an ASCII OpenFOAM file after its FoamFile header (``path`` or ``path.gz``)."""
    if not os.path.exists(path) and os.path.exists(path + ".gz"):
        path += ".gz"
    try:
        raw = gzip.open(path).read() if path.endswith(".gz") else open(path, "rb").read()
    except OSError as e:
        raise MeshError(f"{path}: cannot read ({e.strerror or e})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise MeshError(f"{path}: not a text file (binary OpenFOAM files are not supported: run "
                        f"foamFormatConvert or set writeFormat ascii)") from None
    tokens = _Tokens(path, text)
    if tokens.peek() == "FoamFile":
        tokens.next("FoamFile")
        header = tokens.dictionary()
        if header.get("format", ["ascii"])[0] != "ascii":
            raise tokens.error(f"format {header['format'][0]} is not supported (ascii only: run foamFormatConvert)")
    return tokens


def _list(tokens: _Tokens, item) -> list:
    """An OpenFOAM list: optional count, then ( items ); checks the count."""
    count = None
    if tokens.peek() not in ("(", None):
        line = tokens.items[tokens.k][1]
        count = tokens.number(int, "a list size")
    tokens.expect("(")
    out = []
    while tokens.peek() != ")":
        if tokens.peek() is None:
            raise tokens.error("unexpected end of file inside a list")
        out.append(item(tokens))
    tokens.expect(")")
    if count is not None and count != len(out):
        raise tokens.error(f"the list announces {count} entries but has {len(out)}", line)
    return out


def _point(tokens: _Tokens):
    tokens.expect("(")
    p = [tokens.number(float, "a coordinate") for _ in range(3)]
    tokens.expect(")")
    return p


def _face(tokens: _Tokens):
    line = tokens.items[tokens.k][1] if tokens.k < len(tokens.items) else None
    t = tokens.next("a face")
    try:
        n = int(t)  # "4(0 1 2 3)": the tokenizer splits the count from its parenthesis
    except ValueError:
        raise tokens.error(f"expected a face 'n(a b c ...)', found {t!r}", line) from None
    tokens.expect("(")
    labels = [tokens.number(int, "a point label") for _ in range(n)]
    tokens.expect(")")
    if n < 3:
        raise tokens.error(f"a face needs at least 3 points, got {n}", line)
    return labels


def read_polymesh(case: str, patches: Iterable[str] | None = None) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Triangles (n, 3, 3) of the chosen boundary patches of ``case`` (its ``constant/polyMesh``,
    or ``case`` itself if it is a polyMesh folder), and the triangle indices of each patch.
    Polygons are split into fans from their first point, keeping OpenFOAM's orientation
    (normals out of the fluid domain)."""
    folder = case
    if not os.path.exists(os.path.join(folder, "boundary")):
        folder = os.path.join(case, "constant", "polyMesh")
    t = _open_foam(os.path.join(folder, "points"))
    points = np.array(_list(t, _point), dtype=np.float64).reshape(-1, 3)
    t = _open_foam(os.path.join(folder, "faces"))
    face_tokens = t
    faces = _list(t, _face)
    t = _open_foam(os.path.join(folder, "boundary"))

    def entry(tokens: _Tokens):
        return tokens.next("a patch name"), tokens.dictionary(), tokens.items[tokens.k - 1][1]

    boundary = _list(t, entry)
    known = [name for name, _, _ in boundary]
    wanted = list(known if patches is None else patches)
    missing = [p for p in wanted if p not in known]
    if missing:
        raise MeshError(f"{os.path.join(folder, 'boundary')}: no patch {missing[0]!r} (patches: {', '.join(known)})")
    triangles, groups = [], {}
    for name, d, line in boundary:
        if name not in wanted:
            continue
        try:
            start, n = int(d["startFace"][0]), int(d["nFaces"][0])
        except (KeyError, IndexError, ValueError):
            raise t.error(f"patch {name!r} needs integer startFace and nFaces", line) from None
        if start < 0 or n < 0 or start + n > len(faces):
            raise t.error(f"patch {name!r} covers faces {start}..{start + n - 1} but the mesh has {len(faces)}", line)
        first = len(triangles)
        for f in range(start, start + n):
            labels = faces[f]
            if max(labels) >= len(points) or min(labels) < 0:
                raise face_tokens.error(f"face {f} refers to point {max(labels)} but there are {len(points)} points")
            for k in range(1, len(labels) - 1):
                triangles.append(points[[labels[0], labels[k], labels[k + 1]]])
        groups[name] = np.arange(first, len(triangles))
    return np.array(triangles, dtype=np.float64).reshape(-1, 3, 3), groups


def polyMesh(case: str, patches: Sequence[str] | None = None, material=-1, scale: float = 1.0,
             shift=(0.0, 0.0, 0.0), **kw) -> list[BodySpec]:
    """Facets of the boundary patches ``patches`` (default: all) of an OpenFOAM case or polyMesh
    folder, scaled then shifted; their normals point out of the fluid domain."""
    triangles, _ = read_polymesh(case, patches)
    return _facets(_transform(triangles, scale, shift), case, material)


# ------------------------------------------------------------------------------------------------
# OpenFOAM blockMeshDict

# The faces of OpenFOAM's hex block in its local vertex numbering, each ordered so that its normal
# (right-hand rule) points out of the block: x-min, x-max, y-min, y-max, z-min, z-max.
_HEX_FACES = ((0, 4, 7, 3), (1, 2, 6, 5), (0, 1, 5, 4), (3, 7, 6, 2), (0, 3, 2, 1), (4, 5, 6, 7))


def _skip_entry(tokens: _Tokens):
    """Skip the value of a top-level entry: tokens up to the ';' outside any bracket, or one
    braced dictionary."""
    if tokens.peek() == "{":
        tokens.dictionary()
        return
    depth = 0
    while True:
        t = tokens.next("';'")
        depth += t in "({" and len(t) == 1
        depth -= t in ")}" and len(t) == 1
        if t == ";" and depth == 0:
            return


def _labels(tokens: _Tokens, what: str) -> tuple[list[int], int]:
    line = tokens.items[tokens.k][1] if tokens.k < len(tokens.items) else tokens.last_line
    tokens.expect("(")
    out = []
    while tokens.peek() != ")":
        out.append(tokens.number(int, f"a vertex label of {what}"))
    tokens.expect(")")
    return out, line


def _block(tokens: _Tokens) -> tuple[list[int], int]:
    """``hex (8 labels) [zone] (nx ny nz) grading (...)``: the 8 vertex labels."""
    line = tokens.items[tokens.k][1] if tokens.k < len(tokens.items) else tokens.last_line
    shape = tokens.next("a block shape")
    if shape != "hex":
        raise tokens.error(f"block shape {shape!r} is not supported (hex only)", line)
    labels, _ = _labels(tokens, "a hex block")
    if len(labels) != 8:
        raise tokens.error(f"a hex block has 8 vertices, this one {len(labels)}", line)
    if tokens.peek() != "(":
        tokens.next("a cell zone name")
    _labels(tokens, "the cell counts")
    tokens.next("a grading keyword")
    _skip_group(tokens, "the grading")   # one list, possibly of lists (multi-grading)
    return labels, line


def _skip_group(tokens: _Tokens, what: str):
    """Skip one parenthesised group, nested groups included."""
    depth = 0
    while True:
        t = tokens.next(what)
        depth += t == "("
        depth -= t == ")"
        if depth == 0:
            return


def _edge(tokens: _Tokens):
    """A curved edge (``arc 1 5 (x y z)``, ``spline 1 2 ((...) ...)``), read only to refuse it."""
    tokens.next("an edge type")
    tokens.number(int, "an edge's first vertex")
    tokens.number(int, "an edge's second vertex")
    _skip_group(tokens, "an edge's points")


def _patch_dictionary(tokens: _Tokens) -> tuple[str, list, int]:
    """``name { type ...; faces ( (a b c d) ... ); }``"""
    name = tokens.next("a patch name")
    line = tokens.items[tokens.k - 1][1]
    tokens.expect("{")
    faces = None
    while tokens.peek() != "}":
        key = tokens.next("a key or '}'")
        if key == "faces":
            faces = _list(tokens, lambda t: _labels(t, f"a face of patch {name!r}"))
            tokens.expect(";")
        else:
            _skip_entry(tokens)
    tokens.expect("}")
    if faces is None:
        raise tokens.error(f"patch {name!r} has no faces", line)
    return name, faces, line


def _patch_list(tokens: _Tokens) -> tuple[str, list, int]:
    """The older ``patches`` syntax: ``type name ( (a b c d) ... )``."""
    tokens.next("a patch type")
    name = tokens.next("a patch name")
    line = tokens.items[tokens.k - 1][1]
    return name, _list(tokens, lambda t: _labels(t, f"a face of patch {name!r}")), line


def read_blockmeshdict(path: str, patches: Iterable[str] | None = None) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Triangles (n, 3, 3) of the chosen boundary patches of a blockMeshDict (a file, or a case
    folder with system/blockMeshDict), in metres (``convertToMeters`` or ``scale`` applied), and
    the triangle indices of each patch. Each patch face must be a face of one of the hex blocks;
    it is taken in the block's own order, so its normals point out of the fluid domain as
    blockMesh's (which also accepts the face's vertices in any order), and split into two
    triangles. Curved edges and the ``#include``/``$variable`` macros are refused with an error
    naming the line: run blockMesh and read the polyMesh instead."""
    if os.path.isdir(path):
        path = os.path.join(path, "system", "blockMeshDict")
    tokens = _open_foam(path)
    for t, line in tokens.items:
        if t.startswith("#") or t.startswith("$"):
            raise tokens.error(f"{t!r}: macros are not supported here (run blockMesh, then ymport.polyMesh)", line)
    scale, vertices, blocks, boundary = 1.0, None, [], None
    while tokens.peek() is not None:
        key = tokens.next("an entry")
        line = tokens.items[tokens.k - 1][1]
        if key in ("convertToMeters", "scale"):
            scale = tokens.number(float, key)
            tokens.expect(";")
        elif key == "vertices":
            vertices = np.array(_list(tokens, _point), dtype=np.float64).reshape(-1, 3)
            tokens.expect(";")
        elif key == "blocks":
            blocks = _list(tokens, _block)
            tokens.expect(";")
        elif key == "edges":
            if _list(tokens, _edge):
                raise tokens.error("curved edges are not supported here (run blockMesh, then ymport.polyMesh)", line)
            tokens.expect(";")
        elif key == "boundary":
            boundary = _list(tokens, _patch_dictionary)
            tokens.expect(";")
        elif key == "patches":
            boundary = _list(tokens, _patch_list)
            tokens.expect(";")
        else:
            _skip_entry(tokens)
    if vertices is None:
        raise MeshError(f"{path}: no vertices")
    if boundary is None:
        raise MeshError(f"{path}: no boundary (or patches) entry")
    for labels, line in blocks:
        if max(labels) >= len(vertices) or min(labels) < 0:
            raise tokens.error(f"a block refers to vertex {max(labels)} but there are {len(vertices)}", line)
    known = [name for name, _, _ in boundary]
    wanted = list(known if patches is None else patches)
    missing = [p for p in wanted if p not in known]
    if missing:
        raise MeshError(f"{path}: no patch {missing[0]!r} (patches: {', '.join(known)})")
    oriented = {}
    for labels, _ in blocks:
        for face in _HEX_FACES:
            ordered = tuple(labels[i] for i in face)
            oriented.setdefault(frozenset(ordered), ordered)
    triangles, groups = [], {}
    for name, faces, _ in boundary:
        if name not in wanted:
            continue
        first = len(triangles)
        for labels, line in faces:
            ordered = oriented.get(frozenset(labels)) if len(labels) == 4 else None
            if ordered is None:
                raise tokens.error(f"face {tuple(labels)} of patch {name!r} is not a face of any block", line)
            quad = vertices[list(ordered)] * scale
            triangles += [quad[[0, 1, 2]], quad[[0, 2, 3]]]
        groups[name] = np.arange(first, len(triangles))
    return np.array(triangles, dtype=np.float64).reshape(-1, 3, 3), groups


def blockMeshDict(path: str, patches: Sequence[str] | None = None, material=-1, scale: float = 1.0,
                  shift=(0.0, 0.0, 0.0), **kw) -> list[BodySpec]:
    """Facets of the boundary patches ``patches`` (default: all) of a blockMeshDict (or a case
    folder), two per block face, scaled then shifted; their normals point out of the fluid
    domain."""
    triangles, _ = read_blockmeshdict(path, patches)
    return _facets(_transform(triangles, scale, shift), path, material)


# ------------------------------------------------------------------------------------------------
# I-DEAS universal file (.unv)

# FE descriptors of the linear triangles (plane stress, plane strain, axisymmetric, thin shell...)
_UNV_TRIANGLES = {41, 51, 61, 74, 81, 91}
# beam elements have an extra record (orientation) before their nodes
_UNV_BEAMS = {11, 21, 22, 23, 24}


def read_unv(file: str) -> tuple[np.ndarray, np.ndarray]:
    """Nodes (n, 3) and triangles (m, 3, indices into the nodes) of a universal file: dataset
    2411 (nodes: a record line, then x y z) and the linear triangles of dataset 2412 (elements:
    a record line ending with the node count, then the node labels); other elements and datasets
    are skipped."""
    with open(file) as f:
        lines = f.read().splitlines()
    labels: dict[int, int] = {}
    nodes: list[tuple] = []
    triangles: list[tuple] = []
    n, dataset = 0, None
    try:
        while n < len(lines):
            items = lines[n].split()
            if items == ["-1"]:                      # delimits a dataset
                dataset = None if dataset is not None else "header"
                n += 1
                continue
            if dataset == "header":
                dataset = int(items[0])
                n += 1
                continue
            if dataset == 2411:
                labels[int(items[0])] = len(nodes)
                # Fortran writes double-precision exponents with D
                nodes.append(tuple(float(x.replace("D", "E")) for x in lines[n + 1].split()[:3]))
                n += 2
            elif dataset == 2412:
                kind, count = int(items[1]), int(items[-1])
                n += 2 if kind in _UNV_BEAMS else 1
                ids: list[int] = []
                while len(ids) < count:
                    ids += [int(x) for x in lines[n].split()]
                    n += 1
                if kind in _UNV_TRIANGLES:
                    triangles.append(tuple(labels[i] for i in ids[:3]))
            else:
                n += 1
    except (ValueError, IndexError, KeyError) as e:
        raise MeshError(f"{file}:{n + 1}: unreadable universal-file record ({type(e).__name__}: {e})") from None
    if dataset is not None:
        raise MeshError(f"{file}: the last dataset ({dataset}) is not closed by -1")
    return np.array(nodes, dtype=float).reshape(-1, 3), np.array(triangles, dtype=int).reshape(-1, 3)


def unv(fileName: str, shift=(0.0, 0.0, 0.0), scale: float = 1.0, returnConnectivityTable: bool = False, **kw):
    """Facets of the triangles of a universal file (Yade's ymport.unv), points scaled by
    ``scale`` then shifted by ``shift``; ``kw`` go to :func:`facet`. With
    ``returnConnectivityTable``: ``(facets, nodes, elements)``, the nodes as (x, y, z) and the
    triangles as node indices (from 0), as Yade returns them."""
    nodes, elements = read_unv(fileName)
    nodes = _transform(nodes, scale, shift)
    facets = [facet(nodes[e], **kw) for e in elements]
    if returnConnectivityTable:
        return facets, [tuple(p) for p in nodes], [tuple(int(i) for i in e) for e in elements]
    return facets
