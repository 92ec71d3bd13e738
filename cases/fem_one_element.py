"""FEM x DEM case: one element, homogeneous strain (issue #7). The FEM x DEM stress path equals a
direct DEM run of the same RVE under the same strain path.

Run:      build/bin/talus run cases/fem_one_element.py [--quick] [--results DIR]
Set-up:   one bilinear quadrilateral (unit square, plane strain, 2x2 Gauss points, dolfinx 0.5)
          whose four Gauss points carry copies of one RVE (talus.fem.prepareRVE: a periodic
          makeCloud packing, rMean 0.1, consolidated to -100 kPa). Drained biaxial loading: left
          edge ux = 0, bottom uy = 0, top uy lowered to an axial strain of 2 % (quick) or 5 % in
          10 (quick) or 25 load steps, right edge under a 100 kPa confining traction; the lateral
          displacement is an unknown, so Newton iterates (with RVE rollbacks) every step. Then a
          direct DEM run (talus.dem Scene, O.cell.velGrad sub-steps) of the same RVE file replays
          the converged displacement gradients of Gauss point 0.
Checked:  fem.one-element.stress-path: largest relative difference (to the largest stress) between
          the FEM x DEM stress of Gauss point 0 and the direct DEM stress, over all load steps
          (<= 1e-8).
          fem.one-element.homogeneous: largest spread of the converged gradients between the four
          Gauss points, relative to the gradient (<= 1e-8: the solution is homogeneous).
          fem.one-element.confinement: relative gap of the final lateral stress to -100 kPa (Newton
          tolerance 1e-6, <= 1e-3).
Produces: the records and chart fem.one-element.png (axial and lateral stress against axial strain,
          FEM x DEM and direct DEM; Newton iterations per step).
"""
import tempfile
from pathlib import Path

import numpy as np

from talus import results

P_CONF = 1e5


def main():
    args = results.case_arguments(__doc__).parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs, prepareRVE
    from talus.fem.direct import replay
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, Traction

    case = results.Case("fem.one-element", quick=args.quick, folder=args.results)
    strain, steps, nSteps, size = (0.02, 10, 50, 1.0) if args.quick else (0.05, 25, 100, 1.5)
    work = Path(tempfile.mkdtemp(prefix="fem_one_element_"))
    rve = work / "rve.h5"
    info = prepareRVE(rve, size=size, rMean=0.1, seed=1, sigma=-P_CONF, young=1e8)
    print(f"RVE: {info['spheres']} spheres, porosity {info['porosity']:.4f}, stress {info['stress']}")

    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.ones(2)], [1, 1], dmesh.CellType.quadrilateral)
    rves = MultiscaleRVEs(str(rve), numPoints=4, nSteps=nSteps)
    solver = MultiscaleSolver(
        msh, rves, tol=1e-6,
        dirichlet=[Dirichlet(lambda x: np.isclose(x[0], 0), 0), Dirichlet(lambda x: np.isclose(x[1], 0), 1),
                   Dirichlet(lambda x: x[1] > 0.5, 1, lambda t: -strain * t)],
        tractions=[Traction(lambda x: x[0] > 0.5, lambda t: (-P_CONF, 0.0))])
    # The top and right edges move with the mesh (updated Lagrangian): they are selected by their
    # side of the sample's middle, which they never cross.
    ezz, fem_stress, grads, iters, ends, spread = [], [], [], [], [], 0.0
    for n in range(1, steps + 1):
        report = solver.step(n / steps)
        for r in solver.history[len(grads):]:
            g = r.gradients
            grads.append(g[0])
            spread = max(spread, np.abs(g - g[0]).max() / np.abs(g[0]).max())
            iters.append(r.iterations)
        ends.append(len(grads) - 1)     # a cut step converges in several increments
        s, _ = rves.getStressAndTangent()
        fem_stress.append(s[0])
        ezz.append(solver.t * strain)
        print(f"step {n}: axial strain {ezz[-1]:.4f}, Newton iterations {report.iterations}, "
              f"sxx {s[0][0, 0]:.1f} syy {s[0][1, 1]:.1f}", flush=True)
    dem_stress = replay(rve, grads, nSteps)[1][:, :2, :2]
    fem_stress = np.array(fem_stress)
    ref = dem_stress[ends]
    diff = float(np.abs(fem_stress - ref).max() / np.abs(ref).max())
    case.record("largest relative difference of the FEM x DEM stress path from a direct DEM run of the same RVE",
                diff, "talus.dem Scene replaying the converged Gauss-point gradients", 1e-8, suffix="stress-path",
                steps=steps, nSteps=nSteps, spheres=info["spheres"], newton_iterations=iters)
    case.record("largest spread of the converged displacement gradients over the 4 Gauss points", spread,
                "homogeneous solution", 1e-8, suffix="homogeneous")
    lateral = float(abs(fem_stress[-1][0, 0] / -P_CONF - 1))
    case.record("relative gap of the final lateral stress to the 100 kPa confinement", lateral,
                "traction boundary condition", 1e-3, suffix="confinement")
    print(f"stress path difference {diff:.3e}, Gauss-point spread {spread:.3e}, lateral gap {lateral:.3e}, "
          f"Newton iterations {iters}")

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    e = np.array(ezz) * 100
    axes[0].plot(e, -fem_stress[:, 1, 1] / 1e3, "o-", label="FEM x DEM, axial")
    axes[0].plot(e, -ref[:, 1, 1] / 1e3, "k--", label="direct DEM, axial")
    axes[0].plot(e, -fem_stress[:, 0, 0] / 1e3, "s-", label="FEM x DEM, lateral")
    axes[0].plot(e, -ref[:, 0, 0] / 1e3, "k:", label="direct DEM, lateral")
    axes[0].set_xlabel("axial strain (%)")
    axes[0].set_ylabel("compressive stress (kPa)")
    axes[0].legend()
    axes[0].set_title(f"one element, {info['spheres']}-sphere RVE: max rel. diff {diff:.1e}")
    axes[1].bar(range(1, len(iters) + 1), iters)
    axes[1].set_xlabel("converged increment")
    axes[1].set_ylabel("Newton iterations")
    case.save_chart(fig)


if __name__ == "__main__":
    main()
