"""escript client (run-escript): one finley element, drained biaxial plane-strain loading as in
cases/fem/fem_one_element.py (left ux = 0, bottom uy = 0, top lowered to the axial strain in equal
load steps, right edge under 100 kPa), with the Newton rules of the FEniCSx driver
(talus.fem.newton); argv: RVE file, load steps, axial strain, DEM steps per call, Newton tolerance.
Prints `stress <sxx> <syy> iterations <n>` (Gauss point 0) after each step."""
import sys

import numpy as np
from esys.escript import ContinuousFunction, FunctionOnBoundary, wherePositive, whereZero
from esys.finley import Rectangle

from talus.fem import MultiscaleRVEs
from talus.fem.escript import MultiscaleEscript2D

path, steps, strain = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
dom = Rectangle(l0=1.0, l1=1.0, n0=1, n1=1)
rves = MultiscaleRVEs(path, numPoints=4, nSteps=int(sys.argv[4]))


def loading(t0, t1):
    x = ContinuousFunction(dom).getX()
    left, bottom, top = whereZero(x[0]), whereZero(x[1]), wherePositive(x[1] - 0.5)
    mask = left * np.array([1.0, 0.0]) + (bottom + top) * np.array([0.0, 1.0])
    normal = FunctionOnBoundary(dom).getNormal()      # the right edge: outward normal along +x
    return mask, top * np.array([0.0, -strain * (t1 - t0)]), wherePositive(normal[0] - 0.5) * np.array([-1e5, 0.0])


solver = MultiscaleEscript2D(dom, rves, loading, tol=float(sys.argv[5]))
for n in range(1, steps + 1):
    report = solver.step(n / steps)
    s, _ = rves.getStressAndTangent()
    print(f"stress {s[0][0, 0]!r} {s[0][1, 1]!r} iterations {report.iterations}", flush=True)
