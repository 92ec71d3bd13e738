# Yade side of the pore-flow comparison (tests/flow/pore/test_pore.py): run with
#   cd tests/flow/pore && yade -n -x pore_yade_reference.py [packing.txt] [out.json]
# Reads a sphere list (x y z r per line), puts it in the six walls of its bounding box, runs Yade's
# FlowEngine once (CHOLMOD, pressure 1 at ymin, 0 at ymax, no flux elsewhere) and writes the pore
# network and the solution as JSON: cells keyed by their vertex ids (walls are ids 0..5, the
# spheres 6..), cell volumes, pressures, the conductance of every facet, the boundary fluxes, the
# average velocity and the fluid force on every body.
import json
import sys

args = [a for a in sys.argv[1:] if not a.startswith("-")]
packing = args[0] if args else "../data/pore_packing.txt"
out = args[1] if len(args) > 1 else "../data/pore_yade_reference.json"
spheres = [tuple(map(float, l.split())) for l in open(packing) if l.strip() and not l.startswith("#")]
lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]
O.bodies.append(aabbWalls([Vector3(*lo), Vector3(*hi)], thickness=0))
for x, y, z, r in spheres:
    O.bodies.append(sphere((x, y, z), r, fixed=True))
flow = FlowEngine(useSolver=3, permeabilityFactor=1.0, viscosity=1.0, debug=False)
flow.bndCondIsPressure = [0, 0, 1, 1, 0, 0]
flow.bndCondValue = [0, 0, 1, 0, 0, 0]
flow.boundaryUseMaxMin = [1, 1, 1, 1, 1, 1]
O.engines = [flow]
O.dt = 1e-6
O.step()
cells = []
for i in range(flow.nCells()):
    cells.append({
        "vertices": [int(v) for v in flow.getVertices(i)],
        "volume": flow.getCellVolume(flow.getCellBarycenter(i)),
        "pressure": flow.getCellPressure(i),
        "center": list(flow.getCellCenter(i)),
        "neighbors": [int(n) for n in flow.getNeighbors(i)],
        "conductance": [flow.getConductivity(i, j) for j in range(4)],
    })
res = {
    "nCells": flow.nCells(),
    "boundaryFlux": [flow.getBoundaryFlux(k) for k in range(6)],
    "averageVelocity": list(flow.averageVelocity()),
    "fluidForce": {str(b.id): list(flow.fluidForce(b.id)) for b in O.bodies},
    "cells": cells,
}
json.dump(res, open(out, "w"))
print("nCells", res["nCells"], "flux", res["boundaryFlux"])
