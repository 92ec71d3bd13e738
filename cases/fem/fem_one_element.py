"""FEM x DEM case: one element, homogeneous strain. The FEM x DEM stress path equals a
direct DEM run of the same RVE under the same strain path.

Run:      build/bin/talus run cases/fem/fem_one_element.py [--quick] [--results DIR]
Set-up:   one bilinear quadrilateral (unit square, plane strain, 2x2 Gauss points, dolfinx 0.5)
          whose four Gauss points carry copies of one RVE (talus.fem.prepareRVE: a periodic
          makeCloud packing, rMean 0.1, consolidated to -100 kPa). Drained biaxial loading: left
          edge ux = 0, bottom uy = 0, top uy lowered to an axial strain of 2 % (quick) or 5 % in
          10 (quick) or 25 load steps, right edge under a 100 kPa confining traction; the lateral
          displacement is an unknown, so Newton iterates (with RVE rollbacks) every step. The small
          RVE is anisotropic (shear stress at zero shear strain), so the element shears and the four
          Gauss points follow four strain paths; for each, a direct DEM run (talus.dem Scene,
          O.cell.velGrad sub-steps) of the same RVE file replays its converged gradients.
Checked:  fem.one-element.stress-path: largest relative difference (to the largest stress) between
          the FEM x DEM stress of each Gauss point and its direct DEM stress, over all converged
          increments (<= 1e-8).
          fem.one-element.confinement: relative gap of the right edge's final reaction to the
          confining force (Newton tolerance 1e-6; equilibrium holds on the configuration at the
          start of the step, so O(step strain) after it; <= 1e-3).
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
    strain, steps, nSteps, size = (0.02, 10, 50, 1.2) if args.quick else (0.05, 25, 100, 2.0)
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
    for n in range(1, steps + 1):
        report = solver.step(n / steps)
        s = report.stress
        print(f"step {n}: axial strain {solver.t * strain:.4f}, Newton iterations {report.iterations}, "
              f"Gauss point 0: sxx {s[0][0, 0]:.1f} syy {s[0][1, 1]:.1f}", flush=True)
    history = solver.history                   # every converged increment (a cut step has several)
    ezz = np.array([r.t for r in history]) * strain
    iters = [r.iterations for r in history]
    diff, ref = 0.0, None
    for p in range(4):                         # each Gauss point against a direct run of its own path
        ours = np.array([r.stress[p] for r in history])
        direct = replay(rve, [r.gradients[p] for r in history], [r.nSteps for r in history])[1][:, :2, :2]
        diff = max(diff, float(np.abs(ours - direct).max() / np.abs(direct).max()))
        if p == 0:
            fem_stress, ref = ours, direct
    case.record("largest relative difference of the FEM x DEM stress path from a direct DEM run of the same RVE",
                diff, "talus.dem Scene replaying each Gauss point's converged gradients", 1e-8, suffix="stress-path",
                steps=steps, nSteps=nSteps, spheres=info["spheres"], newton_iterations=iters)
    height = float(msh.geometry.x[:, 1].max())
    reaction = solver.reactions(lambda x: x[0] > 0.5, 0)
    lateral = abs(reaction / (-P_CONF * height) - 1)
    case.record("relative gap of the right edge's reaction to the 100 kPa confinement times its height", lateral,
                "traction boundary condition (equilibrium on the configuration at the start of each step)", 1e-3,
                suffix="confinement")
    print(f"stress path difference {diff:.3e}, confinement gap {lateral:.3e}, Newton iterations {iters}")

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    e = ezz * 100
    axes[0].plot(e, -fem_stress[:, 1, 1] / 1e3, "o-", label="FEM x DEM (Gauss point 0), axial")
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
