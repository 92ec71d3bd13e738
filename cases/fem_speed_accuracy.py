"""FEM x DEM speed and accuracy: Newton iterations and stress error against wall time, over the Newton
tolerance, the tangent (contact stiffness or finite differences) and the DEM steps per call.

Run:      build/bin/talus run cases/fem_speed_accuracy.py [--quick] [--results DIR]
Set-up:   the one-element drained biaxial problem of cases/fem_one_element.py (unit square, 2x2
          Gauss points, 100 kPa confinement) loaded to 1 % axial strain in 4 steps, on an RVE of
          ~100 spheres (quick) or ~230. Sweep 1: Newton tolerance 1e-2 ... 1e-5 with each tangent,
          nSteps 50, against the fd run at tolerance 1e-6 (same nSteps). Sweep 2: nSteps 12, 25, 50
          (fd, tolerance 1e-6) against nSteps 100 (quick) or 12 ... 100 against 400: the DEM steps
          per call set the loading rate of the RVEs, so this is the error of the quasi-static limit.
Checked:  fem.speed-accuracy.fd-iterations: mean Newton iterations per step of the fd tangent at
          tolerance 1e-6 (<= 8).
          fem.speed-accuracy.tolerance: worst relative error of the final axial stress at tolerance
          1e-3 (both tangents) against tolerance 1e-6 (<= 0.01).
          fem.speed-accuracy.rate: observed order of the error in 1 / nSteps (>= 0.7: the
          quasi-static limit is approached at first order).
Produces: the records and chart fem.speed-accuracy.png (error and Newton iterations against wall
          time for both sweeps).
"""
import tempfile
import time
from pathlib import Path

import numpy as np

from talus import results

P_CONF, STRAIN, STEPS = 1e5, 0.01, 4


def solve(rve, tol, form, nSteps):
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, Traction
    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.ones(2)], [1, 1], dmesh.CellType.quadrilateral)
    rves = MultiscaleRVEs(str(rve), numPoints=4, nSteps=nSteps, form=form)
    solver = MultiscaleSolver(
        msh, rves, tol=tol, stall=6,
        dirichlet=[Dirichlet(lambda x: np.isclose(x[0], 0), 0), Dirichlet(lambda x: np.isclose(x[1], 0), 1),
                   Dirichlet(lambda x: x[1] > 0.5, 1, lambda t: -STRAIN * t)],
        tractions=[Traction(lambda x: x[0] > 0.5, lambda t: (-P_CONF, 0.0))])
    start = time.perf_counter()
    for n in range(1, STEPS + 1):
        solver.step(n / STEPS)
    wall = time.perf_counter() - start
    width = float(msh.geometry.x[:, 0].max())
    axial = -solver.reactions(lambda x: x[1] > 0.5, 1) / width
    return {"wall": wall, "axial": axial, "iterations": np.mean([r.iterations for r in solver.history])}


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from talus.fem import prepareRVE
    case = results.Case("fem.speed-accuracy", quick=args.quick, folder=args.results)
    rve = Path(tempfile.mkdtemp(prefix="fem_speed_")) / "rve.h5"
    prepareRVE(rve, size=1.2 if args.quick else 1.6, rMean=0.1, sigma=-P_CONF, young=1e8)
    tols = [1e-2, 1e-3, 1e-4, 1e-5]
    ref = solve(rve, 1e-6, "fd", 50)
    sweep = {form: [solve(rve, tol, form, 50) for tol in tols] for form in ("full", "fd")}
    for form, runs in sweep.items():
        for tol, r in zip(tols, runs):
            r["error"] = abs(r["axial"] / ref["axial"] - 1)
            print(f"{form} tol {tol:g}: error {r['error']:.2e}, iterations {r['iterations']:.1f}, {r['wall']:.2f} s",
                  flush=True)
    steps, finest = ([12, 25, 50], 100) if args.quick else ([12, 25, 50, 100], 400)
    limit = solve(rve, 1e-6, "fd", finest)
    substeps = [ref if n == 50 else solve(rve, 1e-6, "fd", n) for n in steps]
    for n, r in zip(steps, substeps):
        r["rate_error"] = abs(r["axial"] / limit["axial"] - 1)
        print(f"nSteps {n}: error {r['rate_error']:.2e}, iterations {r['iterations']:.1f}, {r['wall']:.2f} s",
              flush=True)
    order = float(-np.polyfit(np.log(steps), np.log([r["rate_error"] for r in substeps]), 1)[0])
    case.record("mean Newton iterations per step, finite-difference tangent, tolerance 1e-6", ref["iterations"],
                "consistent tangent: a few iterations", 8.0, suffix="fd-iterations",
                contact_tangent_iterations_at_1e5=sweep["full"][-1]["iterations"])
    worst = max(sweep[f][1]["error"] for f in sweep)
    case.record("worst relative error of the final axial stress at Newton tolerance 1e-3 against 1e-6", worst,
                "fd tangent, tolerance 1e-6, same nSteps", 0.01, suffix="tolerance",
                wall_full=[r["wall"] for r in sweep["full"]], wall_fd=[r["wall"] for r in sweep["fd"]])
    case.record(f"observed order of the axial stress error in 1 / nSteps (against nSteps {finest})", order,
                "first-order approach of the quasi-static limit", 0.7, comparison=">=", suffix="rate",
                errors=[r["rate_error"] for r in substeps], nSteps=steps)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for form, marker in (("full", "o-"), ("fd", "s-")):
        runs = sweep[form]
        axes[0].loglog([r["wall"] for r in runs], [max(r["error"], 1e-7) for r in runs], marker,
                       label=f"tangent {form}, tolerance 1e-2 ... 1e-5")
        for tol, r in zip(tols, runs):
            axes[0].annotate(f"{tol:g}: {r['iterations']:.0f} it", (r["wall"], max(r["error"], 1e-7)), fontsize=7)
    axes[0].set_xlabel("wall time (s)")
    axes[0].set_ylabel("relative error of the final axial stress")
    axes[0].legend(fontsize=8)
    axes[1].loglog([r["wall"] for r in substeps], [r["rate_error"] for r in substeps], "^-")
    for n, r in zip(steps, substeps):
        axes[1].annotate(f"nSteps {n}", (r["wall"], r["rate_error"]), fontsize=8)
    axes[1].set_xlabel("wall time (s)")
    axes[1].set_ylabel(f"relative error against nSteps {finest}")
    axes[1].set_title("DEM steps per call")
    case.save_chart(fig)


if __name__ == "__main__":
    main()
