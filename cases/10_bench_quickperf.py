"""Case 10: Yade's speed test, side by side.

Run:      build/bin/talus run cases/10_bench_quickperf.py [--quick] [--results DIR]
Scene:    Yade's `--quickperformance` test reproduced exactly: 4416 spheres (radius 0.5/23.658,
          gap radius/2) on an hcp lattice inside a ball of radius 0.5, in a 12-facet box 1.05
          times the packing's extents, ViscElMat (density 2300, friction 35 deg, tc 1e-3,
          en = et = 0.003), gravity -9.81 along y, no damping, dt = 0.1 tc; one step to
          initialise, then 2000 timed steps.
Compared: `yade -n -j1 --quickperformance` (Yade 2023.02a from Debian), run in the same
          invocation, alternately with ours; medians of the iterations per second.
Produces: dem.bench.yade-quickperf (ratio, target >= 5 at one thread) and
          dem.bench.yade-quickperf.threads (our 2-thread over 1-thread speed-up, target >= 1.7;
          Yade's own speed-up, `yade -j2`, and the ratio at two threads as extras).
"""
import math
import os
import shutil
import sys
import tempfile
import time

from talus import bench, results

STEPS = 2000


def run_scene(steps: int) -> float:
    """Build the scene, run it, return iterations per second over the timed steps."""
    from talus.dem import (ForceResetter, InsertionSortCollider, InteractionLoop,
                           Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
                           NewtonIntegrator, O, ViscElMat, geom, pack)
    import numpy as np
    tc = 1e-3
    mat = O.materials.append(ViscElMat(density=2300, frictionAngle=math.radians(35), tc=tc, en=0.003, et=0.003))
    O.dt = 0.1 * tc
    radius = 0.5 / 23.658
    ids = O.bodies.append(pack.regularHexa(pack.inSphere((0, 0, 0), 0.5), radius=radius, gap=radius * 0.5, material=mat))
    pos = O.positions()[ids]
    lo, hi = (pos - radius).min(axis=0), (pos + radius).max(axis=0)
    O.bodies.append(geom.facetBox((lo + hi) / 2, (hi - lo) / 2 * 1.05, material=mat))
    O.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]),
                 NewtonIntegrator(damping=0, gravity=(0, -9.81, 0))]
    O.run(1)
    start = time.perf_counter()
    O.run(steps)
    rate = steps / (time.perf_counter() - start)
    assert np.all(np.isfinite(O.positions())), "the speed test diverged"
    return rate


def main():
    if "--run-talus" in sys.argv:
        print(f"Performance {run_scene(STEPS):.3f} iter/sec")
        return
    args = results.case_arguments(__doc__).parse_args()
    repeat = 1 if args.quick else 3
    me = bench.talus_command("run", os.path.abspath(__file__), "--run-talus")
    pattern = r"Performance ([0-9.]+) iter/sec"
    case = results.Case("dem.bench.yade-quickperf", quick=args.quick, folder=args.results)
    if shutil.which("yade") is None:
        print("yade is not installed (apt-get install yade): no comparison recorded")
        return
    ours = bench.Side("talus -j1", me, pattern)
    os.environ["OMP_NUM_THREADS"] = "1"
    # Yade's speed test writes a summary file where it runs: give it a scratch folder.
    with tempfile.TemporaryDirectory(prefix="talus-bench-") as scratch:
        yade = bench.Side("yade -j1", ["yade", "-n", "-j1", "--quickperformance"],
                          r"calculation velocity=\s*([0-9.]+)", cwd=scratch)
        c = bench.compare(ours, yade, repeat=repeat, unit="it/s", higher_is_better=True)
    case.record("iterations per second, Talus over Yade, 1 thread", c.ratio,
                "yade 2023.02a --quickperformance, same machine, same invocation", 5.0, comparison=">=",
                peer="yade 2023.02a, 1 thread", ours=c.ours, theirs=c.theirs, unit="it/s", ratio=c.ratio)
    # Two threads, ours and Yade's own (the peer's speed-up on the same machine tells how much
    # of a shortfall is the machine's: two vCPUs need not give two cores' worth of throughput).
    os.environ["OMP_NUM_THREADS"] = "2"
    two = bench.Side("talus -j2", me, pattern)
    with tempfile.TemporaryDirectory(prefix="talus-bench-") as scratch:
        yade_two = bench.Side("yade -j2", ["yade", "-n", "-j2", "--quickperformance"],
                              r"calculation velocity=\s*([0-9.]+)", cwd=scratch)
        c2 = bench.compare(two, yade_two, repeat=repeat, unit="it/s", higher_is_better=True)
    speedup, yade_speedup = c2.ours / c.ours, c2.theirs / c.theirs
    case.record("speed-up from 1 to 2 OpenMP threads", speedup, "Talus at 1 thread, same scene", 1.7,
                suffix="threads", comparison=">=", yade_speedup=yade_speedup, ours_2_threads=c2.ours,
                yade_2_threads=c2.theirs, ratio_2_threads=c2.ratio)
    print(f"Talus {c.ours:.0f} it/s, Yade {c.theirs:.0f} it/s: {c.ratio:.2f}x; 2 threads: Talus {speedup:.2f}x, "
          f"Yade {yade_speedup:.2f}x (Talus over Yade at 2 threads {c2.ratio:.2f}x)")


main()
