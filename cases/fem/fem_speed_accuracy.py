"""FEM x DEM speed and accuracy: Newton iterations and stress error against wall time, over the Newton
tolerance, the tangent (contact stiffness or finite differences) and the DEM steps per call.

Run:      build/bin/talus run cases/fem/fem_speed_accuracy.py [--quick] [--results DIR]
Set-up:   the one-element drained biaxial problem of cases/fem/fem_one_element.py (unit square, 2x2
          Gauss points, 100 kPa confinement) loaded to 1 % axial strain in 4 steps, on an RVE of
          ~100 spheres (quick) or ~230. Sweep 1: Newton tolerance 1e-2 ... 1e-4 with each tangent
          (and 1e-5 with the contact tangent), nSteps 50, against the fd run at tolerance 1e-5 on
          the same four load steps. The reference tolerance is the tightest every step reaches:
          the residual of the last step cycles at 3.3e-6 (a contact opening and closing between
          iterations), so at 1e-6 that step is cut, and the cut run is on another load path
          (4.2e-3 off; 6.9 % when the parts of a cut step ran at half the RVEs' loading rate). A
          reference run that cuts a step stops the case. Sweep 2: nSteps 12, 25, 50 (fd, tolerance
          1e-5) against nSteps 100 (quick) or 12 ... 100 against 400: the DEM steps per call set
          the loading rate of the RVEs, so this is the error of the quasi-static limit.
Checked:  fem.speed-accuracy.fd-iterations: mean Newton iterations per step of the fd tangent at
          tolerance 1e-5 (<= 8).
          fem.speed-accuracy.tolerance: worst relative error of the final axial stress at tolerance
          1e-3 (both tangents) against the reference (<= 0.01).
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
REFERENCE_TOL = 1e-5          # the tightest tolerance all four load steps reach without a cut


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
    return {"wall": wall, "axial": axial, "iterations": np.mean([r.iterations for r in solver.history]),
            "cuts": len(solver.history) - STEPS}


def reference(rve, nSteps):
    """The fd run at REFERENCE_TOL; its load steps must be the sweep's (no cut step)."""
    ref = solve(rve, REFERENCE_TOL, "fd", nSteps)
    if ref["cuts"]:
        raise RuntimeError(f"fem_speed_accuracy: the reference run (tolerance {REFERENCE_TOL:g}, nSteps {nSteps}) "
                           f"cut {ref['cuts']} load step(s): it is not on the sweep's load path")
    return ref


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from talus.fem import prepareRVE
    case = results.Case("fem.speed-accuracy", quick=args.quick, folder=args.results)
    rve = Path(tempfile.mkdtemp(prefix="fem_speed_")) / "rve.h5"
    prepareRVE(rve, size=1.2 if args.quick else 1.6, rMean=0.1, sigma=-P_CONF, young=1e8)
    tols = {"full": [1e-2, 1e-3, 1e-4, 1e-5], "fd": [1e-2, 1e-3, 1e-4]}
    ref = reference(rve, 50)
    sweep = {form: [solve(rve, tol, form, 50) for tol in tols[form]] for form in tols}
    for form, runs in sweep.items():
        for tol, r in zip(tols[form], runs):
            r["error"] = abs(r["axial"] / ref["axial"] - 1)
            print(f"{form} tol {tol:g}: error {r['error']:.2e}, iterations {r['iterations']:.1f}, cut steps "
                  f"{r['cuts']}, {r['wall']:.2f} s", flush=True)
    steps, finest = ([12, 25, 50], 100) if args.quick else ([12, 25, 50, 100], 400)
    limit = reference(rve, finest)
    substeps = [ref if n == 50 else reference(rve, n) for n in steps]
    for n, r in zip(steps, substeps):
        r["rate_error"] = abs(r["axial"] / limit["axial"] - 1)
        print(f"nSteps {n}: error {r['rate_error']:.2e}, iterations {r['iterations']:.1f}, {r['wall']:.2f} s",
              flush=True)
    order = float(-np.polyfit(np.log(steps), np.log([r["rate_error"] for r in substeps]), 1)[0])
    case.record(f"mean Newton iterations per step, finite-difference tangent, tolerance {REFERENCE_TOL:g}",
                ref["iterations"],
                "consistent tangent: a few iterations", 8.0, suffix="fd-iterations",
                contact_tangent_iterations_at_1e5=sweep["full"][-1]["iterations"])
    worst = max(sweep[f][1]["error"] for f in sweep)
    case.record(f"worst relative error of the final axial stress at Newton tolerance 1e-3 against "
                f"{REFERENCE_TOL:g}", worst, f"fd tangent, tolerance {REFERENCE_TOL:g}, same nSteps and load steps",
                0.01, suffix="tolerance",
                wall_full=[r["wall"] for r in sweep["full"]], wall_fd=[r["wall"] for r in sweep["fd"]])
    case.record(f"observed order of the axial stress error in 1 / nSteps (against nSteps {finest})", order,
                "first-order approach of the quasi-static limit", 0.7, comparison=">=", suffix="rate",
                errors=[r["rate_error"] for r in substeps], nSteps=steps)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for form, marker in (("full", "o-"), ("fd", "s-")):
        runs = sweep[form]
        axes[0].loglog([r["wall"] for r in runs], [max(r["error"], 1e-7) for r in runs], marker,
                       label=f"tangent {form}, tolerance {tols[form][0]:g} ... {tols[form][-1]:g}")
        for tol, r in zip(tols[form], runs):
            axes[0].annotate(f"{tol:g}: {r['iterations']:.0f} it", (r["wall"], max(r["error"], 1e-7)), fontsize=7)
    axes[0].set_xlabel("wall time (s, shared machine)")
    axes[0].set_ylabel("relative error of the final axial stress")
    axes[0].set_title(f"Newton tolerance (against the fd tangent at {REFERENCE_TOL:g})")
    axes[0].legend(fontsize=8)
    axes[1].loglog([r["wall"] for r in substeps], [r["rate_error"] for r in substeps], "^-")
    for n, r in zip(steps, substeps):
        axes[1].annotate(f"nSteps {n}", (r["wall"], r["rate_error"]), fontsize=8)
    axes[1].set_xlabel("wall time (s, shared machine)")
    axes[1].set_ylabel(f"error against nSteps {finest}")
    axes[1].set_title("DEM steps per call")
    case.save_chart(fig)


if __name__ == "__main__":
    main()
