"""escript client of the FEM x DEM multiscale calls (run with `run-escript`, as the seed's msFEM2D):
drained biaxial compression of a 1 x 2 plane-strain sample of finley quadrilaterals, every Gauss
point an RVE, with the boundary conditions and Newton rules of the FEniCSx run of
cases/fem/fem_escript_vs_fenicsx.py (which runs this). On its own:

    PYTHONPATH=build/python run-escript cases/fem/fem_escript_biaxial.py RVE.h5 NX NY STRAIN STEPS NSTEPS TOL FORM

Prints per load step `step <axial strain> <mean sxx> <mean syy> <Newton iterations> <cut>` (means
over the Gauss points)."""
import sys

import numpy as np
from esys.escript import ContinuousFunction, FunctionOnBoundary, sup, wherePositive
from esys.finley import Rectangle

from talus.fem import MultiscaleRVEs
from talus.fem.escript import MultiscaleEscript2D

path, form = sys.argv[1], sys.argv[8]
nx, ny, strain, steps, nSteps, tol = (int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5]),
                                      int(sys.argv[6]), float(sys.argv[7]))
W, H, P_CONF = 1.0, 2.0, 1e5
dx, dy = W / nx / 2, H / ny / 2              # edges are found by their side of these lines, as in FEniCSx
dom = Rectangle(l0=W, l1=H, n0=nx, n1=ny)
rves = MultiscaleRVEs(path, numPoints=4 * nx * ny, nSteps=nSteps, form=form)


def loading(t0, t1):
    x = ContinuousFunction(dom).getX()
    bottom, top = wherePositive(dy - x[1]), wherePositive(x[1] - (sup(x[1]) - dy))   # top: near the current top
    corner = bottom * wherePositive(dx - x[0])
    mask = corner * np.array([1.0, 0.0]) + (bottom + top) * np.array([0.0, 1.0])
    normal = FunctionOnBoundary(dom).getNormal()         # lateral faces: outward normal along -x / +x
    traction = (wherePositive(-normal[0] - 0.5) - wherePositive(normal[0] - 0.5)) * np.array([P_CONF, 0.0])
    # the increment of the total displacement, computed as the FEniCSx driver does (value(t1) - value(t0))
    return mask, top * np.array([0.0, -strain * H * t1 - -strain * H * t0]), traction


solver = MultiscaleEscript2D(dom, rves, loading, tol=tol)
for n in range(1, steps + 1):
    report = solver.step(n / steps)
    s = report.stress
    print(f"step {strain * n / steps!r} {s[:, 0, 0].mean()!r} {s[:, 1, 1].mean()!r} {report.iterations} "
          f"{int(report.cut)}", flush=True)
