"""The dense bed of case 11 (cases/bench/11_bench_dense.py: spheres on a cubic lattice resting on the
floor of a five-wall box, linear Cundall-Strack law) with the time of each stage per process: the
distributed DEM's speed-up case (cases/bench/dem_mpi_speedup.py). A script written for one process, run
as it is by `talus run` and by `mpirun -np N talus run`.

Arguments: PACKING (written by case 11's write_packing), STEPS, OUTPUT (JSON written by process
0: per process the seconds of the set-up, of the timed steps (wall and CPU) and of each stage,
the halo traffic, the load (talus.dem.distributed.balance(): spheres, ghosts, contacts, regions)
and every body's position after the last step).
"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
from bench_scene import read_packing, walled_bed  # noqa: E402
from talus.dem import distributed  # noqa: E402
from talus.dem.analysis import timing

started = time.perf_counter()
packing, steps, output = sys.argv[1], int(sys.argv[2]), sys.argv[3]
(dt, young, density, box_x, box_y), spheres, _ = read_packing(packing)
material = O.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))
O.bodies.append([utils.sphere((x, y, z), r, material=material) for x, y, z, r in spheres])
walled_bed(O, material, box_x, box_y)
O.dt = dt
O.run(1, True)                           # the split over the processes and the first detection
distributed.reset_traffic()
O.timingEnabled = True
built, cpu = time.perf_counter(), time.process_time()
O.run(steps, True)
seconds, cpu = time.perf_counter() - built, time.process_time() - cpu
mine = {"setup_seconds": built - started, "seconds": seconds, "cpu_seconds": cpu}
for engine in timing.rows():
    mine[engine["name"]] = engine["nsec"] * 1e-9
    for stage in engine["stages"]:
        mine[f"{engine['name']}: {stage['name']}"] = stage["nsec"] * 1e-9
result = {"steps": steps, "processes": distributed.per_process(mine), "traffic": distributed.traffic(),
          "balance": distributed.balance(),
          "positions": distributed.positions().tolist()}
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
