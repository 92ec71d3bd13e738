"""FEM x DEM: the same drained biaxial run driven by escript and by FEniCSx (issue #7).

Run:      build/bin/talus run cases/fem_escript_vs_fenicsx.py [--quick] [--results DIR]
Set-up:   a uniform 1 x 2 plane-strain sample, 2 x 4 bilinear quadrilaterals (2x2 Gauss points, one
          RVE each: talus.fem.prepareRVE, rMean 0.1, -100 kPa), bottom uy = 0 (ux = 0 at the
          bottom-left corner), top lowered to 1 % (quick: 4 steps) or 3 % (12 steps), 100 kPa on the
          lateral faces, contact-stiffness tangent, Newton tolerance 1e-6, 30 DEM steps per call.
          FEniCSx: talus.fem.fenicsx in this process; escript: cases/fem_escript_biaxial.py under
          run-escript (talus.fem.escript, LinearPDE with A = tangent, X = -stress).
Checked:  fem.escript-vs-fenicsx: largest relative difference of the mean axial stress over the
          Gauss points between the two drivers, over all steps (<= 1 %).
Produces: the record and chart fem.escript-vs-fenicsx.png (mean axial and lateral stress against
          axial strain, both drivers).
"""
import os
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from talus import results

P_CONF = 1e5
CLIENT = Path(__file__).resolve().with_name("fem_escript_biaxial.py")


def fenicsx(rve, nx, ny, strain, steps, nSteps, tol):
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, Traction
    W, H = 1.0, 2.0
    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.array([W, H])], [nx, ny],
                                 dmesh.CellType.quadrilateral)
    rves = MultiscaleRVEs(str(rve), numPoints=4 * nx * ny, nSteps=nSteps)
    dx, dy = W / nx / 2, H / ny / 2
    solver = MultiscaleSolver(
        msh, rves, tol=tol,
        dirichlet=[Dirichlet(lambda x: x[1] < dy, 1), Dirichlet(lambda x: (x[1] < dy) & (x[0] < dx), 0),
                   Dirichlet(lambda x: x[1] > x[1].max() - dy, 1, lambda t: -strain * H * t)],  # current top
        tractions=[Traction(lambda x: x[0] < dx, lambda t: (P_CONF, 0.0)),
                   Traction(lambda x: x[0] > W - dx, lambda t: (-P_CONF, 0.0))])
    rows = []
    for n in range(1, steps + 1):
        report = solver.step(n / steps)
        s = report.stress
        rows.append((strain * n / steps, s[:, 0, 0].mean(), s[:, 1, 1].mean(), report.iterations))
        print(f"FEniCSx step {n}: {rows[-1]}", flush=True)
    return np.array(rows)


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import talus
    from talus.fem import prepareRVE
    case = results.Case("fem.escript-vs-fenicsx", quick=args.quick, folder=args.results)
    nx, ny, nSteps, tol = 2, 4, 30, 1e-6
    strain, steps = (0.01, 4) if args.quick else (0.03, 12)
    rve = Path(tempfile.mkdtemp(prefix="fem_esc_")) / "rve.h5"
    prepareRVE(rve, size=1.2, rMean=0.1, sigma=-P_CONF, young=1e8)
    ours = fenicsx(rve, nx, ny, strain, steps, nSteps, tol)
    env = {**os.environ, "PYTHONPATH": str(Path(talus.__file__).resolve().parent.parent), "OMP_NUM_THREADS": "1"}
    done = subprocess.run(["run-escript", str(CLIENT), str(rve), str(nx), str(ny), str(strain), str(steps),
                           str(nSteps), str(tol)], capture_output=True, text=True, env=env, timeout=3600)
    if done.returncode != 0:
        raise RuntimeError("run-escript failed:\n" + done.stdout[-2000:] + done.stderr[-2000:])
    theirs = np.array([[float(v) for v in m] for m in re.findall(r"^step (\S+) (\S+) (\S+) (\d+)$", done.stdout,
                                                                   re.MULTILINE)])
    print("escript:", theirs.tolist())
    diff = float(np.abs(theirs[:, 2] - ours[:, 2]).max() / np.abs(ours[:, 2]).max())
    print(f"largest relative difference of the mean axial stress: {diff:.2e}")
    case.record("largest relative difference of the mean axial stress, escript driver against FEniCSx driver",
                diff, "the same run driven by talus.fem.fenicsx", 0.01, steps=steps, cells=nx * ny,
                newton_iterations_fenicsx=ours[:, 3].tolist(), newton_iterations_escript=theirs[:, 3].tolist())
    fig, ax = plt.subplots(figsize=(6, 4))
    for data, style, name in ((ours, "o-", "FEniCSx"), (theirs, "k--x", "escript")):
        ax.plot(100 * data[:, 0], -data[:, 2] / 1e3, style, label=f"{name}, axial")
        ax.plot(100 * data[:, 0], -data[:, 1] / 1e3, style, alpha=0.5, label=f"{name}, lateral")
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("mean compressive stress over the Gauss points (kPa)")
    ax.set_title(f"escript vs FEniCSx: max rel. diff {diff:.1e}")
    ax.legend(fontsize=8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
