"""Deterministic results of Yade's pack, geom and ymport functions, written so that the same
file runs in Yade (`yade -n -x`) and in Talus: predicate membership and boxes, regular
lattices, facet coordinates (facetBox, flat facetBox, facetCylinder, facetCone, facetBunker,
sweptPolylines2gtsSurface), ymport.unv of Yade's own example file, a flat periodic makeCloud.
Prints one RESULT line of JSON."""
import json
import os
import random

from yade import geom, pack, ymport

HERE = os.getcwd()
rng = random.Random(5)
points = [(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 3)) for _ in range(400)]
pads = [0.0, 0.15]
s1, s2 = pack.inSphere((0, 0, 0), 1), pack.inSphere((0, 0, 1), 1)
box = pack.inAlignedBox((-1, -1.5, -0.5), (1.5, 1, 2))
cyl = pack.inCylinder((0.2, -0.3, -1), (0.5, 0.8, 2), 1.1)
predicates = {
    "sphere": s1, "box": box, "cylinder": cyl,
    "hyperboloid": pack.inHyperboloid((0, 0, -1.5), (0, 0.5, 2), 1.6, 0.8),
    "ellipsoid": pack.inEllipsoid((0.1, 0.2, 0.3), (1.5, 1.0, 2.0)),
    "parallelepiped": pack.inParallelepiped((-1, -1, -1), (1.5, -0.5, -1), (-0.5, 1.2, -0.8), (-0.6, -0.7, 1.8)),
    "union": s1 | s2, "intersection": s1 & box, "difference": cyl - s2, "symdiff": s1 ^ s2,
    "notch": box & pack.notInNotch((0.2, 0, 0.5), (0, 1, 0), (0, 0, 1), 0.3),
    "explicit": pack.PredicateUnion(cyl, pack.PredicateIntersection(s2, box)),
}


def aabb(p):
    lo, hi = p.aabb()
    return [list(map(float, lo)), list(map(float, hi))]


out = {"inside": {name: [[bool(p(x, pad)) for x in points] for pad in pads] for name, p in predicates.items()},
       "aabb": {name: aabb(p) for name, p in predicates.items() if name != "notch"},
       "dim": [float(x) for x in cyl.dim()], "center": [float(x) for x in cyl.center()]}


def centres(bodies):
    return [[float(x) for x in b.state.pos] for b in bodies]


out["hexa"] = centres(pack.regularHexa(cyl, radius=0.2, gap=0.05))
out["ortho"] = centres(pack.regularOrtho(s1 | s2, radius=0.15, gap=0.02))


def vertices(facets):
    # a facet's vertices in the global frame (Yade keeps them relative to the facet's position)
    rows = []
    for f in facets:
        if isinstance(getattr(f, "vertices", None), tuple):     # Talus's body spec: global vertices
            rows.append([[float(x) for x in v] for v in f.vertices])
            continue
        pos, ori = f.state.pos, f.state.ori
        rows.append([[float(x) for x in pos + ori * v] for v in f.shape.vertices])
    return rows


out["facetBox"] = vertices(geom.facetBox((0.1, 0.2, 0.3), (1, 2, 3), wallMask=45))
out["flatBox"] = vertices(geom.facetBox((0, 0, 0), (30e-3, 30e-3, 0), wallMask=32))
out["facetCylinder"] = vertices(geom.facetCylinder((0, 0, 1), 2.05, 4.0, segmentsNumber=7, wallMask=7))
out["facetCone"] = vertices(geom.facetCone((1, 0, 0), 1.5, 0.5, 2.0, segmentsNumber=6))
out["facetBunker"] = vertices(geom.facetBunker((0.5, -0.2, 0.1), dBunker=2.8, dOutput=1.19, hBunker=2.1, hOutput=0.7,
                                               hPipe=0.7 / 3, wallMask=7, segmentsNumber=10))
surf = pack.sweptPolylines2gtsSurface([[(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
                                       [(0, 0, 1), (1, 0, 1.2), (1, 1, 1), (0, 1, 1.1)]], capStart=True, capEnd=True)
out["swept"] = sorted(vertices(pack.gtsSurface2Facets(surf)))
facets, nodes, elements = ymport.unv(os.path.join(HERE, "shell.unv"), shift=(100, 200, 300), scale=1000,
                                     returnConnectivityTable=True)
out["unv"] = {"facets": vertices(facets), "nodes": [list(map(float, n)) for n in nodes],
              "elements": [list(map(int, e)) for e in elements]}
sp = pack.SpherePack()
n = sp.makeCloud(minCorner=(0, 0, .05), maxCorner=(.24, .24, .05), rMean=.005, rRelFuzz=.4, num=60, periodic=True, seed=1)
out["flatCloud"] = {"n": int(n), "periodic": bool(sp.isPeriodic), "cellSize": [float(x) for x in sp.cellSize],
                    "spheres": [[float(c[0]), float(c[1]), float(c[2]), float(r)] for c, r in sp]}
print("RESULT " + json.dumps(out))
