# Yade side of the alpha-shape boundary comparison (tests/flow/pore/test_pore_alpha.py): run with
#   cd tests/flow/pore && yade -n -x pore_yade_alpha.py [out.json]
# Builds the packing of Yade's examples/FluidCouplingPFV/alphaShape.py (randomDensePack in a unit
# sphere, radius 0.1, rRelFuzz 0.1, seed 1, inside six zero-thickness walls), runs its FlowEngine
# once (alphaBound 0.3, alphaBoundValue 0, fixedAlpha False, pressure 1 imposed at the origin) and
# writes the spheres, the alpha flag of every vertex (printVertices' vertices.txt), the cells
# (vertex ids, pressure, whether the pressure is imposed) and the flux out of the origin's cell.
import json
import os
import sys

from yade import pack

args = [a for a in sys.argv[1:] if not a.startswith("-")]
out = args[0] if args else "../data/pore_yade_alpha.json"
mx = Vector3(0.9639118565206523, 0.9324110610237126, 0.8800533096533549)
mn = Vector3(-0.9518976876470108, -0.9685168132064216, -0.9451956043076566)
O.bodies.append(aabbWalls([mn, mx], thickness=0))
sp = pack.randomDensePack(pack.inSphere(Vector3(0, 0, 0), 1), radius=0.1, rRelFuzz=0.1, returnSpherePack=False, seed=1)
O.bodies.append(sp)
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.dynamic = False
flow = FlowEngine(multithread=False, useSolver=4, permeabilityFactor=-1e-1, defTolerance=-1, meshUpdateInterval=-1)
flow.alphaBound = 0.3
flow.alphaBoundValue = 0
flow.fixedAlpha = False
flow.imposePressure((0, 0, 0), 1)
O.engines = [flow]
O.dt = 1e-6
O.step()
flow.printVertices()
rows = [l.split() for l in open("vertices.txt").readlines()[1:] if l.strip()]
os.remove("vertices.txt")
cells = []
for i in range(flow.nCells()):
    cells.append({"vertices": [int(v) for v in flow.getVertices(i)], "pressure": flow.getCellPressure(i),
                  "imposed": bool(flow.getCellPImposed(i)), "center": list(flow.getCellCenter(i))})
res = {
    "spheres": [[b.id] + list(b.state.pos) + [b.shape.radius] for b in O.bodies if isinstance(b.shape, Sphere)],
    "vertexHeader": "id x y z r alpha fictious",
    "vertices": [[float(x) for x in r] for r in rows],
    "cells": cells,
    "originFlux": flow.getCellFlux(0),
}
json.dump(res, open(out, "w"))
print("nCells", len(cells), "imposed", sum(c["imposed"] for c in cells), "flux", res["originFlux"],
      "alpha vertices", sum(1 for r in rows if float(r[5]) != 0))
