# Yade side of the periodic pore-flow comparison in cases/pore/flow_permeability.py: run by
# talus.twin.run(script, params, "yade"), i.e. `yade -n -j1 -x pore_flow_periodic.py` with the
# parameters as JSON in $TALUS_SCENARIO:
#   packings   list of sphere files (x y z r per line)
#   cells      one [Lx, Ly, Lz] per packing: the periodic cell [0, L)
#   gradP      the macroscopic pressure gradient, threshold: duplicateThreshold, viscosity
# For each packing Yade's PeriodicFlowEngine (CHOLMOD, no boundary) runs one step; the case gets
# the average velocity (K = -mu v.g / |g|^2), the cell count and the time of the step, as one line
# `RESULT {json}`.
import json
import os
import time

params = json.loads(os.environ["TALUS_SCENARIO"])
out = []
for path, L in zip(params["packings"], params["cells"]):
    O.reset()
    O.periodic = True
    O.cell.hSize = Matrix3(L[0], 0, 0, 0, L[1], 0, 0, 0, L[2])
    for line in open(path):
        if line.strip() and not line.startswith("#"):
            x, y, z, r = map(float, line.split()[:4])
            O.bodies.append(sphere((x, y, z), r, fixed=True))
    flow = PeriodicFlowEngine(useSolver=3, duplicateThreshold=float(params["threshold"]),
                              gradP=Vector3(*params["gradP"]), viscosity=float(params.get("viscosity", 1.0)))
    O.engines = [flow]
    O.dt = 1e-6
    t0 = time.perf_counter()
    O.step()
    out.append({"packing": path, "nCells": flow.nCells(), "averageVelocity": list(flow.averageVelocity()),
                "first_step_s": time.perf_counter() - t0})
print("RESULT " + json.dumps(out))
