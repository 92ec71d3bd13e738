"""CFD-DEM case: cost of one coupling exchange against the particle count and the number of
fluid ranks (issue #6: O(N/P) data per rank, a bounded number of messages).

Run:      build/bin/talus run cases/cfd_exchange_cost.py [--quick] [--results DIR]
          [--solver talusPointForceFoam|talusVolumeAveragedFoam]
Set-up:   N spheres (r = 0.1 mm, rho_p = 2500) at random positions (seed 1) in the closed box
          of cases/cfd_settling_sphere/ (45 x 45 x 90 mm) meshed 10 x 10 x 20, decomposed along
          z for 2 ranks; one DEM step per fluid step (no contacts: the DEM costs nothing);
          2 warm-up exchanges then 10 measured. N = 1000, 10000 (quick) and 100000 (full).
Measured: per exchange the messages (DEM <-> fluid and between fluid ranks), the doubles the
          DEM process sends and receives, the largest number of particles a fluid rank got, and
          the wall time the DEM waits for the forces (median; it includes what is left of the
          fluid's previous step). Checked: the messages do not depend on N (3 per fluid rank
          plus at most 2 between the 2 ranks per reduction) and with 2 ranks no rank gets more
          than 60 % of the particles (O(N/P)).
Produces: record cfd.exchange_cost; chart cfd.exchange_cost.png.
"""
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from talus import results
from talus.coupling import FoamCoupling
from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere

HERE = Path(__file__).resolve().parent
CASE = HERE / "cfd_settling_sphere"


def prepare(procs: int) -> Path:
    work = Path(tempfile.mkdtemp(prefix="talus_cfd_exchange_"))
    shutil.copytree(CASE, work, dirs_exist_ok=True)
    mesh = work / "system" / "blockMeshDict"
    mesh.write_text(mesh.read_text().replace("(9 9 18)", "(10 10 20)"))
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    for tool in ["blockMesh"] + (["decomposePar"] if procs > 1 else []):
        subprocess.run([tool, "-case", str(work)], check=True, capture_output=True, env=env)
    return work


def measure(n: int, procs: int, solver: str):
    work = prepare(procs)
    rng = np.random.default_rng(1)
    x = rng.uniform((-0.022, -0.022, 0.001), (0.022, 0.022, 0.089), size=(n, 3))
    s = Scene()
    s.materials.append(FrictMat(density=2500.0))
    s.bodies.append([sphere(tuple(p), 1e-4) for p in x])
    s.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.0)]
    s.dt = 2e-5
    coupling = FoamCoupling(s, work, rhoFluid=1000.0, nu=1e-3, gravity=(0, 0, -9.81), nProcs=procs,
                            solver=solver).start()
    s.run(2 * coupling.substeps, True)
    seconds, messages, doubles = [], [], []
    for _ in range(10):
        s.run(coupling.substeps, True)
        seconds.append(coupling.link.lastExchangeSeconds)
        messages.append(coupling.link.lastMessages)
        doubles.append(coupling.link.lastDemDoubles)
    boxes = np.array(coupling.link.boxes).reshape(-1, 7)
    per_rank = []
    for b in boxes:
        m = b[6]
        inside = np.all((x >= b[:3] - m) & (x <= b[3:6] + m), axis=1)
        per_rank.append(int(inside.sum()))
    coupling.stop()
    shutil.rmtree(work, ignore_errors=True)
    return dict(n=n, procs=procs, seconds=float(np.median(seconds)), messages=int(max(messages)),
                dem_doubles=int(np.median(doubles)), particles_per_rank=per_rank)


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--solver", default="talusPointForceFoam")
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = results.Case("cfd.exchange_cost" + ("" if args.solver == "talusPointForceFoam" else "_va"),
                        quick=args.quick, folder=args.results)
    counts = [1000, 10000] if args.quick else [1000, 10000, 100000]
    rows = []
    for procs in (1, 2):
        for n in counts:
            row = measure(n, procs, args.solver)
            rows.append(row)
            print(f"{args.solver}, {procs} fluid rank(s), {n} particles: {row['seconds'] * 1e3:.2f} ms per exchange, "
                  f"{row['messages']} messages, {row['dem_doubles']} doubles through the DEM, particles per rank "
                  f"{row['particles_per_rank']}")
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for procs in (1, 2):
        sel = [r for r in rows if r["procs"] == procs]
        ax.loglog([r["n"] for r in sel], [r["seconds"] * 1e3 for r in sel], "o-", label=f"{procs} fluid rank(s)")
    ax.set_xlabel("particles")
    ax.set_ylabel("wall time per exchange [ms]")
    ax.set_title(f"Coupling exchange cost ({args.solver})")
    ax.legend(fontsize=7)
    two = [r for r in rows if r["procs"] == 2]
    share = max(max(r["particles_per_rank"]) / r["n"] for r in two)
    bounded = len({r["messages"] for r in two}) == 1 and len({r["messages"] for r in rows if r["procs"] == 1}) == 1
    case.record("largest share of the particles sent to one of 2 fluid ranks", share,
                "O(N/P): at most 0.6 with 2 ranks", 0.6, messages_independent_of_n=bounded, rows=rows)
    case.save_chart(fig)
    if not bounded:
        raise SystemExit("the number of messages per exchange depends on the particle count")


if __name__ == "__main__":
    main()
