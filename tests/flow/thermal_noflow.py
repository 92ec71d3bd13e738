# The set-up of Yade's examples/ThermalEngine/noFlowScenario.py (210 spheres of 4 mm in a 5 cm box,
# mechanically static, spheres at 333.15 K in still water at 343.15 K: conduction between the
# spheres, sphere-fluid exchange in each pore and conduction through the fluid), shortened and run
# by the same text in Yade and Talus:
#   yade -n -x thermal_noflow.py out.json      (the reference: data/thermal_noflow_yade.json)
#   talus run thermal_noflow.py out.json       (tests/flow/test_thermal_fluid.py)
# Differences from the example: one boundary imposes the pressure (0, as the others' fluxes):
# with none the pressure system is singular and Yade 2023.02a's temperatures are all NaN; no
# TriaxialStressController, GlobalStiffnessTimeStepper or output (they change nothing here).
# Settings by environment: NF_STEPS (2000), NF_FLUIDCOND (fluidConduction, 1). Writes the sphere
# temperatures and the pore temperatures at a few points, at the end and a step before.
import json
import os
import sys

PACKING = "/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres"
steps = int(os.environ.get("NF_STEPS", "2000"))
mn, mx = Vector3(0, 0, 0), Vector3(0.05, 0.05, 0.05)
O.materials.append(FrictMat(young=1e9, poisson=0.5, frictionAngle=radians(3), density=2600, label='spheres'))
O.materials.append(FrictMat(young=1e9, poisson=0.5, frictionAngle=0, density=0, label='walls'))
O.bodies.append(aabbWalls([mn, mx], thickness=0, material='walls'))
with open(PACKING) as f:   # the example's ymport.textExt(PACKING, 'x_y_z_r'), read by hand
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
flow.viscosity = 0.001
flow.bndCondIsPressure = [1, 0, 0, 0, 0, 0]
flow.bndCondValue = [0, 0, 0, 0, 0, 0]
flow.thermalEngine = True
flow.fluidRho = 997
flow.fluidCp = 4181.7
flow.bndCondIsTemperature = [0, 0, 0, 0, 0, 0]
flow.thermalBndCondValue = [0, 0, 0, 0, 0, 0]
flow.tZero = 343.15
thermal.fluidConduction = bool(int(os.environ.get("NF_FLUIDCOND", "1")))
thermal.ignoreFictiousConduction = True
for name in ("thermoMech", "solidThermoMech", "fluidThermoMech"):
    setattr(thermal, name, False)
thermal.advection = True
thermal.fluidK = 0.6069
thermal.uniformReynolds = 10
thermal.particleT0 = 333.15
thermal.particleDensity = 2600.
thermal.particleK = 2.
thermal.particleCp = 710.
thermal.tsSafetyFactor = 0
thermal.useKernMethod = True
O.dt = 1e-5
probes = [(0.025, 0.025, 0.025), (0.0125, 0.025, 0.025), (0.0375, 0.02, 0.03), (0.02, 0.035, 0.015),
          (0.03, 0.015, 0.035)]
O.run(steps - 1, True)
poreTempBefore = [flow.getPoreTemperature(p) for p in probes]   # a step before the end
O.run(1, True)
spheres = [b for b in O.bodies if isinstance(b.shape, Sphere)]
out = dict(ids=[b.id for b in spheres], temp=[b.state.temp for b in spheres], time=O.time,
           poreTemp=[flow.getPoreTemperature(p) for p in probes], poreTempBefore=poreTempBefore, probes=probes,
           contacts=O.interactions.countReal())
with open(sys.argv[-1] if sys.argv[-1].endswith(".json") else "thermal_noflow.json", "w") as f:
    json.dump(out, f)
