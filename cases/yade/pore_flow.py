# Yade side of the pore-flow cases (cases/pore/flow_permeability.py, cases/pore/flow_bench_pore.py): run by
# talus.twin.run(script, params, "yade"), i.e. `yade -n -j1 -x pore_flow.py` with the
# parameters as JSON in $TALUS_SCENARIO:
#   packings   list of sphere files (x y z r per line, talus SpherePack.save format)
#   boxes      optional, one [lo, hi] per packing: the corners of the six walls (default: the
#              packing's extremes)
#   axis       flow direction 0, 1, 2: pressure `dp` on its lower boundary, 0 on the upper one
#   dp, viscosity, permeabilityFactor
#   solves     extra solves timed after the first step (0: none)
#   remeshes   how many times the first step is timed, each on a fresh scene (default 1; when
#              more than 1, after one untimed warm-up)
# For each packing the spheres are put in the six walls of its box (boundaryUseMaxMin off) or of
# their bounding box (boundaryUseMaxMin on), FlowEngine (CHOLMOD, useSolver=3) runs one step, and the case gets the
# boundary fluxes, the cell count, the time of the first step (triangulation, geometry,
# conductances, factorisation, solve; each of the `remeshes` repeats in remesh_s, remesh_cpu_s)
# and of the later solves (wall and process CPU time), as one line `RESULT {json}`.
import json
import os
import time

params = json.loads(os.environ["TALUS_SCENARIO"])
axis = int(params.get("axis", 1))
out = []
boxes = params.get("boxes")


def first_step(spheres, lo, hi):
    """A fresh scene of the spheres in their walls, FlowEngine as its only engine; the wall and
    CPU time of its first step (the remesh), and the engine."""
    O.reset()
    O.bodies.append(aabbWalls([Vector3(*lo), Vector3(*hi)], thickness=0))
    for x, y, z, r in spheres:
        O.bodies.append(sphere((x, y, z), r, fixed=True))
    flow = FlowEngine(useSolver=3, permeabilityFactor=float(params.get("permeabilityFactor", 1.0)),
                      viscosity=float(params.get("viscosity", 1.0)))
    cond = [0] * 6
    cond[2 * axis] = cond[2 * axis + 1] = 1
    value = [0.0] * 6
    value[2 * axis] = float(params.get("dp", 1.0))
    flow.bndCondIsPressure = cond
    flow.bndCondValue = value
    flow.boundaryUseMaxMin = [0] * 6 if boxes else [1] * 6
    flow.meshUpdateInterval = 10 ** 9
    O.engines = [flow]
    O.dt = 1e-6
    t0, c0 = time.perf_counter(), time.process_time()
    O.step()
    return time.perf_counter() - t0, time.process_time() - c0, flow


for n, path in enumerate(params["packings"]):
    spheres = [tuple(map(float, l.split()[:4])) for l in open(path) if l.strip() and not l.startswith("#")]
    if boxes:   # walls at given planes (spheres may cross them)
        lo, hi = boxes[n]
    else:                 # the packing's extremes
        lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
        hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]
    remesh, remesh_cpu = [], []
    if int(params.get("remeshes", 1)) > 1:
        first_step(spheres, lo, hi)  # warm-up, untimed: the timed ones are those of a running process
    for _ in range(int(params.get("remeshes", 1))):
        first, first_cpu, flow = first_step(spheres, lo, hi)
        remesh.append(first)
        remesh_cpu.append(first_cpu)
    solve_times, solve_cpu = [], []
    for _ in range(int(params.get("solves", 0))):
        t0, c0 = time.perf_counter(), time.process_time()
        O.step()
        solve_times.append(time.perf_counter() - t0)
        solve_cpu.append(time.process_time() - c0)
    out.append({"packing": path, "nCells": flow.nCells(), "boundaryFlux": [flow.getBoundaryFlux(k) for k in range(6)],
                "box": [lo, hi], "first_step_s": remesh[0], "solve_s": solve_times,
                "first_step_cpu_s": remesh_cpu[0], "solve_cpu_s": solve_cpu,
                "remesh_s": remesh, "remesh_cpu_s": remesh_cpu})
print("RESULT " + json.dumps(out))
