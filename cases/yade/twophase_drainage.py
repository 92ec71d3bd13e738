# The drainage scenario of cases/twophase_drainage.py, one script for both programs: run by
# talus.dem.twin.run(script, params, "yade" or "talus") (Yade: `yade -n -j1 -x twophase_drainage.py`;
# Talus: its Yade names) with the parameters as JSON in $TALUS_SCENARIO:
#   packing              sphere file (x y z r per line)
#   pcs                  capillary pressures of the drainage steps, in order
#   imbibition_pcs       optional: capillary pressures of the imbibition steps that follow (drainage
#                        off, imbibition on; their saturations are in "imbibition")
#   surfaceTension, entryPressureMethod, isPhaseTrapped
#   repeats              how many times the drainage is timed, each on a fresh scene (the median is
#                        the case's; the saturations are those of the last)
# The spheres go in the six walls of their bounding box (boundaryUseMaxMin on), TwoPhaseFlowEngine
# gets the wetting reservoir at ymin and the non-wetting one at ymax (pressure 0), and for each pc
# the wetting pressure is set to -pc before invasion(); the saturation (side pores excluded,
# Yade's default) is read after each step. Printed as one line `RESULT {json}`: the saturations,
# the wall and CPU time of initialization() + the drainage steps, the cell count.
import json
import os
import time

try:
    O
except NameError:  # not in Yade: Talus's names
    from talus.dem import *
    from talus.flow import TwoPhaseFlowEngine

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres = [tuple(map(float, l.split()[:4])) for l in open(params["packing"]) if l.strip() and not l.startswith("#")]
lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]


def drainage():
    O.reset()
    O.bodies.append(aabbWalls([Vector3(*lo), Vector3(*hi)], thickness=0))
    for x, y, z, r in spheres:
        O.bodies.append(sphere((x, y, z), r, fixed=True))
    tp = TwoPhaseFlowEngine()
    tp.bndCondIsPressure = [0, 0, 1, 1, 0, 0]
    tp.bndCondValue = [0, 0, 0, 0, 0, 0]
    tp.surfaceTension = float(params["surfaceTension"])
    tp.entryPressureMethod = int(params["entryPressureMethod"])
    tp.isPhaseTrapped = bool(params["isPhaseTrapped"])
    t0, c0 = time.perf_counter(), time.process_time()
    tp.initialization()
    saturations = []
    for pc in params["pcs"]:
        tp.bndCondValue = [0, 0, -pc, 0, 0, 0]
        tp.invasion()
        saturations.append(tp.getSaturation(False))
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    tp.isDrainageActivated = False
    tp.isImbibitionActivated = True
    imbibition = []
    for pc in params.get("imbibition_pcs", []):
        tp.bndCondValue = [0, 0, -pc, 0, 0, 0]
        tp.invasion()
        imbibition.append(tp.getSaturation(False))
    return wall, cpu, saturations, tp.nCells(), imbibition


runs = [drainage() for _ in range(int(params.get("repeats", 1)))]
walls, cpus = sorted(r[0] for r in runs), sorted(r[1] for r in runs)
print("RESULT " + json.dumps({"saturations": runs[-1][2], "wall_s": walls[len(walls) // 2],
                              "cpu_s": cpus[len(cpus) // 2], "nCells": runs[-1][3], "imbibition": runs[-1][4]}))
