"""escript client (run-escript): one finley element, drained biaxial plane-strain loading as in
cases/fem_one_element.py (left ux = 0, bottom uy = 0, top lowered by 0.4 % per step, right edge
under 100 kPa); argv: RVE file, load steps, axial strain, DEM steps per call, Newton tolerance. Prints `stress <sxx> <syy>` (Gauss point 0) after each step."""
import sys

import numpy as np
from esys.escript import ContinuousFunction, FunctionOnBoundary, wherePositive, whereZero
from esys.finley import Rectangle

from talus.fem import MultiscaleRVEs
from talus.fem.escript import MultiscaleEscript2D

path, steps, strain = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
dom = Rectangle(l0=1.0, l1=1.0, n0=1, n1=1)
rves = MultiscaleRVEs(path, numPoints=4, nSteps=int(sys.argv[4]))
solver = MultiscaleEscript2D(dom, rves, tol=float(sys.argv[5]))
for n in range(steps):
    x = ContinuousFunction(dom).getX()
    left, bottom, top = whereZero(x[0]), whereZero(x[1]), wherePositive(x[1] - 0.5)
    mask = left * np.array([1.0, 0.0]) + (bottom + top) * np.array([0.0, 1.0])
    increment = top * np.array([0.0, -strain / steps])
    normal = FunctionOnBoundary(dom).getNormal()      # the right edge: outward normal along +x
    traction = wherePositive(normal[0] - 0.5) * np.array([-1e5, 0.0])
    it = solver.step(mask, increment, traction)
    s, _ = rves.getStressAndTangent()
    print(f"stress {s[0][0, 0]!r} {s[0][1, 1]!r} iterations {it}", flush=True)
