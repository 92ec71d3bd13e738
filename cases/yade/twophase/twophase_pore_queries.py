# TwoPhaseFlowEngine's per-pore queries and the pendular pairs, one script for both programs: run by
# talus.twin.run(script, params, "yade" or "talus") with the parameters as JSON in $TALUS_SCENARIO:
#   packing       sphere file (x y z r per line)
#   pc            capillary pressure of the invasion() after which the pendular pairs are taken again
# TwoPhaseFlowEngine on the spheres in the walls of their bounding box (wetting reservoir ymin,
# non-wetting ymax). Printed as one line `RESULT {json}`: by pore (named by its sorted vertex ids,
# the network's numbering being each program's own) getCellVolume, getCellVoidVolume,
# getCellPorosity, getCellIsFictious, and whether each of its neighbours is one (isCellNeighbor);
# the vertex pairs of getPotentialPendularSpheresPair (sorted) after initialization() and after
# invasion() at pc; by pore, getCellFluxFromId in the injection's set-up (below).
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # twophase_scene.py, under Yade's -x too
from twophase_scene import read_spheres, reservoir_engine  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres, lo, hi = read_spheres(params["packing"])
flow = reservoir_engine(spheres, lo, hi, surfaceTension=0.0728)
flow.initialization()
n = flow.nCells()
name = [" ".join(map(str, sorted(flow.getVertices(i)))) for i in range(n)]
out = {"volume": {name[i]: flow.getCellVolume(i) for i in range(n)},
       "voidVolume": {name[i]: flow.getCellVoidVolume(i) for i in range(n)},
       "porosity": {name[i]: flow.getCellPorosity(i) for i in range(n)},
       "fictious": {name[i]: flow.getCellIsFictious(i) for i in range(n)},
       "neighbours": all(flow.isCellNeighbor(i, j) for i in range(n) for j in flow.getNeighbors(i) if 0 <= j < n),
       "notNeighbours": any(flow.isCellNeighbor(i, (i + 7) % n) for i in range(n)
                            if (i + 7) % n not in flow.getNeighbors(i)),
       "pendular0": sorted(sorted(p) for p in flow.getPotentialPendularSpheresPair())}
flow.bndCondValue = [0, 0, -float(params["pc"]), 0, 0, 0]
flow.invasion()
out["pendular"] = sorted(sorted(p) for p in flow.getPotentialPendularSpheresPair())
# the injection's set-up (cases/yade/twophase/twophase_injection.py): the wetting reservoir at 1000 Pa grown
# through its first 40 interfaces, its pressures solved; every pore's flux (getCellFluxFromId)
flow = reservoir_engine(spheres, lo, hi, yadeInsertionOrder=True, viscosity=0.1, bndCondIsPressure=[0, 0, 1, 0, 0, 0],
                        bndCondValue=[0, 0, 1000.0, 0, 0, 0], boundaryUseMaxMin=[0] * 6, surfaceTension=0.0,
                        drainageFirst=False, isDrainageActivated=False, isImbibitionActivated=True,
                        isCellLabelActivated=True)
flow.initialization()
reservoir = flow.getClusters()[1]
for inner, outer, area, rank in reservoir.getInterfaces()[:40]:
    if flow.getCellLabel(outer) == 0:
        flow.clusterOutvadePore(inner, outer)
reservoir.solvePressure()
flow.computeCapillaryForce()   # in Yade, makes the fluxes read the current triangulation
name = [" ".join(map(str, sorted(flow.getVertices(i)))) for i in range(flow.nCells())]
out["flux"] = {name[i]: flow.getCellFluxFromId(i) for i in range(flow.nCells())}
print("RESULT " + json.dumps(out))
