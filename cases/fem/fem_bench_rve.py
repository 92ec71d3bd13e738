"""FEM x DEM benchmark: Gauss-point calls per second, Talus against a Yade-based call.

Run:      build/bin/talus run cases/fem/fem_bench_rve.py [--quick] [--results DIR]
Set-up:   one RVE (talus.fem.prepareRVE, rMean 0.1, cube of edge 1.5 (quick) or 2.5, -100 kPa),
          exported (talus.fem.exportRVE) and built identically in both programs by
          cases/yade/fem_rve_call.py: `points` Gauss points, each call deforming every RVE by a small
          gradient over nSteps = 100 DEM steps, reading stress and tangent, and rolling back (a
          Newton iteration). Yade restores the scene with O.loadTmp and runs it (the seed's way);
          Talus keeps the committed state in memory and calls all points in C++. One thread each
          (OMP_NUM_THREADS=1, yade -j1); then Talus over 2 MPI ranks.
Checked:  fem.bench.rve-calls: Gauss-point calls per second, Talus / Yade (target >= 5).
          fem.bench.mpi-2: calls per second on 2 MPI ranks / on 1 (>= 1.3; the machine has 2
          cores shared with other jobs, so this is indicative).
Produces: the records and chart fem.bench.png (calls per second: Yade, Talus 1 rank, 2 ranks; MPI
          scaling 1 -> 2 ranks against ideal).
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from talus import results
from talus import twin

SCENARIO = Path(__file__).resolve().parents[1] / "yade" / "fem_rve_call.py"


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from talus.fem import exportRVE, prepareRVE, rve_scene
    case = results.Case("fem.bench", quick=args.quick, folder=args.results)
    size, points, calls = (1.5, 4, 3) if args.quick else (2.5, 8, 5)
    work = Path(tempfile.mkdtemp(prefix="fem_bench_"))
    prepareRVE(work / "rve.h5", size=size, rMean=0.1, sigma=-1e5, young=1e8)
    exportRVE(work / "rve.h5", work / "packing.json")
    params = {"packing": str(work / "packing.json"), "points": points, "calls": calls, "nSteps": 100,
              "rveSceneDir": rve_scene.FOLDER}
    ours = twin.run(SCENARIO, params, "talus")
    print(f"Talus: {ours['calls_per_s']:.1f} Gauss-point calls/s ({ours['spheres']} spheres)", flush=True)
    import talus
    env = {**os.environ, "TALUS_SCENARIO": json.dumps(params), "OMP_NUM_THREADS": "1",
           "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "PYTHONPATH": str(Path(talus.__file__).resolve().parent.parent)}
    done = subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2", sys.executable,
                           str(SCENARIO)], capture_output=True, text=True, env=env, cwd=SCENARIO.parent, timeout=600)
    lines = [l for l in done.stdout.splitlines() if l.startswith("RESULT ")]
    if done.returncode != 0 or not lines:
        raise RuntimeError("mpirun failed:\n" + done.stdout[-2000:] + done.stderr[-2000:])
    two = json.loads(lines[-1][len("RESULT "):])
    print(f"Talus, 2 ranks: {two['calls_per_s']:.1f} calls/s", flush=True)
    bars = {"Talus, 1 rank": ours["calls_per_s"], "Talus, 2 ranks": two["calls_per_s"]}
    if twin.yade_available():
        theirs = twin.run(SCENARIO, params, "yade")
        bars["Yade (loadTmp + run)"] = theirs["calls_per_s"]
        ratio = ours["calls_per_s"] / theirs["calls_per_s"]
        print(f"Yade: {theirs['calls_per_s']:.1f} calls/s; ratio {ratio:.2f}")
        case.record("Gauss-point calls per second, Talus / Yade (same RVE, 100 DEM steps per call, one thread)",
                    ratio, "Yade 2023.02a, O.loadTmp + O.run + getStressAndTangent per point", 5.0,
                    comparison=">=", suffix="rve-calls", peer="yade 2023.02a", ours=ours["calls_per_s"],
                    theirs=theirs["calls_per_s"], unit="Gauss-point calls/s", spheres=ours["spheres"], points=points)
    case.record("Gauss-point calls per second on 2 MPI ranks / on 1", two["calls_per_s"] / ours["calls_per_s"],
                "the same calls on one rank", 1.3, comparison=">=", suffix="mpi-2", one_rank=ours["calls_per_s"],
                two_ranks=two["calls_per_s"])
    fig, (ax, scaling) = plt.subplots(1, 2, figsize=(11, 3.5))
    ax.bar(list(bars), list(bars.values()), color=["C0", "C1", "C7"][:len(bars)])
    ax.set_ylabel("Gauss-point calls per second")
    ax.set_title(f"{ours['spheres']}-sphere RVE, 100 DEM steps per call")
    ranks = [1, 2]
    scaling.plot(ranks, [ours["calls_per_s"], two["calls_per_s"]], "o-", label="Talus (mpirun -n)")
    scaling.plot(ranks, [ours["calls_per_s"] * r for r in ranks], "k:", label="ideal")
    scaling.set_xticks(ranks)
    scaling.set_xlabel("MPI ranks (one thread each)")
    scaling.set_ylabel("Gauss-point calls per second")
    scaling.set_title(f"MPI scaling, {points} Gauss points (2-core machine, shared)")
    scaling.legend()
    case.save_chart(fig)


if __name__ == "__main__":
    main()
