# Pores drained one at a time through the clusters (clusterInvadePore), one script for both
# programs: run by talus.twin.run(script, params, "yade" or "talus") with the parameters as JSON in
# $TALUS_SCENARIO:
#   packing       sphere file (x y z r per line)
#   pc            capillary pressure of the invasion() before (it leaves trapped wetting clusters)
#   invasions     number of pores drained by clusterInvadePore after it
#   fast          (optional) drain them by clusterInvadePoreFast instead
#   pcs           (optional) instead of the above, invasion() at each of these capillary pressures
#                 with useFastInvasion (the clusters kept through the drainage by the fast update)
# TwoPhaseFlowEngine with isCellLabelActivated on the spheres in the walls of their bounding box
# (wetting reservoir ymin, non-wetting ymax), one quasi-static invasion() at `pc`, then, in turn,
# the inner pore of one interface of one wetting cluster drained: the cluster taken in turn among
# the wetting clusters that have interfaces (by label), the interface by a fixed stride through
# its list (so the choice depends on the order of the interfaces, which both programs must share).
# Pores are named by their sorted vertex ids (the network's pore numbering is each program's own).
# Printed as one line `RESULT {json}`: per invasion the pore drained and the labels returned (with
# pcs: the saturation and the number of clusters after each invasion()); at the end each pore's
# label and interface flag (getCellHasInterface) and each cluster's pores, interfaces (inner,
# outer) in their order, volume, entry radius and entry pore.
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # twophase_scene.py, under Yade's -x too
from twophase_scene import read_spheres, reservoir_engine  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres, lo, hi = read_spheres(params["packing"])
pc = float(params.get("pc", 0))
pcs = params.get("pcs", [])
flow = reservoir_engine(spheres, lo, hi, yadeInsertionOrder=True, surfaceTension=0.0728, isCellLabelActivated=True,
                        useFastInvasion=bool(pcs))
flow.initialization()
key = [" ".join(map(str, sorted(flow.getVertices(i)))) for i in range(flow.nCells())]
steps = []
for p in pcs:
    flow.bndCondValue = [0, 0, -p, 0, 0, 0]
    flow.invasion()
    steps.append({"saturation": flow.getSaturation(False), "clusters": len(flow.getClusters())})
if not pcs:
    flow.bndCondValue = [0, 0, -pc, 0, 0, 0]
    flow.invasion()
drain = flow.clusterInvadePoreFast if params.get("fast") else flow.clusterInvadePore
STRIDE = 7919  # a prime: the interface drained wanders through the lists
for k in range(0 if pcs else int(params["invasions"])):
    clusters = [c for c in flow.getClusters() if c.label > 0 and len(c.getInterfaces()) > 0]
    if not clusters:
        break
    cluster = clusters[k % len(clusters)]
    interfaces = cluster.getInterfaces()
    inner = interfaces[(k * STRIDE) % len(interfaces)][0]
    steps.append({"pore": key[inner], "label": cluster.label, "returned": list(drain(inner))})
clusters = [{"label": c.label, "pores": [key[p] for p in c.getPores()],
             "interfaces": [[key[i[0]], key[i[1]]] for i in c.getInterfaces()], "volume": c.volume,
             "entryRadius": c.entryRadius, "entryPore": key[c.entryPore] if c.entryPore >= 0 else None}
            for c in flow.getClusters()]
print("RESULT " + json.dumps({"nCells": flow.nCells(), "steps": steps, "clusters": clusters,
                              "labels": {key[i]: flow.getCellLabel(i) for i in range(flow.nCells())},
                              "hasInterface": [key[i] for i in range(flow.nCells()) if flow.getCellHasInterface(i)]}))
