"""yade.export's files, written so that the same file runs in Yade (`yade -n -x`) and in Talus:
VTKExporter.exportFacetsAsMesh (the facets of shell.unv with its connectivity table),
exportPeriodicCell and VTKRecorder's 'pericell' (a skewed cell), textExt in each format Talus
writes, text, text2vtk and text2vtkSection. Yade writes legacy .vtk and compressed .vtu files,
Talus .vtu with inline data: the geometry is read back from either. Prints one RESULT line
(tests/yade/test_export_yade.py)."""
import base64
import glob
import json
import os
import re
import tempfile
import zlib

import numpy

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403
from yade import export, ymport

TYPES = {"Float32": numpy.float32, "Float64": numpy.float64, "Int64": numpy.int64, "Int32": numpy.int32,
         "UInt8": numpy.uint8}


def legacy_vtk(path):
    """Points and cells (POLYGONS or CELLS) of an ASCII legacy VTK file."""
    words = open(path).read().split("\n")
    out, k = {}, 0
    while k < len(words):
        head = words[k].split()
        if head and head[0] == "POINTS":
            out["points"] = [[float(w) for w in words[k + 1 + i].split()] for i in range(int(head[1]))]
        elif head and head[0] in ("POLYGONS", "CELLS"):
            out["cells"] = [[int(w) for w in words[k + 1 + i].split()[1:]] for i in range(int(head[1]))]
        k += 1
    return out


def xml_vtu(path):
    """Points and cells of a .vtu: Talus's inline base64 (UInt64 count then data) or Yade's
    appended, zlib-compressed base64 (one block: four UInt32 header words, then the data)."""
    text = open(path).read()
    appended = text.split('<AppendedData encoding="base64">')[-1].split("</AppendedData>")[0].strip()[1:]
    arrays = {}
    for attributes, inline in re.findall(r"<DataArray ([^>]*?)/?>(?:([^<]*)</DataArray>)?", text):
        name = re.search(r'Name="(\w+)"', attributes)
        dtype = TYPES[re.search(r'type="(\w+)"', attributes).group(1)]
        if 'format="appended"' in attributes:
            offset = int(re.search(r'offset="(\d+)"', attributes).group(1))
            header = numpy.frombuffer(base64.b64decode(appended[offset:offset + 24]), dtype=numpy.uint32)
            size = (int(header[3]) + 2) // 3 * 4
            raw = zlib.decompress(base64.b64decode(appended[offset + 24:offset + 24 + size]))
        else:
            raw = base64.b64decode(inline)[8:]
        arrays[name.group(1) if name else "Points"] = numpy.frombuffer(raw, dtype=dtype)
    offsets = [0] + [int(o) for o in arrays["offsets"]]
    connectivity = [int(c) for c in arrays["connectivity"]]
    return {"points": arrays["Points"].astype(float).reshape(-1, 3).tolist(),
            "cells": [connectivity[a:b] for a, b in zip(offsets, offsets[1:])]}


def read(path):
    return legacy_vtk(path) if path.endswith(".vtk") else xml_vtu(path)


def written(folder, pattern):
    (path,) = glob.glob(os.path.join(folder, pattern))
    return path


folder = tempfile.mkdtemp()
result = {}

# 1. A facet mesh from an I-DEAS file, exported with shared nodes.
facets, nodes, table = ymport.unv("shell.unv", returnConnectivityTable=True)
O.bodies.append(facets)
export.VTKExporter(os.path.join(folder, "mesh")).exportFacetsAsMesh(connectivityTable=table)
result["mesh"] = read(written(folder, "mesh-facets-*"))

# 2. A skewed periodic cell, by the exporter and by the recorder.
O.reset()
O.periodic = True
O.cell.hSize = Matrix3(2, 0.3, 0.1, 0.2, 3, 0, 0.1, 0.4, 4)
O.bodies.append(sphere((1, 1, 1), 0.5))
O.dt = 1e-6
O.engines = [ForceResetter(), NewtonIntegrator()]
O.step()
export.VTKExporter(os.path.join(folder, "cell")).exportPeriodicCell()
VTKRecorder(fileName=os.path.join(folder, "rec-"), recorders=["pericell"])()
result["cell"] = read(written(folder, "cell-periCell-*"))
result["pericell"] = read(written(folder, "rec-pericell.*.vtu"))

# 3. Spheres as text, and that text as legacy VTK. The plane of the sections does not cut the first
# sphere, which Yade's text2vtkSection leaves out wherever it is (Talus's keeps it).
O.reset()
soft = O.materials.append(FrictMat(young=1e6))
O.materials.append(FrictMat(young=1e7))
O.bodies.append([sphere((i * 0.9, (i * 0.37) % 1.1, (i * 0.61) % 1.3), 0.3 + 0.05 * (i % 3), material=i % 2)
                 for i in range(12)])
texts = {}
for form in ("x_y_z_r", "x_y_z_r_matId", "id_x_y_z_r_matId"):
    path = os.path.join(folder, form + ".txt")
    texts[form] = [export.textExt(path, format=form, comment="twelve spheres"), open(path).read()]
attrs = os.path.join(folder, "attrs.txt")
texts["attrs"] = [export.textExt(attrs, format="x_y_z_r_attrs", attrs=("b.state.pos.norm()", "b.state.pos"),
                                 comment="d px py pz"), open(attrs).read()]
plain = os.path.join(folder, "plain.txt")
texts["text"] = [export.text(plain), open(plain).read()]
for name, source in (("plain", plain), ("attrs", attrs)):
    export.text2vtk(source, os.path.join(folder, name + ".vtk"))
    export.text2vtkSection(source, os.path.join(folder, name + "-section.vtk"), point=(4.3, 0.5, 0.6), normal=(0.1, 0.2, 1))
    texts[name + ".vtk"] = open(os.path.join(folder, name + ".vtk")).read()
    texts[name + "-section.vtk"] = open(os.path.join(folder, name + "-section.vtk")).read()
result["texts"] = texts
print("RESULT " + json.dumps(result))
