"""The dense bed's step against this machine's roofs: memory bandwidth and peak flop rate.

Run:      build/bin/talus run cases/bench/dem_roofline.py [--quick] [--spheres N] [--results DIR]
Machine:  cases/bench/roofline_probe.cpp, compiled here with the project's Release flags (-O3 -DNDEBUG,
          no -march: SSE2, vectors of 2 doubles, no fused multiply-add) and once more with
          -march=native (the widest vectors and FMA the CPU has), OpenMP: STREAM's copy and triad
          (bytes counted as STREAM does: every element read or written once) over arrays the size
          of the bed's working set and of 1 GiB (past the caches), and chains of independent
          multiply-adds held in registers; the best of 10 repetitions (quick 5), at 1 and 2 threads
          (each thread times itself and the rates add up: no barrier waits for a thread the
          shared machine paused; if the threads did not overlap the sum is too high, so the
          fractions below are then too low, never too high).
Bed:      cases/scenes/dense_bed.py on case 11's lattice (20 000 spheres, quick 8 000; linear
          Cundall-Strack, five walls), 20 steps to settle past the first re-detections, then
          200 steps (quick 100) with O.timingEnabled, at 1 and 2 threads; the run of least total
          time of 3 (quick 1). Each stage's time is the scheduler's (the longest thread's).
          The bed and the probe run under `chrt -f 10` where allowed (talus.bench.realtime_prefix):
          on the shared machine a 2-thread run otherwise waits at each barrier for a thread
          another session's process holds.
Model:    the bytes a stage must move per step, counting each array element it reads or writes
          once (no reuse across steps, no read-for-ownership; a lower bound of the traffic, as
          STREAM's convention), for N bodies, C candidate pairs in the contact list, R of them real:
            reset        force, torque = extForce, extTorque: 96 B per body, no flops;
            contacts     a candidate's first cache line (ids, kind, real): 64 B, and 13 flops of
                         its overlap test; a real contact reads and writes its whole 256-B record
                         (512 B) and 153 flops (geometry 128: distance, normal, contact point,
                         the shear force turned with the frame, the incident velocity, the shear
                         increment; the linear law 25); the bodies' position, radius, velocity
                         and angular velocity once each: 80 B per body;
            gather       per body start index, position, force and torque read and written: 128 B
                         and 6 flops; per contact its two index entries and first line: 80 B, and
                         42 flops (force and moment on each of its bodies);
            integration  per body 205 B read (flags, force, torque, velocities, inverse mass and
                         inertia, position, orientation) and 104 B written, 129 flops (Cundall
                         damping on six components, leap-frog, the orientation turned by a
                         normalised quaternion product), with the skin check made right after
                         (the reference position and two flags, 26 B, and 16 flops); sqrt and
                         divisions count as one flop.
          The re-detections are not modelled: their share of the time is reported. The flop
          counts are read off the code (dem/contact/ContactGeometry.h, dem/laws/parts,
          dem/step); `perf stat` has no hardware counters on this virtual machine to check them.
Derived:  per stage and for the step: bytes and flops per particle-step, arithmetic intensity
          (flop/B), achieved GB/s and GFLOP/s; the roof at that intensity is min(peak, intensity x
          bandwidth) with the bandwidth of the bed's working set (the triad's, at the same
          threads) and the peak of the project's flags; the step is memory-bound when its
          intensity is below the ridge (peak / bandwidth), and the fraction is achieved over roof.
Produces: dem.roofline.step-1t and dem.roofline.step-2t: the fraction of the roof that bounds the
          step (target <= 1: a fraction above 1 would mean the counting model undercounts), with
          the bound named, the machine's figures, the per-stage table and the load average; the
          chart dem.roofline.png (log-log: the roofs, the stages and the step at 1 and 2 threads).
"""
import argparse
import json
import os
import re
import runpy
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from talus import bench, results

HERE = Path(__file__).resolve().parent
SCENE = HERE.parent / "scenes" / "dense_bed.py"
PROBE = HERE / "roofline_probe.cpp"
PROJECT_FLAGS = ["-O3", "-DNDEBUG"]   # CMakeLists.txt's Release build: no -march
SETTLE_STEPS = 20
DRAM_BYTES = 1 << 30

# (bytes, flops) per item of each modelled stage: the docstring's model.
PER_BODY = {"reset": (96, 0), "contacts": (80, 0), "gather": (128, 6), "integration": (309 + 26, 129 + 16)}
CANDIDATE = (64, 13)          # a candidate pair's first line and overlap test
REAL = (512 - 64, 153 - 13)   # what a real contact adds to its candidate test
GATHER_CONTACT = (80, 42)
CONTACT_RECORD = 256


def stage_model(bodies: int, candidates: int, real: int) -> dict:
    """Bytes and flops per step of each modelled stage."""
    model = {name: [b * bodies, f * bodies] for name, (b, f) in PER_BODY.items()}
    for (b, f), count, stage in ((CANDIDATE, candidates, "contacts"), (REAL, real, "contacts"),
                                 (GATHER_CONTACT, candidates, "gather")):
        model[stage][0] += b * count
        model[stage][1] += f * count
    return {name: tuple(v) for name, v in model.items()}


def working_set(bodies: int, candidates: int) -> int:
    """Bytes of the arrays a step touches: the contact records and index, the body arrays."""
    return candidates * (CONTACT_RECORD + 16) + bodies * sum(b for b, _ in PER_BODY.values())


# ----------------------------------------------------------------------------- the bed (child)
def run_bed(packing: str, steps: int) -> None:
    """Run in a `talus run -j T` child: the dense bed, then `steps` timed steps; prints one line
    `ROOFLINE {json}` with the stage times and the counts."""
    sys.argv = [str(SCENE), packing, str(SETTLE_STEPS)]
    runpy.run_path(str(SCENE), init_globals=dict(globals()), run_name="__main__")   # the names `talus run` gives a script
    import time
    from talus.dem import O
    from talus.dem.analysis import timing
    O.timingEnabled = True
    timing.reset()
    start = time.perf_counter()
    O.run(steps, True)
    wall = time.perf_counter() - start
    rows = {r["name"]: r for r in timing.rows()}
    stages = {r["name"]: r["nsec"] for r in rows["InteractionLoop"]["stages"]}
    collider = rows["InsertionSortCollider"]
    skin = sum(s["nsec"] for s in collider["stages"] if s["name"] == "skin check")
    # The skin check is mostly made by each thread right after moving its bodies (docs/dem.md,
    # "The step"), so it is one stage with the integration here.
    seconds = {"contacts": stages["geometry, physics, law"], "gather": stages["forces per body"],
               "integration": rows["NewtonIntegrator"]["nsec"] + skin, "re-detection": collider["nsec"] - skin}
    # A step that resets each body's forces in the gather's pass (dem/step/GatherAhead.h) books
    # the reset with the gather (ForceResetter shows no time): roofline() joins the two stages.
    if rows["ForceResetter"]["nsec"] > 0:
        seconds["reset"] = rows["ForceResetter"]["nsec"]
    print("ROOFLINE " + json.dumps({
        "steps": steps, "wall_s": wall, "seconds": {k: v * 1e-9 / steps for k, v in seconds.items()},
        "bodies": len(O.bodies), "spheres": sum(1 for b in O.bodies if b.shape.__class__.__name__ == "Sphere"),
        "candidates": len(O.interactions), "real": O.interactions.countReal()}))


def measure_bed(packing: Path, steps: int, threads: int, runs: int) -> dict:
    best = None
    for _ in range(runs):
        command = bench.talus_command("run", "-j", str(threads), __file__, "--bed", str(packing), "--steps", str(steps))
        out = subprocess.run(bench.realtime_prefix() + command, capture_output=True, text=True, timeout=3600)
        found = re.search(r"^ROOFLINE (.*)$", out.stdout, re.M)
        if out.returncode != 0 or not found:
            raise RuntimeError(f"the dense bed at {threads} threads failed:\n{out.stdout[-2000:]}\n{out.stderr[-2000:]}")
        run = json.loads(found.group(1))
        if best is None or sum(run["seconds"].values()) < sum(best["seconds"].values()):
            best = run
    return best


# ----------------------------------------------------------------------------- the machine
def compile_probe(folder: Path, native: bool) -> Path:
    compiler = os.environ.get("CXX") or shutil.which("c++")
    if not compiler:
        raise RuntimeError("no C++ compiler (c++ or $CXX) to build cases/bench/roofline_probe.cpp")
    exe = folder / ("probe-native" if native else "probe")
    flags = PROJECT_FLAGS + (["-march=native", "-DLANES=8"] if native else ["-DLANES=2"])
    subprocess.run([compiler, "-std=c++20", *flags, "-fopenmp", "-o", str(exe), str(PROBE)], check=True)
    return exe


def probe(exe: Path, threads: int, *args) -> dict:
    out = subprocess.run(bench.realtime_prefix() + [str(exe), *map(str, args)], capture_output=True, text=True, check=True, timeout=600,
                         env={**os.environ, "OMP_NUM_THREADS": str(threads), "OMP_PROC_BIND": "false"}).stdout
    return {m.group(1): [float(v) for v in m.group(2).split()] for m in re.finditer(r"^(\w+) (.*)$", out, re.M)}


def machine(plain: Path, native: Path, threads: int, bed_bytes: int, repetitions: int) -> dict:
    at_bed = probe(plain, threads, "bandwidth", bed_bytes, repetitions)
    dram = probe(plain, threads, "bandwidth", DRAM_BYTES, repetitions)
    return {"threads": threads, "triad_bed_gbs": at_bed["TRIAD"][0], "copy_bed_gbs": at_bed["COPY"][0],
            "bed_bytes": bed_bytes, "triad_dram_gbs": dram["TRIAD"][0], "copy_dram_gbs": dram["COPY"][0],
            "peak_gflops": probe(plain, threads, "flops", 3 * repetitions)["FLOPS"][0], "lanes": 2,
            "peak_native_gflops": probe(native, threads, "flops", 3 * repetitions)["FLOPS"][0],
            "lanes_native": int(probe(native, 1, "flops", 1)["FLOPS"][1])}


# ----------------------------------------------------------------------------- the roofline
def roofline(bed: dict, roofs: dict) -> dict:
    """Per stage and for the modelled step: intensity, achieved rates, bound and fraction."""
    model = stage_model(bed["bodies"], bed["candidates"], bed["real"])
    if "reset" not in bed["seconds"]:   # the reset made in the gather's pass, timed with it
        model["gather"] = [a + b for a, b in zip(model["gather"], model.pop("reset"))]
    bandwidth, peak = roofs["triad_bed_gbs"], roofs["peak_gflops"]
    rows = {}
    for name, (nbytes, flops) in list(model.items()) + [("step", tuple(map(sum, zip(*model.values()))))]:
        seconds = sum(bed["seconds"][k] for k in model) if name == "step" else bed["seconds"][name]
        intensity = flops / nbytes
        gflops, gbs = flops / seconds * 1e-9, nbytes / seconds * 1e-9
        memory_bound = intensity * bandwidth < peak
        rows[name] = {"bytes_per_particle_step": nbytes / bed["spheres"], "flops_per_particle_step": flops / bed["spheres"],
                      "ns_per_particle_step": seconds * 1e9 / bed["spheres"], "intensity": intensity,
                      "gbs": gbs, "gflops": gflops, "bound": "memory" if memory_bound else "compute",
                      "fraction": gbs / bandwidth if memory_bound else gflops / peak}
    rows["step"]["redetection_share"] = bed["seconds"]["re-detection"] / sum(bed["seconds"].values())
    return rows


def chart(case, measured: dict) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(figsize=(7, 5))
    x = np.logspace(-1.5, 1.5, 200)
    colours = {1: "tab:blue", 2: "tab:orange"}
    for threads, (roofs, rows) in measured.items():
        c = colours[threads]
        ax.loglog(x, np.minimum(roofs["peak_gflops"], x * roofs["triad_bed_gbs"]), "-", color=c,
                  label=f"{threads} thread(s): triad over the bed's {roofs['bed_bytes'] / 2**20:.0f} MiB, peak of the project's flags")
        ax.loglog(x, np.minimum(roofs["peak_gflops"], x * roofs["triad_dram_gbs"]), ":", color=c,
                  label=f"{threads} thread(s): triad over 1 GiB")
        ax.axhline(roofs["peak_native_gflops"], ls="--", color=c, lw=0.8,
                   label=f"{threads} thread(s): peak with -march=native ({roofs['lanes_native']}-lane FMA)")
        for name, r in rows.items():
            if r["intensity"] == 0:   # the reset: no flops, no point on a log scale (its fraction is recorded)
                continue
            ax.loglog(r["intensity"], r["gflops"], "*" if name == "step" else "o", color=c, ms=12 if name == "step" else 6)
            if threads == 1:
                ax.annotate(name, (r["intensity"], r["gflops"]), textcoords="offset points", xytext=(5, -10), fontsize=8)
    ax.set_xlabel("arithmetic intensity (flop per byte)")
    ax.set_ylabel("GFLOP/s")
    ax.set_title("Dense bed (linear law): stages against the roofs")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    case.save_chart(fig)


def main():
    if "--bed" in sys.argv:
        child = argparse.ArgumentParser()
        child.add_argument("--bed", required=True)
        child.add_argument("--steps", type=int, required=True)
        a = child.parse_args()
        run_bed(a.bed, a.steps)
        return
    parser = results.case_arguments(__doc__)
    parser.add_argument("--spheres", type=int, default=None, help="spheres in the bed (default 20 000, quick 8 000)")
    args = parser.parse_args()
    quick = args.quick
    spheres = args.spheres or (8000 if quick else 20000)
    steps, runs, repetitions = (100, 1, 5) if quick else (200, 3, 10)
    sys.path.insert(0, str(HERE))
    bench_dense = __import__("11_bench_dense")
    case = results.Case("dem.roofline", quick=quick, folder=args.results)
    load = os.getloadavg()[0]
    measured = {}
    with tempfile.TemporaryDirectory(prefix="talus-roofline-") as scratch:
        folder = Path(scratch)
        packing = folder / "bed.txt"
        bench_dense.write_packing(packing, spheres)
        probes = compile_probe(folder, False), compile_probe(folder, True)
        for threads in (1, 2):
            bed = measure_bed(packing, steps, threads, runs)
            roofs = machine(*probes, threads, max(1 << 20, working_set(bed["bodies"], bed["candidates"])), repetitions)
            measured[threads] = (roofs, roofline(bed, roofs))
            step = measured[threads][1]["step"]
            print(f"{threads} thread(s), load {load:.1f}: triad {roofs['triad_bed_gbs']:.1f} GB/s at "
                  f"{roofs['bed_bytes'] / 2**20:.0f} MiB ({roofs['triad_dram_gbs']:.1f} at 1 GiB), peak "
                  f"{roofs['peak_gflops']:.1f} GFLOP/s (SSE2), {roofs['peak_native_gflops']:.1f} ({roofs['lanes_native']} lanes, FMA)")
            for name, r in measured[threads][1].items():
                print(f"  {name:<12} {r['ns_per_particle_step']:7.1f} ns {r['bytes_per_particle_step']:7.0f} B "
                      f"{r['flops_per_particle_step']:6.0f} flop  I={r['intensity']:.3f}  {r['gbs']:6.2f} GB/s "
                      f"{r['gflops']:6.2f} GFLOP/s  {r['bound']}-bound, {100 * r['fraction']:.0f} % of the roof")
            case.record(f"{bed['spheres']} spheres, {threads} thread(s): fraction of the bounding roof the step reaches",
                        step["fraction"],
                        f"{step['bound']}-bound: {step['bytes_per_particle_step']:.0f} B and {step['flops_per_particle_step']:.0f} "
                        f"flop per particle-step against triad {roofs['triad_bed_gbs']:.1f} GB/s over the working set, "
                        f"peak {roofs['peak_gflops']:.1f} GFLOP/s (project flags); load {load:.1f}",
                        1.0, suffix=f"step-{threads}t", bound=step["bound"], threads=threads, spheres=bed["spheres"],
                        contacts=bed["candidates"], real_contacts=bed["real"], load_average=load, machine=roofs,
                        stages=measured[threads][1], model="bytes: each element read or written once per step; "
                        "contact record 256 B (first line 64 B for a candidate's test); flops read off the code")
    chart(case, measured)


if __name__ == "__main__":
    main()
