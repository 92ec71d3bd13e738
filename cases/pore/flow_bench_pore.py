"""Pore-scale flow benchmark: Talus's FlowEngine against Yade's on the same packings, in the same
invocation, on one thread each and on two threads each; a remesh with the solve after it, a solve
alone; and a 1 000 000-sphere packing remeshed and solved with its memory (full mode).

Run:      build/bin/talus run cases/pore/flow_bench_pore.py [--quick] [--results DIR]
Set-up:   loose seeded clouds (makeCloud, rMean 0.035, rRelFuzz 0.3, side (n / 1000)^(1/3)) of
          10 000, 30 000 and 100 000 spheres (full mode: also 200 000), written to a file that both
          programs read; pressure 1 on ymin, 0 on ymax, box of the spheres' extremes. Each side runs
          in its own process (this script again for Talus, cases/yade/pore_flow.py for Yade) with
          OMP_NUM_THREADS and OMP_THREAD_LIMIT at 1, then at 2 (Yade with -j1, -j2: CHOLMOD's
          supernodal factorisation opens four-thread OpenMP teams whatever OMP_NUM_THREADS says;
          only the thread limit holds Yade's to the count; Talus's PressureSolver does it itself).
          - Yade 2023.02a: FlowEngine(useSolver=3) as the only engine; "remesh" = the first O.step()
            (triangulation, volumes, conductances, CHOLMOD analysis and factorisation, solve,
            forces), the median over fresh scenes; "solve" = the median of the later steps on the
            same mesh (volume update, solve with the kept factor, forces).
          - Talus: "remesh" = triangulate + solve + vertexForces, the median over fresh engines,
            each side after one untimed warm-up below 100 000 spheres; "solve" = moveVertices
            (each sphere moved by up to 1e-4 of its radius, so that the multigrid does not start
            from the answer) + solve + vertexForces; with CHOLMOD (useSolver=3, the default), with
            the aggregation multigrid (useSolver=4) and with hypre's BoomerAMG (useSolver=5; its
            process's one-time MPI initialisation done on a small network before the timing).
          - "remesh + solve" = the remesh and the solve of the step after it: the figure the
            issue's target is on (Yade factorises lazily in the step after a remesh of a running
            scene: both steps hold one factorisation).
          - 1 000 000 spheres (full mode): a jittered cubic lattice (spacing 0.1, radius 0.035 +-
            30 %), Talus with BoomerAMG (a Cholesky factor of its 6 million unknowns would take
            tens of GB), one remesh and one solve on one thread, with the process's peak memory.
Checked:  nothing is timed as a test; records flow.bench.remesh-<n>[-2t] (Yade's remesh + solve
          over Talus's with CHOLMOD; the issue's target >= 4; 1 thread on process CPU time, which
          the load of a shared machine disturbs least, 2 threads on wall time), remesh-mg-<n>[-2t]
          (the same with the multigrid), each with the load average and, for two threads, the CPU-time
          ratio (ratio_cpu), remesh-amg-<n>[-2t] (the same with BoomerAMG), solve-<n>[-2t] (a
          solve; target >= 1), flux (the same network as Yade's, the spheres inserted in Yade's
          order: the inlet flux within 1e-6 of Yade's at every size; the multigrids' from
          CHOLMOD's are kept in the record), symbolic-reuse (analysis share of a
          factorisation at 10 000 spheres) and, full mode, million (seconds and peak GB).
          Without yade the Yade records are skipped.
Produces: the records and flow.bench.png (remesh + solve against spheres, both programs, both
          thread counts; the dotted line is the target, Yade / 4).
"""
import json
import os
import resource
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results
from talus import twin
from talus.dem.packing.pack import SpherePack

YADE_SCRIPT = Path(__file__).resolve().parents[1] / "yade" / "pore_flow.py"
SOLVES = 3
# remeshes timed per size (their median is the record): fewer where one takes seconds
REMESHES = {10000: 3, 30000: 3, 100000: 1, 200000: 1, 1000000: 1}
WARM_UP_BELOW = 100000


def cloud(num: int, seed: int) -> SpherePack:
    side = (num / 1000) ** (1 / 3)
    sp = SpherePack()
    # rMean small enough for makeCloud to place all `num` spheres (with 0.045 it stopped at about
    # half of them)
    sp.makeCloud((0, 0, 0), (side, side, side), rMean=0.035, rRelFuzz=0.3, num=num, seed=seed)
    if len(sp) != num:
        raise SystemExit(f"flow_bench_pore: makeCloud placed {len(sp)} of {num} spheres")
    return sp


def lattice(num: int, seed: int) -> np.ndarray:
    """x y z r of `num` spheres on a jittered cubic lattice (makeCloud would take hours for a
    million): spacing 0.1, radii 0.035 +- 30 %, centres moved by up to 0.004 (no overlaps)."""
    side = round(num ** (1 / 3))
    rng = np.random.default_rng(seed)
    grid = np.stack(np.meshgrid(*[np.arange(side)] * 3, indexing="ij"), -1).reshape(-1, 3) * 0.1
    centres = grid + rng.uniform(-0.004, 0.004, grid.shape)
    return np.column_stack([centres, 0.035 * rng.uniform(0.7, 1.3, len(grid))])


class Timer:
    """Wall and process CPU time of a block."""

    def __enter__(self):
        self.wall, self.cpu = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc):
        self.wall, self.cpu = time.perf_counter() - self.wall, time.process_time() - self.cpu


def talus_side(params: dict) -> dict:
    """One size, one solver, the threads of this process: remeshes, solves, flux."""
    from talus.flow import FlowEngine

    data = np.loadtxt(params["packing"])
    centers, radii = data[:, :3].copy(), data[:, 3].copy()
    if params["useSolver"] == 5 and not params["warmup"]:
        # hypre initialises MPI once per process (about half a second): not a remesh's cost
        small = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], useSolver=5)
        small.triangulate(centers[:500], radii[:500])
        small.solve()
    remesh, remesh_cpu = [], []
    for k in range(params["remeshes"] + (1 if params["warmup"] else 0)):
        flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0],
                          useSolver=params["useSolver"])
        with Timer() as t:
            flow.triangulate(centers, radii)
            flow.solve()
            flow._flow.vertexForces()
        if k or not params["warmup"]:
            remesh.append(t.wall)
            remesh_cpu.append(t.cpu)
    flux = flow.getBoundaryFlux(2)
    stats = flow.solverStats()
    rng = np.random.default_rng(1)
    solve, solve_cpu = [], []
    for _ in range(params["solves"]):
        moved = centers + rng.uniform(-1e-4, 1e-4, centers.shape) * radii[:, None]
        with Timer() as t:
            flow.moveVertices(moved, 1e-6)
            flow.solve()
            flow._flow.vertexForces()
        solve.append(t.wall)
        solve_cpu.append(t.cpu)
    out = dict(remesh_s=remesh, remesh_cpu_s=remesh_cpu, solve_s=solve, solve_cpu_s=solve_cpu, flux=flux,
               nCells=flow.nCells(), peak_rss_gb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2 ** 20,
               **stats)
    if params.get("compressible"):
        # compressible: same pattern, new values every step -> numeric factorisation only
        flow.fluidBulkModulus = 1e3
        flow.setTimeStep(1e-3)
        flow.solve()
        out["after"] = flow.solverStats()
    return out


def median(values) -> float:
    return float(np.median(values))


# the row key of each Talus solver: its useSolver, record suffix and name
SOLVERS = {"talus": (3, "remesh", "CHOLMOD"), "mg": (4, "remesh-mg", "multigrid"),
           "amg": (5, "remesh-amg", "BoomerAMG")}
CLOCK = {1: ("remesh_cpu_s", "solve_cpu_s", "CPU time"), 2: ("remesh_s", "solve_s", "wall time")}


def record_row(case, row):
    """The records of one size and thread count, written as soon as it is measured."""
    remesh_key, solve_key, what = CLOCK[row["threads"]]
    tag = f"{row['spheres']}" + ("-2t" if row["threads"] == 2 else "")
    for key in SOLVERS:
        row[key]["pair"] = median(row[key][remesh_key]) + median(row[key][solve_key])
    if "yade" not in row:
        return
    y = row["yade"]
    y["pair"] = median(y[remesh_key]) + median(y[solve_key])
    label = f"{row['spheres']} spheres, {row['threads']} thread{'s' if row['threads'] > 1 else ''}, {what}"
    peer = f"Yade 2023.02a FlowEngine -j{row['threads']}, same packing, same invocation"
    # the machine's load when the size was measured; on two threads the CPU-time pair beside the
    # wall-time one (a loaded machine's wall time measures the load more than the programs)
    load = os.getloadavg()[0]
    cpu_pair = {k: median(row[k]["remesh_cpu_s"]) + median(row[k]["solve_cpu_s"]) for k in (*SOLVERS, "yade")}
    for key, (_, suffix, solver) in SOLVERS.items():
        ours = row[key]
        case.record(f"speed ratio Yade / Talus ({solver}), remesh + the solve after it ({label})",
                    y["pair"] / ours["pair"], peer, 4.0, suffix=f"{suffix}-{tag}", comparison=">=",
                    peer=f"yade 2023.02a -j{row['threads']}", ratio=y["pair"] / ours["pair"],
                    ours=ours["pair"], theirs=y["pair"], unit="s", ours_remesh=median(ours[remesh_key]),
                    ours_solve=median(ours[solve_key]), theirs_remesh=median(y[remesh_key]),
                    theirs_solve=median(y[solve_key]), nCells=ours["nCells"], ours_samples=ours[remesh_key],
                    theirs_samples=y[remesh_key], flux_rel_diff=abs(ours["flux"] - y["flux"]) / abs(y["flux"]),
                    load_average=load, ours_cpu=cpu_pair[key], theirs_cpu=cpu_pair["yade"],
                    ratio_cpu=cpu_pair["yade"] / cpu_pair[key])
    ours, theirs = median(row["talus"][solve_key]), median(y[solve_key])
    case.record(f"speed ratio Yade / Talus (CHOLMOD), a solve ({label})", theirs / ours, peer, 1.0,
                suffix=f"solve-{tag}", comparison=">=", peer=f"yade 2023.02a -j{row['threads']}",
                ratio=theirs / ours, ours=ours, theirs=theirs, unit="s", multigrid=median(row["mg"][solve_key]))
    print(f"{label}: remesh + solve Talus {row['talus']['pair']:.3f} s (multigrid {row['mg']['pair']:.3f}, "
          f"BoomerAMG {row['amg']['pair']:.3f}), Yade {y['pair']:.3f} s: ratio {y['pair'] / row['talus']['pair']:.2f} "
          f"(multigrid {y['pair'] / row['mg']['pair']:.2f}, BoomerAMG {y['pair'] / row['amg']['pair']:.2f}); "
          f"solve {ours * 1e3:.1f} ms (multigrid {median(row['mg'][solve_key]) * 1e3:.1f}, BoomerAMG "
          f"{median(row['amg'][solve_key]) * 1e3:.1f}) against {theirs * 1e3:.1f} ms; CPU time: Talus "
          f"{cpu_pair['talus']:.3f} s (multigrid {cpu_pair['mg']:.3f}, BoomerAMG {cpu_pair['amg']:.3f}), "
          f"Yade {cpu_pair['yade']:.3f} s; load {load:.1f}", flush=True)


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("flow.bench", quick=args.quick, folder=args.results)
    sizes = [10000, 30000, 100000] if args.quick else [10000, 30000, 100000, 200000]
    # Threads that wait for work sleep instead of spinning: a team's spinning threads took the
    # cores from the others on a shared 2-core machine (both programs, the same setting)
    os.environ["OMP_WAIT_POLICY"] = "passive"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        paths = {}
        for n in sizes:
            paths[n] = Path(tmp) / f"cloud-{n}.txt"
            cloud(n, seed=n).save(str(paths[n]))
        for threads in (1, 2):
            os.environ["OMP_THREAD_LIMIT"] = str(threads)
            for n in sizes:
                common = dict(packing=str(paths[n]), remeshes=REMESHES[n], solves=SOLVES, warmup=n < WARM_UP_BELOW)
                row = dict(spheres=n, threads=threads)
                for key, (solver, _, _) in SOLVERS.items():
                    row[key] = twin.run(__file__, dict(common, useSolver=solver,
                                                       compressible=threads == 1 and n == sizes[0] and solver == 3),
                                        "talus", threads=threads)
                if twin.yade_available():
                    y = twin.run(YADE_SCRIPT, {"packings": [str(paths[n])], "axis": 1, "dp": 1.0, "solves": SOLVES,
                                               "remeshes": REMESHES[n]}, "yade", threads=threads)[0]
                    y["flux"] = y["boundaryFlux"][2]
                    row["yade"] = y
                rows.append(row)
                record_row(case, row)
                if row is rows[0]:
                    first = row["talus"]
                    share = first["analyseSeconds"] / (first["analyseSeconds"] + first["factorizeSeconds"])
                    case.record(f"share of CHOLMOD's symbolic analysis in analysis + factorisation, {n} spheres "
                                "(saved on every refactorisation of an unchanged pattern)", share,
                                "Talus, compressible step with the analysis kept", 0.0, suffix="symbolic-reuse",
                                comparison=">=", analyses_after=first["after"]["analyses"])
        if not args.quick:
            path = Path(tmp) / "lattice-1000000.txt"
            np.savetxt(path, lattice(1000000, seed=1))
            os.environ["OMP_THREAD_LIMIT"] = "1"
            million = twin.run(__file__, dict(packing=str(path), remeshes=1, solves=1, warmup=False, useSolver=5),
                               "talus", threads=1)
            case.record("1 000 000 spheres remeshed and solved (BoomerAMG, 1 thread): remesh + solve, s wall",
                        million["remesh_s"][0] + million["solve_s"][0], "Talus alone (a factor would not fit)", 0.0,
                        suffix="million", comparison=">=", peak_rss_gb=million["peak_rss_gb"], nCells=million["nCells"],
                        remesh_s=million["remesh_s"][0], solve_s=million["solve_s"][0],
                        remesh_cpu_s=million["remesh_cpu_s"][0], solve_cpu_s=million["solve_cpu_s"][0],
                        iterations=million["multigridIterations"], load_average=os.getloadavg()[0])
            print(f"1 000 000 spheres: {million['nCells']} pores, remesh {million['remesh_s'][0]:.1f} s wall "
                  f"({million['remesh_cpu_s'][0]:.1f} s CPU), solve {million['solve_s'][0]:.1f} s wall "
                  f"({million['solve_cpu_s'][0]:.1f} s CPU), peak memory {million['peak_rss_gb']:.1f} GB", flush=True)

    peered = [r for r in rows if "yade" in r]
    if peered:
        worst = max(abs(r["talus"]["flux"] - r["yade"]["flux"]) / abs(r["yade"]["flux"]) for r in peered)
        worst_mg, worst_amg = (max(abs(r[key]["flux"] - r["talus"]["flux"]) / abs(r["talus"]["flux"]) for r in rows)
                               for key in ("mg", "amg"))
        case.record("worst relative difference of the inlet flux from Yade's (CHOLMOD)", worst,
                    "Yade 2023.02a FlowEngine, same packings", 1e-6, suffix="flux", multigrid_from_cholmod=worst_mg,
                    boomeramg_from_cholmod=worst_amg, spheres=[r["spheres"] for r in peered])

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, threads in zip(axes, (1, 2)):
        mine = [r for r in rows if r["threads"] == threads]
        n = [r["spheres"] for r in mine]
        ax.loglog(n, [r["talus"]["pair"] for r in mine], "o-", color="C0", label="Talus, CHOLMOD")
        ax.loglog(n, [r["mg"]["pair"] for r in mine], "s-", color="C2", label="Talus, multigrid")
        ax.loglog(n, [r["amg"]["pair"] for r in mine], "^-", color="C3", label="Talus, BoomerAMG")
        if mine and all("yade" in r for r in mine):
            ax.loglog(n, [r["yade"]["pair"] for r in mine], "o--", color="C1", label="Yade")
            ax.loglog(n, [r["yade"]["pair"] / 4 for r in mine], ":", color="C1", label="Yade / 4 (target)")
        ax.set_xlabel("spheres")
        ax.set_title(f"{threads} thread{'s' if threads > 1 else ''} ({CLOCK[threads][2]})")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("remesh + the solve after it (s)")
    case.save_chart(fig)


if __name__ == "__main__":
    if twin.ENV in os.environ:
        print("RESULT " + json.dumps(talus_side(json.loads(os.environ[twin.ENV]))))
    else:
        main()
