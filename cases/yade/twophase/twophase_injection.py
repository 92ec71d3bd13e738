# The injection scenario of cases/pore/twophase_injection.py and of
# tests/flow/twophase/test_twophase_injection.py, one script for both programs: run by
# talus.twin.run(script, params, "yade" or "talus") with the parameters as JSON in
# $TALUS_SCENARIO:
#   packing       sphere file (x y z r per line)
#   steps, dt     number and length of the time steps
#   every         the state is recorded every this many steps (and after the last)
#   pressure      wetting pressure imposed on ymin
#   viscosity     of the wetting fluid
# The dynamic injection of Yade's examples/FluidCouplingPFV/TwoPhaseFlowInjection.py on a fixed
# packing (the spheres in the walls of their bounding box, no DEM motion: the flow does not depend
# on it): TwoPhaseFlowEngine with isCellLabelActivated, all pores non-wetting but those of ymin,
# where the wetting fluid is at `pressure`; the pores below a third of the height filled first
# through the reservoir cluster (clusterOutvadePore). Each step the menisci of the cluster's
# interfaces advance by their flux (updateCapVolList); a dry pore whose interfaces brought its
# void volume joins the cluster (clusterOutvadePore) and passes what exceeded it to its own new
# interfaces in proportion to their conductivity (to a trapped-air count when it has none);
# repeated until no pore is full; then the cluster's pressures (solvePressure). Printed as one
# line `RESULT {json}`: per record the step, the injected volume through ymin (getBoundaryFlux),
# the volume stored (imbibed pores + menisci), the lost (trapped) volume and the wet pore count;
# the pore count, the interfaces at the start; the capillary force on the ymin wall at the end;
# the CPU time of the steps (stepsCpu: the scenario's own loop and the engine's calls).
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # twophase_scene.py, under Yade's -x too
from twophase_scene import read_spheres, reservoir_engine  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres, lo, hi = read_spheres(params["packing"])
# yadeInsertionOrder: Talus's option for Yade's vertex order in the cells, hence its throat
# geometry to round-off (Yade keeps it as an attribute it does not read)
flow = reservoir_engine(spheres, lo, hi, yadeInsertionOrder=True, useSolver=3, permeabilityFactor=1,
                        viscosity=float(params["viscosity"]), bndCondIsPressure=[0, 0, 1, 0, 0, 0],
                        bndCondValue=[0, 0, float(params["pressure"]), 0, 0, 0], boundaryUseMaxMin=[0] * 6,
                        iniVoidVolumes=True, surfaceTension=0.0, drainageFirst=False, isDrainageActivated=False,
                        isImbibitionActivated=True, isCellLabelActivated=True)
flow.initialization()
reservoir = flow.getClusters()[1]
n = flow.nCells()
capacity = [1.0 / flow.getCellInvVoidVolume(i) for i in range(n)]
height = [flow.getCellBarycenter(i)[1] for i in range(n)]
level = lo[1] + (hi[1] - lo[1]) / 3

# initial filling: every dry pore below the level that the cluster touches joins it, repeatedly
while True:
    below = {}
    for inner, outer, area, rank in reservoir.getInterfaces():
        if height[outer] < level and outer not in below:
            below[outer] = inner
    if not below:
        break
    for outer, inner in below.items():
        flow.clusterOutvadePore(inner, outer)
for rank in range(len(reservoir.getInterfaces())):
    reservoir.setCapVol(rank, 0.0)
reservoir.solvePressure()
# as the example: the forces once before the steps (which in Yade also makes getBoundaryFlux read
# the current triangulation; before, it reads the other, empty one and gives 0)
flow.computeCapillaryForce(addForces=False, permanently=False)
interfaces0 = len(reservoir.getInterfaces())
dry0 = [i for i in range(n) if flow.getCellLabel(i) == 0]
state = {"injected": 0.0, "lost": 0.0}


def step(dt):
    reservoir.updateCapVolList(dt)
    state["injected"] -= flow.getBoundaryFlux(flow.wallIds[flow.ymin]) * dt
    while True:
        brought, via = {}, {}
        for inner, outer, area, rank in reservoir.getInterfaces():
            brought[outer] = brought.get(outer, 0.0) + reservoir.getCapVol(rank)
            via.setdefault(outer, inner)
        full = [p for p in brought if brought[p] >= capacity[p]]
        if not full:
            break
        for p in full:
            flow.clusterOutvadePore(via[p], p)
        for p in full:
            excess = brought[p] - capacity[p]
            onward = reservoir.getInterfaces(p)
            conductivity = sum(reservoir.getConductivity(i[3]) for i in onward)
            if conductivity == 0.0:
                state["lost"] += excess
                continue
            for inner, outer, area, rank in onward:
                reservoir.setCapVol(rank, excess * reservoir.getConductivity(rank) / conductivity)
    reservoir.solvePressure()


def record(k):
    menisci = sum(reservoir.getCapVol(i[3]) for i in reservoir.getInterfaces())
    wet = [i for i in dry0 if flow.getCellLabel(i) != 0]
    return {"step": k, "injected": state["injected"], "stored": menisci + sum(capacity[i] for i in wet),
            "lost": state["lost"], "wet": len(wet)}


records = []
cpu = time.process_time()
for k in range(int(params["steps"])):
    step(float(params["dt"]))
    if (k + 1) % int(params["every"]) == 0 or k + 1 == int(params["steps"]):
        records.append(record(k + 1))
cpu = time.process_time() - cpu
flow.computeCapillaryForce(addForces=False, permanently=False)
print("RESULT " + json.dumps({"records": records, "stepsCpu": cpu, "nCells": n, "dry0": len(dry0), "interfaces0": interfaces0,
                              "dryVolume": sum(capacity[i] for i in dry0),
                              "wallForce": list(flow.fluidForce(flow.wallIds[flow.ymin]))}))
