# Runs Yade's examples/ThermalEngine/noFlowScenario.py unchanged (copied with its packing into the
# working folder), then completes NF_STEPS steps in all: the script ends with an open-ended
# O.run() (under Yade it goes on in the background). No boundary of the script imposes a
# pressure, so its incompressible fluid in the closed static packing is at rest at pZero. Writes
# the sphere temperatures and the pore temperatures at thermal_noflow.py's probes, at the end
# and a step before, as thermal_noflow.py.
import json
import os
import sys

steps = int(os.environ.get("NF_STEPS", "2000"))
out = sys.argv[-1]
sys.argv = ["noFlowScenario.py"]   # the script copies itself by that name
with open("noFlowScenario.py") as f:
    exec(compile(f.read(), "noFlowScenario.py", "exec"))
O.pause()
O.wait()
O.run(steps - 1 - O.iter, True)
probes = [(0.025, 0.025, 0.025), (0.0125, 0.025, 0.025), (0.0375, 0.02, 0.03), (0.02, 0.035, 0.015),
          (0.03, 0.015, 0.035)]
poreTempBefore = [flow.getPoreTemperature(p) for p in probes]
O.run(1, True)
spheres = [b for b in O.bodies if isinstance(b.shape, Sphere)]
with open(out, "w") as f:
    json.dump(dict(ids=[b.id for b in spheres], temp=[b.state.temp for b in spheres], steps=O.iter,
                   poreTemp=[flow.getPoreTemperature(p) for p in probes], poreTempBefore=poreTempBefore,
                   pressures=list(flow.pressures), contacts=O.interactions.countReal()), f)
