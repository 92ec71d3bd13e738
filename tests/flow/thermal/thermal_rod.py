# The rod of Yade's examples/ThermalEngine/conductionVerification.py (a chain of 166 spheres,
# r = 3 mm, along a 1 m box, the end spheres held at 0 by the xmin and xmax temperature
# boundaries, the others starting at 400), run by the same text in Yade and Talus:
#   yade -n -x thermal_rod.py out.json          (the reference: data/thermal_rod_yade.json)
#   talus run thermal_rod.py out.json           (tests/flow/thermal/test_thermal.py)
# Settings by environment: ROD_STEPS (2000), ROD_DT (1 s), ROD_K (particleK, 2 W/(m K)),
# ROD_TSF (tsSafetyFactor, 0), ROD_KERN (useKernMethod, 0); Talus only: ROD_SAVE (a checkpoint
# path: saves half-way, runs on, reloads and runs the second half again), ROD_VTK (a VTKRecorder
# file prefix with the thermal recorder). Writes the sphere ids, positions and temperatures, the
# boundary fluxes every 100 steps, the scheme's step numbers and Talus's heat per boundary. The set-up
# the thermal examples share is cases/yade/thermal_examples.py.
import json
import os
import sys

from yade import pack

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), "..", "..", "..", "cases", "yade"))
from thermal_examples import static_box  # noqa: E402

steps = int(os.environ.get("ROD_STEPS", "2000"))
rad = 0.003
mn, mx = Vector3(0, 0, 0), Vector3(1.0, 0.008, 0.008)
flow, thermal = static_box(mn, mx, 1e6, lambda material: pack.regularOrtho(pack.inAlignedBox(mn, mx), radius=rad,
                                                                            gap=-1e-8, material=material))
for name in ("thermoMech", "advection", "fluidThermoMech", "solidThermoMech", "fluidConduction"):
    setattr(thermal, name, False)
thermal.bndCondIsTemperature = [1, 1, 0, 0, 0, 0]
thermal.thermalBndCondValue = [0, 0, 0, 0, 0, 0]
thermal.tsSafetyFactor = float(os.environ.get("ROD_TSF", "0"))
thermal.particleDensity = 2600
thermal.particleT0 = 400.
thermal.particleCp = 710.
thermal.particleK = float(os.environ.get("ROD_K", "2"))
thermal.useKernMethod = bool(int(os.environ.get("ROD_KERN", "0")))
O.dt = float(os.environ.get("ROD_DT", "1"))
flow.updateTriangulation = True
flow.emulateAction()   # the triangulation only: it finds the spheres next to each boundary
flow.dead = True
if os.environ.get("ROD_VTK"):
    O.engines = O.engines + [VTKRecorder(fileName=os.environ["ROD_VTK"], recorders=["spheres", "thermal"],
                                         iterPeriod=max(1, steps // 2))]
fluxes = []
O.engines = O.engines + [PyRunner(iterPeriod=100, command="fluxes.append(list(thermal.thermalBndFlux))")]
spheres = [b for b in O.bodies if isinstance(b.shape, Sphere)]
out = {}
if os.environ.get("ROD_SAVE"):
    O.run(steps // 2, True)
    O.save(os.environ["ROD_SAVE"])
    O.run(steps - steps // 2, True)
    out["tempBeforeReload"] = [b.state.temp for b in spheres]
    O.load(os.environ["ROD_SAVE"])
    thermal = O.engines[4]
    spheres = [b for b in O.bodies if isinstance(b.shape, Sphere)]
    O.run(steps - steps // 2, True)
else:
    O.run(steps, True)
out.update(ids=[b.id for b in spheres], x=[b.state.pos[0] for b in spheres], temp=[b.state.temp for b in spheres],
           fluxes=fluxes, time=O.time, thermalDT=thermal.getThermalDT(), period=thermal.getConductionIterPeriod(),
           contacts=O.interactions.countReal(), heat=list(getattr(thermal, "thermalBndHeat", [])))
with open(sys.argv[-1] if sys.argv[-1].endswith(".json") else "thermal_rod.json", "w") as f:
    json.dump(out, f)
