"""DEM case: the largest dense bed this machine steps on two MPI processes, its memory per sphere
and its steps per second.

Run:      build/bin/talus run cases/bench/dem_mpi_largest.py [--quick] [--results DIR]
Set-up:   the dense bed of case 11 (cases/bench/11_bench_dense.py: spheres of radius 5 mm on a
          cubic lattice resting on the floor of a five-wall box, linear Cundall-Strack law), written
          as a sphere file and run by cases/scenes/file_bed.py, a script written for one process,
          which reads it with ymport.text: under `mpirun -np 2 talus run -j 1` each process reads
          its own slab of the file (no process ever holds all the spheres), the first step splits
          the scene (Zoltan's RCB), then STEPS steps are timed. First 200 000 spheres in one
          process and on two (what splitting does to a process's peak memory), then, in full
          mode, at least 5 000 000 spheres (5 038 848: whole rows of the lattice) on two processes;
          quick: the 200 000 only.
Checked:  dem.mpi.largest: the peak resident memory of both processes together (the sum of their
          peaks) stepping 5 038 848 spheres in full mode (quick mode projects the 200 000-sphere
          run's bytes per sphere to 5 million): <= 24 GB, the machine's memory.
          The details hold the spheres run, each process's peak and where it was reached (reading,
          first step, the steps), the bytes per sphere, the steps per second (the slower process's
          wall seconds for the timed steps, and its CPU seconds, which other work on the machine
          does not lengthen), the contacts, and the 200 000-sphere runs in one process and on two.
Result:   full (2026-12-07, load 2): 5 038 848 spheres on 2 processes in 15.8 GB (3 144 bytes
          per sphere, the peak at the end of the first step; much of it heap kept by the
          allocator: docs/distributed-dem.md), 1.68 steps/s of CPU time, the reading 70 s.
Produces: the record and the chart dem.mpi.largest.png (peak memory per process at each stage).
"""
import importlib.util
import os
import tempfile
from pathlib import Path

import numpy as np

from talus import bench, results

HERE = Path(__file__).resolve().parent
SCENE = HERE.parent / "scenes" / "file_bed.py"
TARGET_SPHERES, MEMORY = 5_000_000, 24e9
STAGES = [("reading", "read_peak_bytes"), ("first step", "first_step_peak_bytes"), ("steps", "peak_bytes")]


def dense_bed_case():
    """Case 11 (cases/bench/11_bench_dense.py), whose lattice this case steps."""
    spec = importlib.util.spec_from_file_location("bench_dense", HERE / "11_bench_dense.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def write_packing(path: Path, n: int) -> int:
    """Case 11's lattice of about n spheres as a sphere file file_bed.py reads: `# dt young
    density box_x box_y`, then `x y z r` per sphere."""
    bench_dense = dense_bed_case()
    centres, dt, box_x, box_y = bench_dense.bed_lattice(n)
    radius = bench_dense.RADIUS
    with open(path, "w") as out:
        out.write(f"# {dt!r} {bench_dense.YOUNG!r} {bench_dense.DENSITY!r} {box_x!r} {box_y!r}\n")
        for start in range(0, len(centres), 100_000):
            out.writelines(f"{x!r} {y!r} {z!r} {radius!r}\n" for x, y, z in centres[start:start + 100_000].tolist())
    return len(centres)


def lattice_request(target: int) -> int:
    """The smallest request for which case 11's lattice (whole rows of spheres) holds at least
    `target` spheres: asking for exactly 5 million gives 4 992 300."""
    shape = dense_bed_case().bed_shape
    n = target
    while np.prod(shape(n)) < target:
        n += max(1, target // 1000)
    return n


def run(packing: Path, spheres: int, steps: int, processes: int | None, folder: Path) -> dict:
    """file_bed.py on `packing` in one process (None) or on `processes`; its output with the
    bytes per sphere and the steps per second."""
    out = folder / "run.json"
    load = os.getloadavg()[0]
    result = bench.run_talus_script([SCENE, packing, steps, out], out, processes=processes, timeout=7200)
    per = result["processes"]
    peaks = [p["peak_bytes"] for p in per]
    result.update(load=load, processes_count=len(per), peak_sum_bytes=sum(peaks),
                  bytes_per_sphere=sum(peaks) / spheres,
                  largest_process_bytes_per_owned_sphere=max(p["peak_bytes"] / p["owned"] for p in per),
                  steps_per_second=steps / max(p["seconds"] for p in per),
                  cpu_steps_per_second=steps / max(p["cpu_seconds"] for p in per))
    print(f"{spheres} spheres on {len(per)} process(es): peaks {[f'{b / 1e9:.2f} GB' for b in peaks]}, "
          f"{result['bytes_per_sphere']:.0f} bytes per sphere, {result['steps_per_second']:.2f} steps/s, "
          f"reading {max(p['read_seconds'] for p in per):.1f} s, load {load:.2f}")
    return result


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.largest", quick=args.quick, folder=args.results)
    steps = 20
    runs = {}
    with tempfile.TemporaryDirectory(prefix="talus-largest-") as tmp:
        folder = Path(tmp)
        small = folder / "bed-small.txt"
        n = write_packing(small, 200_000)
        runs[f"{n} x 1"] = (n, run(small, n, steps, None, folder))
        runs[f"{n} x 2"] = (n, run(small, n, steps, 2, folder))
        if not args.quick:
            small.unlink()
            large = folder / "bed-large.txt"
            n = write_packing(large, lattice_request(TARGET_SPHERES))
            runs[f"{n} x 2"] = (n, run(large, n, steps, 2, folder))
    label, (spheres, largest) = list(runs.items())[-1]
    if spheres >= TARGET_SPHERES:   # full mode: the run's own peak
        measured = f"stepping {spheres} spheres of a dense bed"
        peak = largest["peak_sum_bytes"]
    else:                           # quick mode: the 200 000-sphere run's peak, scaled
        measured = f"for {TARGET_SPHERES} spheres of a dense bed, at the measured bytes per sphere"
        peak = largest["bytes_per_sphere"] * TARGET_SPHERES
    one, two = list(runs.values())[0][1], list(runs.values())[1][1]
    case.record(f"peak resident memory of 2 processes (summed) {measured}", peak / 1e9,
                "the machine's memory (GB)", MEMORY / 1e9, comparison="<=",
                spheres=spheres, steps=steps, bytes_per_sphere=largest["bytes_per_sphere"],
                largest_process_bytes_per_owned_sphere=largest["largest_process_bytes_per_owned_sphere"],
                steps_per_second=largest["steps_per_second"], cpu_steps_per_second=largest["cpu_steps_per_second"],
                split_over_one_process_peak=max(p["peak_bytes"] for p in two["processes"])
                / one["processes"][0]["peak_bytes"],
                runs={k: {key: r[key] for key in ("bytes_per_sphere", "steps_per_second", "cpu_steps_per_second",
                                                  "peak_sum_bytes", "load",
                                                  "largest_process_bytes_per_owned_sphere")}
                      | {"processes": r["processes"], "spheres": n} for k, (n, r) in runs.items()})

    fig, ax = plt.subplots(figsize=(8, 4))
    bars = [(f"{k}\nprocess {p}", process) for k, (_, r) in runs.items() for p, process in enumerate(r["processes"])]
    for s, (stage, key) in enumerate(STAGES):
        ax.bar(np.arange(len(bars)) + (s - 1) * 0.27, [process[key] / 1e9 for _, process in bars], 0.27, label=stage)
    ax.set_xticks(np.arange(len(bars)), [b for b, _ in bars], fontsize=8)
    ax.set_ylabel("peak resident memory (GB)")
    ax.set_title(f"dense bed read in slabs ({label} spheres x processes): {largest['bytes_per_sphere']:.0f} bytes "
                 f"per sphere, {largest['steps_per_second']:.2f} steps/s", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
