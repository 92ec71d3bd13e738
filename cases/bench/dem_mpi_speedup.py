"""DEM case: two MPI processes step a dense bed faster than one.

Run:      build/bin/talus run cases/bench/dem_mpi_speedup.py [--quick] [--results DIR]
Set-up:   the dense bed of case 11 (cases/bench/11_bench_dense.py: spheres of radius 5 mm on a cubic
          lattice resting on the floor of a five-wall box, linear Cundall-Strack law), run by
          cases/scenes/mpi_bed.py, unchanged, as `talus run -j 1` (1 process x 1 thread),
          `talus run -j 2` (1 x 2) and `mpirun -np 2 talus run -j 1` (2 x 1), as a user types it. One
          step builds the contacts (and splits the scene), then STEPS steps are timed. Full:
          200 000 spheres, 200 steps, each configuration twice, alternately (the faster run
          counts: other work on the machine only slows a run down); quick: 20 000 spheres, 300
          steps, once. Open MPI binds 2 processes to a core each by default; `talus run` gives
          them every CPU back (a bound process shares its core with other work on the machine
          while every step waits for it: 200 000 spheres, 100 steps, load average 1.9: 6.8 s
          bound, 2.8 s not), unless the user asks for a binding with --bind-to.
Checked:  dem.mpi.speedup-2: the seconds of the timed steps in 1 x 1 over those in 2 x 1 (the
          slower process), >= 1.8 on this 2-core machine. The details hold the ratio against
          1 x 2, the ratios of the whole runs (set-up included) and of the CPU seconds (a
          process's CPU seconds less those it spent waiting in MPI calls for the other), each
          process's seconds per stage, the halo's bytes and messages per process and step, the
          load average before each run (other work on the machine slows the runs: the figure
          means something only when it is low), and the largest difference of a position from
          the 1 x 1 run after the last step (0: the same bits).
Produces: the record and the chart dem.mpi.speedup-2.png (seconds per stage, per process, in each
          configuration).
"""
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import talus
from talus import results

HERE = Path(__file__).resolve().parent
PACKAGE_ROOT = str(Path(talus.__file__).resolve().parents[1])  # for the processes the case starts
SCENE = HERE.parent / "scenes" / "mpi_bed.py"
CONFIGURATIONS = {"1 x 1": (None, 1), "1 x 2": (None, 2), "2 x 1": (2, 1)}
#: Stages of the chart: (label, the per-process entries of mpi_bed.py's output summed).
STAGES = [("contacts", ["InteractionLoop: geometry, physics, law"]),
          ("force gather", ["InteractionLoop: forces per body"]),
          ("force reset", ["ForceResetter"]),
          ("integration", ["NewtonIntegrator", "-update_seconds"]),
          ("ghost update", ["update_seconds"]),
          ("skin check", ["InsertionSortCollider: skin check", "-reduction_seconds"]),
          ("reductions", ["reduction_seconds"]),
          ("re-detection", ["InsertionSortCollider", "-InsertionSortCollider: skin check", "-rebuild_seconds"]),
          ("migration, ghost rebuild", ["rebuild_seconds"])]


def write_packing(path: Path, spheres: int) -> int:
    """Case 11's lattice of about `spheres` spheres (its write_packing)."""
    spec = importlib.util.spec_from_file_location("bench_dense", HERE / "11_bench_dense.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    return bench.write_packing(path, spheres)


def run(configuration: str, packing: Path, steps: int, folder: Path) -> dict:
    """mpi_bed.py in one configuration; its output with the load average before and the wall
    seconds of the whole run (start-up and set-up included)."""
    processes, threads = CONFIGURATIONS[configuration]
    out = folder / "run.json"
    talus = [sys.executable, "-m", "talus", "run", "-j", str(threads), str(SCENE), str(packing), str(steps), str(out)]
    command = talus if processes is None else ["mpirun", "--allow-run-as-root", "-np", str(processes), *talus]
    load = os.getloadavg()[0]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, timeout=3600,
                          env={**os.environ, "OMP_NUM_THREADS": str(threads),
                               "PYTHONPATH": PACKAGE_ROOT})
    whole = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
    result = json.loads(out.read_text())
    result.update(load=load, whole_seconds=whole)
    traffic = result["traffic"] or [{}] * len(result["processes"])
    for process, halo in zip(result["processes"], traffic):
        process.update({k: v for k, v in halo.items() if k.endswith("seconds")})
    print(f"{configuration}: {max(p['seconds'] for p in result['processes']):.3f} s for {steps} steps, "
          f"{whole:.1f} s in all, load {load:.2f}")
    return result


def stage_seconds(process: dict) -> dict:
    """Seconds per charted stage of one process."""
    def term(key):
        sign, key = (-1, key[1:]) if key.startswith("-") else (1, key)
        return sign * process.get(key, 0.0)
    return {label: max(sum(term(k) for k in keys), 0.0) for label, keys in STAGES}


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.speedup-2", quick=args.quick, folder=args.results)
    wanted, steps, repeats = (20_000, 300, 1) if args.quick else (200_000, 200, 2)
    best: dict[str, dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        packing = Path(tmp) / "bed.txt"
        spheres = write_packing(packing, wanted)
        for _ in range(repeats):
            for configuration in CONFIGURATIONS:
                r = run(configuration, packing, steps, Path(tmp))
                r["timed"] = max(p["seconds"] for p in r["processes"])
                if configuration not in best or r["timed"] < best[configuration]["timed"]:
                    best[configuration] = r
    serial, threads, split = best["1 x 1"], best["1 x 2"], best["2 x 1"]
    speedup = serial["timed"] / split["timed"]
    # A process waiting for the other in MPI polls: its CPU seconds less those of the waits are its
    # work, which other work on the machine does not lengthen as it does wall seconds.
    cpu = serial["processes"][0]["cpu_seconds"] / max(p["cpu_seconds"] - p["wait_cpu_seconds"]
                                                      for p in split["processes"])
    difference = float(np.abs(np.asarray(split["positions"]) - np.asarray(serial["positions"])).max())
    halo = [{"update_bytes_per_step": t["update_bytes"] / max(t["updates"], 1),
             "update_messages_per_step": t["update_messages"] / max(t["updates"], 1),
             "rebuild_bytes": t["rebuild_bytes"], "redetections": t["rebuilds"]} for t in split["traffic"]]
    stages = {c: [stage_seconds(p) for p in r["processes"]] for c, r in best.items()}
    print(f"2 x 1 over 1 x 1: {speedup:.3f} (CPU seconds: {cpu:.3f}); over 1 x 2: "
          f"{threads['timed'] / split['timed']:.3f}; largest position difference {difference:.3g}")
    for p, h in enumerate(halo):
        print(f"process {p}: {h['update_bytes_per_step']:.0f} bytes in {h['update_messages_per_step']:.2f} "
              f"messages per step")
    case.record("seconds of the timed steps of a dense bed in 1 process x 1 thread over 2 processes x 1 thread",
                speedup, "the same script in one process with one thread (talus run -j 1)", 1.8, comparison=">=",
                spheres=spheres, steps=steps, repeats=repeats,
                over_one_process_two_threads=threads["timed"] / split["timed"],
                whole_run_ratio=serial["whole_seconds"] / split["whole_seconds"], cpu_seconds_ratio=cpu,
                split_seconds=[p["split_seconds"] for p in split["processes"]],
                seconds={c: r["timed"] for c, r in best.items()},
                whole_seconds={c: r["whole_seconds"] for c, r in best.items()},
                load_before={c: r["load"] for c, r in best.items()},
                largest_position_difference=difference, halo_per_process=halo, stages=stages)

    fig, ax = plt.subplots(figsize=(9, 4.2))
    bars = [(c, p, s) for c, per in stages.items() for p, s in enumerate(per)]
    labels = [f"{c}\nprocess {p}" if len(stages[c]) > 1 else c for c, p, _ in bars]
    bottom = np.zeros(len(bars))
    for label, _ in STAGES:
        heights = np.array([s[label] for _, _, s in bars])
        if heights.any():
            ax.bar(labels, heights, bottom=bottom, label=label)
            bottom += heights
    ax.set_ylabel(f"seconds for {steps} steps")
    loads = ", ".join(f"{r['load']:.1f}" for r in best.values())
    ax.set_title(f"dense bed of {spheres} spheres: time per stage and process (2 x 1 over 1 x 1: "
                 f"{speedup:.2f})\nload averages before the runs: {loads}", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
