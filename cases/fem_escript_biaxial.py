"""escript client of the FEM x DEM multiscale calls (run with `run-escript`, as the seed's msFEM2D):
drained biaxial compression of a 1 x 2 plane-strain sample of finley quadrilaterals, every Gauss
point an RVE. Used by cases/fem_escript_vs_fenicsx.py; on its own:

    PYTHONPATH=build/python run-escript cases/fem_escript_biaxial.py RVE.h5 NX NY STRAIN STEPS NSTEPS TOL

Prints per load step `step <axial strain> <mean sxx> <mean syy> <Newton iterations>` (means over
the Gauss points)."""
import sys

import numpy as np
from esys.escript import ContinuousFunction, FunctionOnBoundary, wherePositive, whereZero
from esys.finley import Rectangle

from talus.fem import MultiscaleRVEs
from talus.fem.escript import MultiscaleEscript2D

path = sys.argv[1]
nx, ny, strain, steps, nSteps, tol = (int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5]),
                                      int(sys.argv[6]), float(sys.argv[7]))
W, H, P_CONF = 1.0, 2.0, 1e5
dom = Rectangle(l0=W, l1=H, n0=nx, n1=ny)
rves = MultiscaleRVEs(path, numPoints=4 * nx * ny, nSteps=nSteps)
solver = MultiscaleEscript2D(dom, rves, tol=tol)
for n in range(1, steps + 1):
    x = ContinuousFunction(dom).getX()
    bottom, top = whereZero(x[1]), wherePositive(x[1] - H / 2)
    corner = bottom * whereZero(x[0])
    mask = corner * np.array([1.0, 0.0]) + (bottom + top) * np.array([0.0, 1.0])
    increment = top * np.array([0.0, -strain * H / steps])
    normal = FunctionOnBoundary(dom).getNormal()         # lateral faces: outward normal along -x / +x
    traction = (wherePositive(-normal[0] - 0.5) - wherePositive(normal[0] - 0.5)) * np.array([P_CONF, 0.0])
    it = solver.step(mask, increment, traction)
    s, _ = rves.getStressAndTangent()
    print(f"step {strain * n / steps!r} {s[:, 0, 0].mean()!r} {s[:, 1, 1].mean()!r} {it}", flush=True)
