# The drainage scenario of cases/pore/twophase_drainage.py, one script for both programs: run by
# talus.twin.run(script, params, "yade" or "talus") (Yade: `yade -n -j1 -x twophase_drainage.py`;
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
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # twophase_scene.py, under Yade's -x too
from twophase_scene import invade, read_spheres, reservoir_engine  # noqa: E402

params = json.loads(os.environ["TALUS_SCENARIO"])
spheres, lo, hi = read_spheres(params["packing"])


def drainage():
    tp = reservoir_engine(spheres, lo, hi, surfaceTension=float(params["surfaceTension"]),
                          entryPressureMethod=int(params["entryPressureMethod"]),
                          isPhaseTrapped=bool(params["isPhaseTrapped"]))
    t0, c0 = time.perf_counter(), time.process_time()
    tp.initialization()
    saturations = invade(tp, params["pcs"])
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    tp.isDrainageActivated = False
    tp.isImbibitionActivated = True
    return wall, cpu, saturations, tp.nCells(), invade(tp, params.get("imbibition_pcs", []))


runs = [drainage() for _ in range(int(params.get("repeats", 1)))]
walls, cpus = sorted(r[0] for r in runs), sorted(r[1] for r in runs)
print("RESULT " + json.dumps({"saturations": runs[-1][2], "wall_s": walls[len(walls) // 2],
                              "cpu_s": cpus[len(cpus) // 2], "nCells": runs[-1][3], "imbibition": runs[-1][4]}))
