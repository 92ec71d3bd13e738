"""A bed of spheres read from a sphere file by ymport.text, resting on the floor of a five-wall box
(linear Cundall-Strack law, gravity): a script written for one process, run as it is by `talus
run` and by `mpirun -np N talus run`, where each process reads only its slab of the file
(talus.dem.files.slabs). The largest-bed case (cases/bench/dem_mpi_largest.py) and the slab tests
(tests/dem/distributed/test_mpi_slabs.py) run it.

Arguments: PACKING STEPS OUTPUT [positions]. PACKING: a first line `# dt young density box_x box_y`,
then `x y z r` per sphere (ymport.text's format, which skips the comment line). OUTPUT: JSON
written by process 0: per process the rows it held before the split, its peak resident memory
and resident memory (bytes) at the end of the reading, of the first step and of the run, the seconds of the reading,
of the first step and of the STEPS timed steps (wall and CPU), the bodies it owns and the contacts
it holds after the last step; with `positions`, every body's position after the last step.
"""
import json
import os
import resource
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
from bench_scene import walled_bed  # noqa: E402
from yade import ymport  # noqa: E402
from talus.dem import distributed  # noqa: E402


def peak_bytes():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()


packing, steps, output = sys.argv[1], int(sys.argv[2]), sys.argv[3]
with open(packing) as f:
    dt, young, density, box_x, box_y = (float(v) for v in f.readline().split()[1:])
started = time.perf_counter()
material = O.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))
O.bodies.append(ymport.text(packing, material=material))
walled_bed(O, material, box_x, box_y)
O.dt = dt
mine = {"rows_before_split": O._cpp.bodyCount(), "read_peak_bytes": peak_bytes(), "read_bytes": resident_bytes(),
        "read_seconds": time.perf_counter() - started}
first = time.perf_counter()
O.run(1, True)                           # the split over the processes and the first detection
mine.update(first_step_seconds=time.perf_counter() - first, first_step_peak_bytes=peak_bytes(),
            first_step_bytes=resident_bytes())
timed, cpu = time.perf_counter(), time.process_time()
O.run(steps, True)
mine.update(seconds=time.perf_counter() - timed, cpu_seconds=time.process_time() - cpu, peak_bytes=peak_bytes(),
            bytes=resident_bytes(), contacts=O._cpp.realContactCount())
d = distributed.domain(O)
mine["owned"] = len(d.ownedBodies(O._cpp)[0]) if d is not None else O._cpp.bodyCount() - 5
result = {"spheres": len(O.bodies) - 5, "steps": steps, "processes": distributed.per_process(mine)}
if sys.argv[4:] == ["positions"]:
    result["positions"] = distributed.positions().tolist()
if distributed.rank() == 0:
    with open(output, "w") as f:
        json.dump(result, f)
