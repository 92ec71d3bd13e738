"""An FEM x DEM drained biaxial test, written into a folder with its inputs (study.json beside
it) by ``talus case femxdem`` (talus.fem.case_builder.biaxial_study): edit either freely.

Run:      build/bin/talus run femxdem.py   (in the folder it was written to)
What:     mesh: a width x height rectangle of cells[0] x cells[1] bilinear quadrilaterals (plane
          strain, 2 x 2 Gauss points); RVEs: one consolidated periodic packing
          (talus.fem.prepareRVE: rMean, friction, the confining stress) at every Gauss point;
          driver: talus.fem.fenicsx.MultiscaleSolver, smooth platens (bottom uy = 0 and ux = 0 at
          its left corner, top lowered to the axial strain in `steps` load steps), the confining
          stress as a traction on the left and right edges; each Gauss-point call runs
          `demSteps` DEM steps, finite-difference consistent tangent.
Produces: biaxial.csv (axial strain, axial stress, stress ratio, volumetric strain per load
          step), biaxial.png (stress ratio and volumetric strain against axial strain) and
          biaxial.xdmf (ParaView: displacement, stress, shear strain) beside this script.
"""
import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def main():
    from dolfinx import mesh as dmesh
    from dolfinx.io import XDMFFile
    from mpi4py import MPI

    from talus.fem import MultiscaleRVEs, prepareRVE
    from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, NewtonDivergence, Traction

    study = json.loads((HERE / "study.json").read_text())
    (nx, ny), (width, height) = study["cells"], study["size"]
    p, strain, steps = study["confinement"], study["axialStrain"], study["steps"]
    rve = HERE / "rve.h5"
    if not rve.exists():   # the packing is kept: a rerun with other loads reuses it
        state = prepareRVE(rve, size=study["rveSize"], rMean=study["rMean"], seed=study["seed"], sigma=-p,
                           young=study["young"], friction=study["friction"])
        print(f"RVE: {state}", flush=True)
    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.array([width, height])], [nx, ny],
                                 dmesh.CellType.quadrilateral)
    rves = MultiscaleRVEs(str(rve), numPoints=4 * nx * ny, nSteps=study["demSteps"], form="fd")
    dx, dy = width / nx / 2, height / ny / 2     # edges are found by their side of these lines
    solver = MultiscaleSolver(
        msh, rves, tol=1e-5, stall=4,
        dirichlet=[Dirichlet(lambda x: x[1] < dy, 1), Dirichlet(lambda x: (x[1] < dy) & (x[0] < dx), 0),
                   Dirichlet(lambda x: x[1] > x[1].max() - dy, 1, lambda t: -strain * height * t)],
        tractions=[Traction(lambda x: x[0] < dx, lambda t: (p, 0.0)),
                   Traction(lambda x: x[0] > x[0].max() - dx, lambda t: (-p, 0.0))])
    rows = []
    with XDMFFile(msh.comm, str(HERE / "biaxial.xdmf"), "w") as xdmf:
        xdmf.write_mesh(msh)
        for n in range(1, steps + 1):
            try:
                report = solver.step(n / steps)
            except NewtonDivergence as e:
                print(f"load step {n}: {e}")
                break
            x = msh.geometry.x
            w, h = np.ptp(x[:, 0]), np.ptp(x[:, 1])
            axial = -solver.reactions(lambda y: y[1] > h - dy, 1) / w
            rows.append((solver.t * strain, axial, (axial - p) / (axial + p), 1 - w * h / (width * height)))
            print(f"load step {n}/{steps}: axial strain {rows[-1][0]:.4f}, axial stress {axial:.0f} Pa, stress ratio "
                  f"{rows[-1][2]:.3f}, Newton iterations {report.iterations}", flush=True)
            solver.write(xdmf, solver.t)
    table = np.array(rows)
    np.savetxt(HERE / "biaxial.csv", table, delimiter=",", fmt="%.8g",
               header="axial_strain,axial_stress_Pa,stress_ratio,volumetric_strain", comments="")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    axes[0].plot(100 * table[:, 0], table[:, 2], "o-")
    axes[0].set_ylabel("(s1 - s3) / (s1 + s3)")
    axes[1].plot(100 * table[:, 0], 100 * table[:, 3], "o-")
    axes[1].set_ylabel("volumetric strain (%, compression +)")
    for ax in axes:
        ax.set_xlabel("axial strain (%)")
    fig.suptitle(f"FEM x DEM biaxial test: {nx} x {ny} cells, {rves.numPoints} RVEs")
    fig.tight_layout()
    fig.savefig(HERE / "biaxial.png", dpi=110)
    print(f"wrote {HERE / 'biaxial.csv'}, {HERE / 'biaxial.png'} and {HERE / 'biaxial.xdmf'}")


if __name__ == "__main__":
    main()
