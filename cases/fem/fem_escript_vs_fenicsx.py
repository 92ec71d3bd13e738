"""FEM x DEM: the same drained biaxial run driven by escript and by FEniCSx.

Run:      build/bin/talus run cases/fem/fem_escript_vs_fenicsx.py [--quick] [--results DIR]
Set-up:   a uniform 1 x 2 plane-strain sample of bilinear quadrilaterals (2x2 Gauss points, one RVE
          each: a planar RVE of talus.fem.prepareRVE, disks of rMean 0.03 compacted to -100 kPa,
          friction 0.5; quick: 1 x 2 cells, 8 RVEs of 63 disks; full: 2 x 4 cells, 32 RVEs of 111
          disks), bottom uy = 0 (ux = 0 at the bottom-left corner), top lowered to 10 % axial
          strain in 20 (quick) or 50 load steps, 100 kPa on the lateral faces, finite-difference
          consistent tangent, Newton tolerance 1e-4, 40 (quick) or 100 DEM steps per call. Both
          drivers use the Newton and load-stepping rules of talus.fem.newton (the same convergence
          measure, stall rule, backtracking and step cutting) on the same discrete problem (the
          same bilinear elements, 2x2 Gauss rule, boundary nodes and tractions), so the
          difference measures the drivers (assembly, linear solver: LU in FEniCSx, an iterative
          solver to 1e-12 in escript), not two paths through the RVEs' non-smooth response.
          FEniCSx: talus.fem.fenicsx in this process; escript: cases/fem/fem_escript_biaxial.py under
          run-escript (talus.fem.escript, LinearPDE with A = tangent, X = -stress).
Checked:  fem.escript-vs-fenicsx: largest relative difference of the mean axial stress over the
          Gauss points between the two drivers, over every load step of the run to 10 % (<= 1 %).
Produces: the record (with the largest difference of the mean lateral stress and both drivers'
          Newton iterations per step) and chart fem.escript-vs-fenicsx.png (mean axial and lateral
          stress against axial strain, both drivers, and their relative difference).
"""
import os
import re
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results

P_CONF = 1e5
CLIENT = Path(__file__).resolve().with_name("fem_escript_biaxial.py")


def fenicsx(rve, nx, ny, strain, steps, nSteps, tol, form):
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, Traction
    W, H = 1.0, 2.0
    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.array([W, H])], [nx, ny],
                                 dmesh.CellType.quadrilateral)
    rves = MultiscaleRVEs(str(rve), numPoints=4 * nx * ny, nSteps=nSteps, form=form)
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
        rows.append((strain * n / steps, s[:, 0, 0].mean(), s[:, 1, 1].mean(), report.iterations, int(report.cut)))
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
    strain, tol, form = 0.10, 1e-4, "fd"
    (nx, ny, steps, nSteps, size, seed) = (1, 2, 20, 40, 0.5, 2) if args.quick else (2, 4, 50, 100, 0.7, 3)
    rve = Path(tempfile.mkdtemp(prefix="fem_esc_")) / "rve.h5"
    info = prepareRVE(rve, size=size, rMean=0.03, seed=seed, sigma=-P_CONF, young=1e8, planar=True,
                      friction=0.5, compactionFriction=0.1)
    start = time.perf_counter()
    ours = fenicsx(rve, nx, ny, strain, steps, nSteps, tol, form)
    wall = {"fenicsx": time.perf_counter() - start}
    env = {**os.environ, "PYTHONPATH": str(Path(talus.__file__).resolve().parent.parent), "OMP_NUM_THREADS": "1"}
    start = time.perf_counter()
    done = subprocess.run(["run-escript", str(CLIENT), str(rve), str(nx), str(ny), str(strain), str(steps),
                           str(nSteps), str(tol), form], capture_output=True, text=True, env=env, timeout=3600)
    wall["escript"] = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError("run-escript failed:\n" + done.stdout[-2000:] + done.stderr[-2000:])
    theirs = np.array([[float(v) for v in m] for m in re.findall(r"^step (\S+) (\S+) (\S+) (\d+) (\d)$",
                                                                   done.stdout, re.MULTILINE)])
    print("escript:", theirs.tolist())
    if theirs.shape != ours.shape:
        raise RuntimeError(f"escript gave {len(theirs)} load steps, FEniCSx {len(ours)}")
    axial, lateral = (np.abs(theirs[:, k] - ours[:, k]) / np.abs(ours[:, k]) for k in (2, 1))
    diff = float(axial.max())
    print(f"largest relative difference of the mean axial stress: {diff:.2e} (at {100 * ours[axial.argmax(), 0]:.1f} %)"
          f", lateral {lateral.max():.2e}; wall {wall}")
    case.record("largest relative difference of the mean axial stress over the run to 10 %, escript driver against "
                "FEniCSx driver", diff, "the same run driven by talus.fem.fenicsx", 0.01, steps=steps, cells=nx * ny,
                gauss_points=4 * nx * ny, spheres_per_rve=info["spheres"], nSteps=nSteps, tol=tol, tangent=form,
                final_strain=float(ours[-1, 0]), at_strain=float(ours[axial.argmax(), 0]),
                lateral_difference=float(lateral.max()), wall_fenicsx_s=wall["fenicsx"], wall_escript_s=wall["escript"],
                newton_iterations_fenicsx=ours[:, 3].astype(int).tolist(),
                newton_iterations_escript=theirs[:, 3].astype(int).tolist(),
                cut_steps_fenicsx=int(ours[:, 4].sum()), cut_steps_escript=int(theirs[:, 4].sum()))
    fig, (ax, dax) = plt.subplots(1, 2, figsize=(11, 4))
    for data, style, name in ((ours, "o-", "FEniCSx"), (theirs, "k--x", "escript")):
        ax.plot(100 * data[:, 0], -data[:, 2] / 1e3, style, label=f"{name}, axial")
        ax.plot(100 * data[:, 0], -data[:, 1] / 1e3, style, alpha=0.5, label=f"{name}, lateral")
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("mean compressive stress over the Gauss points (kPa)")
    ax.set_title(f"{4 * nx * ny} RVEs of {info['spheres']} disks, tangent form={form!r}, tolerance {tol:g}", fontsize=9)
    ax.legend(fontsize=8)
    dax.semilogy(100 * ours[:, 0], np.maximum(axial, 1e-17), "o-", label="axial")
    dax.semilogy(100 * ours[:, 0], np.maximum(lateral, 1e-17), "s--", label="lateral")
    dax.axhline(0.01, color="r", lw=0.8, label="bound 1 %")
    dax.set_xlabel("axial strain (%)")
    dax.set_ylabel("|escript - FEniCSx| / |FEniCSx|, mean stress")
    dax.set_title(f"largest axial difference {diff:.1e}", fontsize=9)
    dax.legend(fontsize=8)
    case.save_chart(fig)


if __name__ == "__main__":
    main()
