"""DEM case: how the distributed DEM would scale to 1024 processes, projected from what 1 to 4
processes measure on this 2-core machine, and the imbalance before and after rebalancing.

Run:      build/bin/talus run cases/bench/dem_mpi_scaling_model.py [--quick] [--results DIR]
          [--latency SECONDS] [--bandwidth BYTES_PER_SECOND]
Measured: (1) the dense bed of case 11 (cases/scenes/mpi_bed.py: spheres on a cubic lattice in a
          five-wall box, linear law) in one process and under `mpirun -np 2, 3, 4` (oversubscribed
          beyond 2, one thread each): the serial CPU seconds per sphere and step (c), and per
          process its spheres, ghosts, the contacts it computes with a ghost (computed by the
          ghost's owner too), its region, and the ghost update's bytes and messages per step
          (MpiDomain::Traffic). Full: 200 000 spheres, 100 timed steps; quick: 20 000, 50.
          (2) the silo of facets discharging (cases/scenes/silo_discharge.py, tall: side=6, its
          spheres leave the regions of the processes at the top as it empties) under `mpirun -np
          4`, without rebalancing (talus.dem.distributed.rebalanceThreshold None) and with the
          default threshold (1.1): the imbalance, the slowest process's compute seconds over the
          mean (CPU seconds not spent waiting in MPI calls) summed over the run, and the
          rebalances. Full: 1500 spheres, 8000 steps; quick: 1000, 4000.
Model:    one step of a process holding n of N spheres among P processes takes
            t(P) = I c n (1 + dup(n)) + m alpha + 128 g(n) / beta + 2 log2(P) alpha
          - g(n) ghosts: its region a cube of side L = (n / rho)^(1/3) among cubes (rho spheres per
            unit volume), the ghosts the spheres within the ghost distance delta of it (twice the
            largest radius plus the skin): g = k rho ((L + 2 delta)^3 - L^3), surface-like
            (~ 6 delta rho^(1/3) n^(2/3)) while L >> delta; k, the ghosts counted over this
            shell's spheres, calibrated on the measured regions (clipped to the bed);
          - 128 bytes a ghost per step (its position, velocity, angular velocity, orientation,
            angular momentum), in m = min(P - 1, 26) messages (a cube's neighbours);
          - dup(n): the contacts computed twice (across a region's faces) over the contacts of
            the region, ~ surface over volume: the contacts with a ghost counted per unit area of
            cut, times 6 L^2, over z n (z contacts per sphere), a duplicated contact costing c / z;
          - the skin check's reduction, 2 log2(P) latencies; the ghost update is not overlapped
            with the contacts (it follows the integration); the migrations and ghost rebuilds of
            re-detections are left out (a small share of the steps of a dense bed); every region
            is taken as a cube among cubes (six faces cut), which overstates the cuts at few processes;
          - I: the silo's imbalance with rebalancing, the slowest process setting the step.
          alpha (latency) and beta (bandwidth) are parameters: 1.5 us and 10 GB/s by default
          (an InfiniBand-class network). Strong scaling (N fixed, n = N / P): efficiency
          c N / (P t(P)); weak (n fixed): c n / t(P).
Checked:  dem.mpi.scaling-model: the projected strong-scaling efficiency of 10 million spheres at
          1024 processes, >= 0.5; .imbalance: the silo's imbalance with rebalancing, <= 1.1 (the
          details hold it without rebalancing, the rebalances, each process's spheres at the end).
          The details hold k and how far a process's ghosts stray from k times its shell's spheres
          (the bed is a lattice: one or two of its planes lie within the ghost distance of a cut,
          depending on where the cut falls, so a process's count strays by up to half; k averages
          over the cuts of 2, 3 and 4 processes).
Produces: the records and the chart dem.mpi.scaling-model.png (the silo's imbalance at each
          re-detection with and without rebalancing; the projected strong and weak efficiencies).
"""
import importlib.util
import math
import tempfile
from pathlib import Path

import numpy as np

from talus import results
from talus.bench import run_talus_script

HERE = Path(__file__).resolve().parent
BED = HERE.parent / "scenes" / "mpi_bed.py"
SILO = HERE.parent / "scenes" / "silo_discharge.py"
GHOST_BYTES = 128          # MpiDomain's ghost update: 16 doubles a ghost
NEIGHBOURS = 26            # of a cube among cubes
PROCESSES = [2 ** k for k in range(11)]


def write_packing(path: Path, spheres: int) -> int:
    """Case 11's lattice of about `spheres` spheres (its write_packing)."""
    spec = importlib.util.spec_from_file_location("bench_dense", HERE / "11_bench_dense.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    return bench.write_packing(path, spheres)


def clipped(box, bounds):
    """The box (lower, upper corners) inside `bounds`, the lower and upper corners."""
    lo = np.maximum(np.asarray(box[0]), bounds[0])
    hi = np.minimum(np.asarray(box[1]), bounds[1])
    return lo, np.maximum(hi, lo)


def shell_and_cut(box, bounds, delta):
    """For a region: the volume within `delta` of it (a box grown by delta, inside the bed) less
    its own, and the area of its faces inside the bed (where it meets other regions)."""
    lo, hi = clipped(box, bounds)
    glo, ghi = clipped((lo - delta, hi + delta), bounds)
    shell = np.prod(ghi - glo) - np.prod(hi - lo)
    cut = 0.0
    for axis in range(3):
        face = np.prod(np.delete(hi - lo, axis))
        cut += face * ((lo[axis] > bounds[0][axis]) + (hi[axis] < bounds[1][axis]))
    return shell, cut


def measure_bed(folder: Path, spheres: int, steps: int) -> dict:
    """The bed in one process and at 2, 3, 4 processes: the calibration of the model."""
    packing = folder / "bed.txt"
    count = write_packing(packing, spheres)
    out = folder / "bed.json"
    serial = run_talus_script([BED, packing, steps, out], out)
    positions = np.asarray(serial["positions"])
    radius = float(packing.read_text().splitlines()[1].split()[3])
    bounds = (positions.min(axis=0), positions.max(axis=0))      # where the centres are
    rho = count / np.prod(bounds[1] - bounds[0])
    c = serial["processes"][0]["cpu_seconds"] / (count * steps)
    runs = {}
    for p in (2, 3, 4):
        r = run_talus_script([BED, packing, steps, out], out, processes=p)
        delta = r["balance"]["ghost_distance"]
        per = []
        for process, halo, region, timed in zip(r["balance"]["processes"], r["traffic"], r["balance"]["regions"],
                                                r["processes"]):
            shell, cut = shell_and_cut(region, bounds, delta)
            per.append({"spheres": process["spheres"], "ghosts": process["ghosts"], "contacts": process["contacts"],
                        "ghost_contacts": process["ghost_contacts"], "shell_spheres": rho * shell, "cut_area": cut,
                        "bytes_per_step": halo["update_bytes"] / max(halo["updates"], 1),
                        "messages_per_step": halo["update_messages"] / max(halo["updates"], 1),
                        "cpu_seconds": timed["cpu_seconds"],
                        "wait_cpu_seconds": halo["wait_cpu_seconds"]})
        runs[p] = per
        print(f"bed at {p} processes: " + "; ".join(
            f"{q['spheres']} spheres, {q['ghosts']} ghosts ({q['shell_spheres']:.0f} in the shell), "
            f"{q['bytes_per_step']:.0f} B in {q['messages_per_step']:.2f} messages a step" for q in per))
    every = [q for per in runs.values() for q in per]
    k = sum(q["ghosts"] for q in every) / sum(q["shell_spheres"] for q in every)
    per_area = sum(q["ghost_contacts"] for q in every) / sum(q["cut_area"] for q in every)
    z = sum(q["contacts"] - q["ghost_contacts"] / 2 for q in every) / sum(q["spheres"] for q in every)
    spread = max(abs(q["ghosts"] / (k * q["shell_spheres"]) - 1) for q in every)
    return {"spheres": count, "steps": steps, "radius": radius, "rho": rho, "delta": delta, "c": c, "k": k,
            "ghost_contacts_per_area": per_area, "contacts_per_sphere": z, "ghost_spread": spread,
            "serial_cpu_seconds": serial["processes"][0]["cpu_seconds"],
            "runs": {str(p): per for p, per in runs.items()}}


def measure_silo(folder: Path, spheres: int, steps: int) -> dict:
    """The tall silo at 4 processes without and with rebalancing."""
    out = {}
    for label, threshold in (("without", "none"), ("with", "1.1")):
        path = folder / f"silo-{label}.json"
        r = run_talus_script([SILO, spheres, steps, path, "side=6", f"rebalance={threshold}"], path, processes=4)
        b = r["balance"]
        out[label] = {"imbalance": b["imbalance"], "rebalances": b["rebalances"],
                      "intervals": b["intervals"], "left": r["left"][-1][1],
                      "spheres": [p["spheres"] for p in b["processes"]],
                      "compute_seconds": [p["compute_seconds"] for p in b["processes"]]}
        print(f"silo {label} rebalancing: imbalance {b['imbalance']:.3f}, {b['rebalances']} rebalances, "
              f"spheres per process at the end {out[label]['spheres']}")
    return out


def step_seconds(model: dict, n: float, processes: int, imbalance: float, latency: float,
                 bandwidth: float) -> dict:
    """The model's seconds of one step of a process holding n spheres among `processes`."""
    c, rho, delta = model["c"], model["rho"], model["delta"]
    if processes == 1:
        return {"compute": c * n, "halo": 0.0, "reduction": 0.0}
    side = (n / rho) ** (1 / 3)
    ghosts = model["k"] * rho * ((side + 2 * delta) ** 3 - side ** 3)
    duplicated = model["ghost_contacts_per_area"] * 6 * side ** 2 / (model["contacts_per_sphere"] * n)
    messages = min(processes - 1, NEIGHBOURS)
    return {"compute": imbalance * c * n * (1 + duplicated),
            "halo": messages * latency + GHOST_BYTES * ghosts / bandwidth,
            "reduction": 2 * math.log2(processes) * latency}


def efficiencies(model, imbalance, latency, bandwidth, total=None, each=None):
    """Strong (`total` spheres) or weak (`each` per process) efficiency at every count of PROCESSES."""
    out = []
    for p in PROCESSES:
        n = total / p if total else each
        t = sum(step_seconds(model, n, p, imbalance, latency, bandwidth).values())
        out.append(model["c"] * n / t)
    return out


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--latency", type=float, default=1.5e-6, help="network latency, seconds (1.5e-6)")
    parser.add_argument("--bandwidth", type=float, default=10e9, help="network bandwidth, bytes/s (10e9)")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = results.Case("dem.mpi.scaling-model", quick=args.quick, folder=args.results)
    bed_spheres, bed_steps = (20_000, 50) if args.quick else (200_000, 100)
    silo_spheres, silo_steps = (1000, 4000) if args.quick else (1500, 8000)
    with tempfile.TemporaryDirectory() as tmp:
        model = measure_bed(Path(tmp), bed_spheres, bed_steps)
        silo = measure_silo(Path(tmp), silo_spheres, silo_steps)
    imbalance = silo["with"]["imbalance"]
    strong = {total: efficiencies(model, imbalance, args.latency, args.bandwidth, total=total)
              for total in (200_000, 1_000_000, 10_000_000)}
    weak = {each: efficiencies(model, imbalance, args.latency, args.bandwidth, each=each)
            for each in (1_000, 10_000, 100_000)}
    at1024 = strong[10_000_000][-1]
    breakdown = step_seconds(model, 10_000_000 / 1024, 1024, imbalance, args.latency, args.bandwidth)
    print(f"c = {model['c']:.3g} s per sphere and step; k = {model['k']:.3f} (spread {model['ghost_spread']:.3f}); "
          f"strong efficiency of 1e7 spheres at 1024 processes {at1024:.3f} ({breakdown})")
    assumptions = {"latency_seconds": args.latency, "bandwidth_bytes_per_second": args.bandwidth,
                   "ghost_bytes": GHOST_BYTES, "neighbours": NEIGHBOURS,
                   "ghosts": "k rho ((L + 2 delta)^3 - L^3), L = (n / rho)^(1/3): a cube region among cubes",
                   "duplicated_contacts": "ghost contacts per unit cut area x 6 L^2 over z n, each costing c / z",
                   "reduction": "2 log2(P) latencies a step", "overlap": "none",
                   "re-detections": "left out", "imbalance": imbalance}
    model_out = {k: v for k, v in model.items() if k != "runs"}
    common = {"assumptions": assumptions, "model": model_out, "bed_runs": model["runs"],
              "processes": PROCESSES}
    case.record("projected strong-scaling efficiency of 10 million spheres at 1024 processes", at1024,
                "the model calibrated on the bed at 1 to 4 processes (assumptions in the details)", 0.5,
                comparison=">=", strong={str(k): v for k, v in strong.items()},
                weak={str(k): v for k, v in weak.items()}, step_at_1024=breakdown, **common)
    case.record("imbalance of the emptying silo with rebalancing (slowest process's compute seconds over the mean, "
                "over the run, 4 processes)", imbalance, "a perfectly balanced split (1)", 1.1,
                suffix="imbalance", without=silo["without"]["imbalance"], rebalances=silo["with"]["rebalances"],
                spheres_at_end={k: v["spheres"] for k, v in silo.items()},
                compute_seconds={k: v["compute_seconds"] for k, v in silo.items()},
                spheres=silo_spheres, steps=silo_steps, left=silo["with"]["left"])

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for label, style in (("without", "C3"), ("with", "C0")):
        intervals = np.asarray([(i[0], i[2]) for i in silo[label]["intervals"]])
        axes[0].plot(intervals[:, 0], intervals[:, 1], ".", color=style, ms=3,
                     label=f"{label} rebalancing: {silo[label]['imbalance']:.2f} over the run")
    axes[0].axhline(1.1, color="grey", ls="--", lw=0.8, label="threshold 1.1")
    axes[0].set(xlabel="step", ylabel="slowest process's compute time / mean",
                title=f"silo emptying, {silo_spheres} spheres, 4 processes")
    axes[0].legend(fontsize=8)
    for ax, curves, what in ((axes[1], strong, "strong: {:.0e} spheres"), (axes[2], weak, "weak: {:.0e} per process")):
        for size, values in curves.items():
            ax.semilogx(PROCESSES, values, "o-", ms=3, base=2, label=what.format(size))
        ax.set(xlabel="processes", ylabel="projected efficiency", ylim=(0, 1.05))
        ax.legend(fontsize=8)
    axes[1].set_title(f"latency {args.latency * 1e6:g} us, bandwidth {args.bandwidth / 1e9:g} GB/s", fontsize=10)
    axes[2].set_title(f"c = {model['c'] * 1e9:.0f} ns per sphere and step (measured)", fontsize=10)
    fig.tight_layout()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
