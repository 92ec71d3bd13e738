"""FEM x DEM case: drained biaxial compression of a coarse plane-strain sample.

Run:      build/bin/talus run cases/fem/fem_biaxial.py [--quick] [--results DIR]
Set-up:   a 1 x 2 sample of bilinear quadrilaterals (quick: 2 x 4, full: 4 x 8; 2x2 Gauss points)
          with an RVE at every Gauss point (talus.fem.prepareRVE, rMean 0.1, -100 kPa, friction
          0.5); the four points of one cell left of the centre get a weaker RVE (friction 0.3)
          as the imperfection. Smooth platens: bottom uy = 0 (and ux = 0 at the bottom-left
          corner), top lowered to an axial strain of 1.5 % (quick) or 6 %, left and right edges under a
          100 kPa traction. 40 (quick) or 100 DEM steps per call; finite-difference consistent
          tangent (form="fd"); Newton tolerance 1e-5, a step is cut in half after 4 iterations
          without progress; updated Lagrangian.
Checked:  fem.biaxial.converged: fraction of the load steps that converged (= 1).
          fem.biaxial.lateral: relative gap of the left-edge reaction to the 100 kPa traction times
          the edge height at the end (equilibrium on the configuration at the start of the step:
          <= 1e-2).
Produces: the records, the chart fem.biaxial.png (stress ratio and volumetric strain against
          axial strain; shear strain of the last increment per cell) and biaxial.xdmf (ParaView:
          displacement, stress, void ratio, shear strain) in the results folder.
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
    from dolfinx.io import XDMFFile
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs, prepareRVE
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, NewtonDivergence, Traction

    case = results.Case("fem.biaxial", quick=args.quick, folder=args.results)
    (nx, ny), strain, steps, nSteps = ((2, 4), 0.015, 6, 40) if args.quick else ((4, 8), 0.06, 30, 100)
    W, H = 1.0, 2.0
    work = Path(tempfile.mkdtemp(prefix="fem_biaxial_"))
    strong, weak = work / "strong.h5", work / "weak.h5"
    prepareRVE(strong, size=1.2, rMean=0.1, seed=1, sigma=-P_CONF, young=1e8)
    prepareRVE(weak, size=1.2, rMean=0.1, seed=1, sigma=-P_CONF, young=1e8, friction=0.3, compactionFriction=0.5)
    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.array([W, H])], [nx, ny],
                                 dmesh.CellType.quadrilateral)
    centres = dmesh.compute_midpoints(msh, 2, np.arange(nx * ny, dtype=np.int32))[:, :2]
    target = np.argmin(np.linalg.norm(centres - [0.3 * W, 0.5 * H], axis=1))
    rves = MultiscaleRVEs([str(weak) if c == target else str(strong) for c in range(nx * ny) for _ in range(4)],
                          nSteps=nSteps, form="fd")
    dx, dy = W / nx / 2, H / ny / 2            # edges are found by their side of these lines
    solver = MultiscaleSolver(
        msh, rves, tol=1e-5, stall=4,
        dirichlet=[Dirichlet(lambda x: x[1] < dy, 1), Dirichlet(lambda x: (x[1] < dy) & (x[0] < dx), 0),
                   Dirichlet(lambda x: x[1] > x[1].max() - dy, 1, lambda t: -strain * H * t)],  # current top
        tractions=[Traction(lambda x: x[0] < dx, lambda t: (P_CONF, 0.0)),
                   Traction(lambda x: x[0] > W - dx, lambda t: (-P_CONF, 0.0))])
    area0 = W * H
    rows, converged = [], 0
    folder = Path(case.folder)
    folder.mkdir(parents=True, exist_ok=True)
    with XDMFFile(msh.comm, str(folder / "biaxial.xdmf"), "w") as xdmf:
        xdmf.write_mesh(msh)
        for n in range(1, steps + 1):
            try:
                report = solver.step(n / steps)
            except NewtonDivergence as e:
                print(f"step {n}: {e}")
                break
            converged += 1
            x = msh.geometry.x
            width = x[:, 0].max() - x[:, 0].min()
            height = x[:, 1].max() - x[:, 1].min()
            top = -solver.reactions(lambda y: y[1] > height - dy, 1) / width      # compressive, Pa
            rows.append((solver.t * strain, top, 1 - width * height / area0))
            print(f"step {n}: axial strain {rows[-1][0]:.4f}, axial stress {top:.0f} Pa, volumetric strain "
                  f"{rows[-1][2]:.5f}, Newton iterations {report.iterations}"
                  f"{' (step cut)' if report.cut else ''}, increments so far {len(solver.history)}", flush=True)
            solver.write(xdmf, solver.t)
    lateral = abs(solver.reactions(lambda y: y[0] < dx, 0) / (P_CONF * (msh.geometry.x[:, 1].max())) - 1)
    case.record("fraction of the load steps that converged", converged / steps, "all steps", 1.0, comparison=">=",
                suffix="converged", cells=nx * ny, gauss_points=rves.numPoints, steps=steps, nSteps=nSteps)
    case.record("relative gap of the left-edge reaction to the 100 kPa traction times the edge height", lateral,
                "traction boundary condition", 1e-2, suffix="lateral")
    r = np.array(rows)
    fields = solver.fields()
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    ratio = (r[:, 1] - P_CONF) / (r[:, 1] + P_CONF)
    axes[0].plot(100 * r[:, 0], ratio, "o-")
    axes[0].set_xlabel("axial strain (%)")
    axes[0].set_ylabel("(s1 - s3) / (s1 + s3)")
    axes[1].plot(100 * r[:, 0], 100 * r[:, 2], "o-")
    axes[1].set_xlabel("axial strain (%)")
    axes[1].set_ylabel("volumetric strain (%, compression +)")
    from matplotlib.collections import PolyCollection
    x = msh.geometry.x[:, :2]
    # dolfinx quadrilaterals list their vertices in tensor-product order: 0 1 3 2 goes around.
    cells = [x[msh.geometry.dofmap.links(c)[[0, 1, 3, 2]]] for c in range(nx * ny)]
    patches = PolyCollection(cells, array=fields["shearStrain"], cmap="viridis", edgecolor="k")
    axes[2].add_collection(patches)
    axes[2].autoscale()
    axes[2].set_aspect("equal")
    sc = patches
    axes[2].set_title("shear strain of the last increment (per cell)")
    fig.colorbar(sc, ax=axes[2])
    fig.suptitle(f"FEM x DEM drained biaxial, {nx}x{ny} cells, {rves.numPoints} RVEs (weak cell {target})")
    case.save_chart(fig)


if __name__ == "__main__":
    main()
