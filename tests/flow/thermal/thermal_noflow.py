# The set-up of Yade's examples/ThermalEngine/noFlowScenario.py (210 spheres of 4 mm in a 5 cm box,
# mechanically static, spheres at 333.15 K in still water at 343.15 K: conduction between the
# spheres, sphere-fluid exchange in each pore and conduction through the fluid), shortened and run
# by the same text in Yade and Talus:
#   yade -n -x thermal_noflow.py out.json      (the reference: data/thermal_noflow_yade.json)
#   talus run thermal_noflow.py out.json       (tests/flow/thermal/test_thermal_fluid.py)
# Differences from the example: one boundary imposes the pressure (0, as the others' fluxes):
# with none the pressure system is singular and Yade 2023.02a's temperatures are all NaN; no
# TriaxialStressController, GlobalStiffnessTimeStepper or output (they change nothing here).
# Settings by environment: NF_STEPS (2000), NF_FLUIDCOND (fluidConduction, 1). Writes the sphere
# temperatures and the pore temperatures at a few points, at the end and a step before. The set-up
# the thermal examples share is cases/yade/thermal_examples.py.
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), "..", "..", "..", "cases", "yade"))
from thermal_examples import EXAMPLE_PACKING, packing_spheres, static_box, water_and_particles  # noqa: E402

steps = int(os.environ.get("NF_STEPS", "2000"))
flow, thermal = static_box(Vector3(0, 0, 0), Vector3(0.05, 0.05, 0.05), 1e9,
                           lambda material: packing_spheres(EXAMPLE_PACKING, material))
water_and_particles(flow, thermal)
flow.bndCondIsPressure = [1, 0, 0, 0, 0, 0]
flow.bndCondValue = [0, 0, 0, 0, 0, 0]
flow.bndCondIsTemperature = [0, 0, 0, 0, 0, 0]
flow.thermalBndCondValue = [0, 0, 0, 0, 0, 0]
flow.tZero = 343.15
thermal.fluidConduction = bool(int(os.environ.get("NF_FLUIDCOND", "1")))
thermal.uniformReynolds = 10
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
