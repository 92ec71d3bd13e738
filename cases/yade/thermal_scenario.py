# Twin scenario of cases/thm_vs_yade.py, the same text in Yade and Talus (talus.dem.twin.run):
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
import time
from math import radians

try:
    O
except NameError:
    from yade import *

params = json.loads(os.environ["TALUS_SCENARIO"])
flowing = params["mode"] == "flow"
PACKING = params.get("packing", "/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres")
t0 = 333.15
mn, mx = Vector3(0, 0, 0), Vector3(0.05, 0.05, 0.05)
O.materials.append(FrictMat(young=1e9, poisson=0.5, frictionAngle=radians(3), density=2600, label='spheres'))
O.materials.append(FrictMat(young=1e9, poisson=0.5, frictionAngle=0, density=0, label='walls'))
O.bodies.append(aabbWalls([mn, mx], thickness=0, material='walls'))
with open(PACKING) as f:   # the examples' ymport.textExt(PACKING, 'x_y_z_r'), read by hand
    rows = [[float(v) for v in line.split()] for line in f if line.strip() and not line.startswith('#')]
O.bodies.append([sphere((x, y, z), r, material='spheres') for x, y, z, r in rows])
for b in O.bodies:
    b.dynamic = False
flow = FlowEngine(label="flow")
thermal = ThermalEngine(label="thermal")
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             flow, thermal, NewtonIntegrator(damping=0.2)]
flow.permeabilityFactor = 1
flow.yadeInsertionOrder = params.get("yadeInsertionOrder", False)
flow.viscosity = 0.001
flow.thermalEngine = True
flow.fluidRho = 997
flow.fluidCp = 4181.7
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
thermal.ignoreFictiousConduction = True
thermal.thermoMech = False
thermal.solidThermoMech = False
thermal.fluidThermoMech = False
thermal.advection = True
thermal.bndCondIsTemperature = [0, 0, 0, 0, 0, 0]
thermal.thermalBndCondValue = [0, 0, 0, 0, 0, 0]
thermal.fluidK = 0.6069
thermal.fluidConductionAreaFactor = 1.
thermal.uniformReynolds = params.get("uniformReynolds", 10)
thermal.particleT0 = t0
thermal.particleDensity = 2600.
thermal.particleK = 2.
thermal.particleCp = 710.
thermal.tsSafetyFactor = 0
thermal.useKernMethod = True
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
