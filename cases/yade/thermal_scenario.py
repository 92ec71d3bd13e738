# Twin scenario of cases/pore/thm_vs_yade.py, the same text in Yade and Talus (talus.twin.run):
# the set-ups of Yade's examples/ThermalEngine/noFlowScenario.py and flowScenario.py on their
# packing (5cmEdge_1mm.spheres, 210 spheres of 4 mm in a 5 cm box, mechanically static),
# parameters as JSON in $TALUS_SCENARIO:
#   mode    "noflow": spheres at 333.15 K in still water at 343.15 K (one boundary imposes the
#           pressure 0, the others no flux: with none the system is singular and Yade's
#           temperatures are NaN);
#           "flow": spheres and water at 333.15 K, water at 343.15 K entering through xmin
#           (pressure 10 Pa there, 0 at xmax; FlowEngine's bndCondIsTemperature on xmin)
#   steps   DEM steps (O.dt 1e-5 s noflow, 1e-4 s flow, as the examples)
#   packing optional sphere file (x y z r per line) instead of the examples' one
#   uniformReynolds optional, default 10 (-1, the flow example's: each pore's own Reynolds number)
#   yadeInsertionOrder optional: Talus's FlowEngine option (Yade keeps it as an unread attribute);
#           each pore's Reynolds number takes the length to its last inner neighbour in the
#           triangulation's vertex order, which then is Yade's
# Differences from the examples, in both programs: uniformReynolds = 10 by default (the flow example
# leaves Yade's -1), tsSafetyFactor = 0 (a thermal step of
# O.dt), no TriaxialStressController, time stepper or output. Prints RESULT with the sphere
# temperatures (by id), the pore temperatures at probe points (inner pores), the volume flux
# through xmax and the wall and CPU time of the steps.
import json
import os
import sys
import time

try:
    O
except NameError:
    from yade import *

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # thermal_examples.py, under Yade's -x too
from thermal_examples import EXAMPLE_PACKING, packing_spheres, static_box, water_and_particles  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
flowing = params["mode"] == "flow"
PACKING = params.get("packing", EXAMPLE_PACKING)
t0 = 333.15
flow, thermal = static_box(Vector3(0, 0, 0), Vector3(0.05, 0.05, 0.05), 1e9,
                           lambda material: packing_spheres(PACKING, material))
water_and_particles(flow, thermal)
flow.yadeInsertionOrder = params.get("yadeInsertionOrder", False)
if flowing:
    flow.bndCondIsPressure = [1, 1, 0, 0, 0, 0]
    flow.bndCondValue = [10, 0, 0, 0, 0, 0]
    flow.bndCondIsTemperature = [1, 0, 0, 0, 0, 0]
    flow.thermalBndCondValue = [343.15, 0, 0, 0, 0, 0]
    flow.tZero = t0
    flow.maxKdivKmean = 1
    flow.minKdivKmean = 0.0001
else:
    flow.bndCondIsPressure = [1, 0, 0, 0, 0, 0]
    flow.bndCondValue = [0, 0, 0, 0, 0, 0]
    flow.bndCondIsTemperature = [0, 0, 0, 0, 0, 0]
    flow.thermalBndCondValue = [0, 0, 0, 0, 0, 0]
    flow.tZero = 343.15
thermal.fluidConduction = True
thermal.bndCondIsTemperature = [0, 0, 0, 0, 0, 0]
thermal.thermalBndCondValue = [0, 0, 0, 0, 0, 0]
thermal.fluidConductionAreaFactor = 1.
thermal.uniformReynolds = params.get("uniformReynolds", 10)
O.dt = 1e-4 if flowing else 1e-5
probes = [(x, y, z) for x in (0.01, 0.02, 0.03, 0.04) for y in (0.015, 0.025, 0.035) for z in (0.015, 0.035)]
O.run(1, True)   # triangulation and first solve, not timed
wall, cpu = time.time(), time.process_time()
O.run(int(params["steps"]) - 1, True)
wall, cpu = time.time() - wall, time.process_time() - cpu
spheres = [b for b in O.bodies if isinstance(b.shape, Sphere)]
print("RESULT " + json.dumps(dict(
    ids=[b.id for b in spheres], temp=[b.state.temp for b in spheres], probes=probes,
    poreTemp=[flow.getPoreTemperature(p) for p in probes], outflux=flow.getBoundaryFlux(1),
    cells=flow.nCells(), contacts=O.interactions.countReal(), time=O.time, wall=wall, cpu=cpu,
    steps=int(params["steps"]) - 1)))
