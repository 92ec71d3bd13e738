# Yade side of cases/pore/flow_injection.py: run by talus.twin.run(script, params, "yade"), i.e.
# `yade -n -j1 -x pore_injection.py` with the parameters as JSON in $TALUS_SCENARIO:
#   packing     sphere file (x y z r per line), the deposited layer
#   cell        the periodic cell's edges [Lx, Ly, Lz]
#   points      injection points (one inside each injection pore), `flux` shared among them
#   flux, viscosity, threshold (duplicateThreshold)
# Yade's PeriodicFlowEngine as in the seed's tutorial 2.6.7 (periodic along x and z, boundaries
# ymin and ymax at the layer's extremes, pressure 0 at ymax), one step on the fixed layer with the
# flux imposed at the points; prints `RESULT {json}`: the pressure of every injection pore.
import json
import os

params = json.loads(os.environ["TALUS_SCENARIO"])
L = params["cell"]
O.periodic = True
O.cell.hSize = Matrix3(L[0], 0, 0, 0, L[1], 0, 0, 0, L[2])
O.bodies.append(box(center=(L[0] / 2, -1.0, L[2] / 2), extents=(1, 0, 1), fixed=True))    # id 0: ymin wall
O.bodies.append(box(center=(L[0] / 2, L[1] + 1.0, L[2] / 2), extents=(1, 0, 1), fixed=True))  # id 1: ymax wall
for line in open(params["packing"]):
    if line.strip() and not line.startswith("#"):
        x, y, z, r = map(float, line.split()[:4])
        O.bodies.append(sphere((x, y, z), r, fixed=True))
flow = PeriodicFlowEngine(useSolver=3, duplicateThreshold=params["threshold"], wallIds=[-1, -1, 0, 1, -1, -1],
                          bndCondIsPressure=[0, 0, 0, 1, 0, 0], viscosity=params["viscosity"], permeabilityFactor=1.0)
points = params["points"]


def impose():
    # as the tutorial: imposed in blockHook, once the mesh exists
    flow.clearImposedFlux()
    for p in points:
        flow.imposeFlux(Vector3(*p), -params["flux"] / len(points))


flow.blockHook = "impose()"
O.engines = [flow]
O.dt = 1e-6
O.step()
print("RESULT " + json.dumps({"pressures": [flow.getPorePressure(Vector3(*p)) for p in points], "nCells": flow.nCells()}))
