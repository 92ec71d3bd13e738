"""escript client of the Gauss-point calls (the seed's msFEM2D procedure, run with `run-escript`).

A LinearPDE for the Newton correction of the displacement increment du, per iteration:
A = the RVE tangent (fourth-order, from :func:`talus.fem.tangentToTensor`), X = -stress,
y = the boundary traction, q/r = the prescribed displacement mask and zero correction; escript's
weak form int A : grad(d) : grad(v) = int X : grad(v) + int y . v is then K d = -R. Plane strain,
updated Lagrangian (the domain moves by the converged du). The Newton and load-stepping rules
(convergence measure, stall, backtracking, step cutting) are those of the FEniCSx driver,
:class:`talus.fem.newton.NewtonLoadStepping`, so that both drivers solve the same discrete problem
along the same path.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from talus.fem.newton import NewtonDivergence, NewtonLoadStepping, StepReport
from talus.fem.rves import tangentToTensor

__all__ = ["MultiscaleEscript2D", "NewtonDivergence", "StepReport", "fromData", "gaussPointCoordinates", "toData"]


def toData(values, where, shape=None):
    """numpy -> escript: ``values`` (numPoints, *shape), one value per data point, as expanded
    escript Data on ``where`` (a function space, or a domain: then ``Function(domain)``, the
    Gauss points). Point p is escript's data point p of that space: sample (element) by sample
    in escript's sample order, and within a sample quadrature point by quadrature point, i.e.
    p = e * nq + q, the order of ``toListOfTuples()``, of ``fromData`` and of
    :func:`gaussPointCoordinates` (the positions of the points). ``shape`` defaults to
    ``values.shape[1:]``."""
    from esys.escript import Data, Function
    fs = where if hasattr(where, "getDomain") else Function(where)
    values = np.asarray(values, dtype=float)
    n = fs.getX().getNumberOfDataPoints()
    if len(values) != n:
        raise ValueError(f"toData: {len(values)} values for {n} data points")
    shape = tuple(values.shape[1:]) if shape is None else tuple(shape)
    d = Data(0, shape, fs, True)        # expanded: one value per data point
    for p in range(n):
        d.setValueOfDataPoint(p, values[p] if shape else float(values[p]))
    return d


def fromData(data) -> np.ndarray:
    """escript -> numpy: the values of ``data`` per data point, shape (numPoints, *data.getShape()),
    in the order of :func:`toData` (p = e * nq + q)."""
    n = data.getNumberOfDataPoints()
    return np.array(data.toListOfTuples(), dtype=float).reshape((n,) + tuple(data.getShape()))


def gaussPointCoordinates(domain) -> np.ndarray:
    """The positions (numPoints, d) of the Gauss points of ``Function(domain)`` in the order of
    :func:`toData` (e.g. to give each Gauss point its RVE by position)."""
    from esys.escript import Function
    return fromData(Function(domain).getX())


class MultiscaleEscript2D(NewtonLoadStepping):
    """``domain``: an escript (finley) 2D domain; ``rves``: :class:`talus.fem.MultiscaleRVEs`
    with one RVE per data point of ``Function(domain)``; ``loading(t0, t1)``: the load step from
    load factor t0 to t1 in the current configuration, as escript Data ``(mask, increment,
    traction)``: the prescribed components (1 on the nodes, per component), the prescribed
    displacement increment there, and the traction at t1 on ``FunctionOnBoundary`` (or None).
    The other arguments are those of :class:`talus.fem.newton.NewtonLoadStepping`."""

    def __init__(self, domain, rves, loading: Callable, tol: float = 1e-6, maxIter: int = 50,
                 minStepFraction: float = 1 / 64, stall: int = 8, backtrack: int = 4):
        from esys.escript import Function
        from esys.escript.linearPDEs import LinearPDE
        super().__init__(rves, tol=tol, maxIter=maxIter, minStepFraction=minStepFraction, stall=stall,
                         backtrack=backtrack)
        self.domain, self.loading = domain, loading
        self.n = Function(domain).getX().getNumberOfDataPoints()
        if rves.numPoints != self.n:
            raise ValueError(f"MultiscaleEscript2D: the domain has {self.n} Gauss points, but {rves.numPoints} RVEs")
        self.pde = LinearPDE(domain, numEquations=2)
        self.pde.getSolverOptions().setTolerance(1e-12)
        self.internal = LinearPDE(domain, numEquations=2, numSolutions=2)   # its right-hand side: int sigma : grad v

    def _tensor(self, values, shape):
        return toData(values, self.domain, shape)

    # -- the hooks of NewtonLoadStepping ------------------------------------------------------
    def _start(self, t0: float, t1: float):
        from esys.escript import Solution, Vector
        self.mask, increment, traction = self.loading(t0, t1)
        self.du = increment * self.mask
        self.pde.setValue(q=self.mask, r=Vector(0, Solution(self.domain)))
        if traction is not None:
            self.pde.setValue(y=traction)

    def gaussGradients(self) -> np.ndarray:
        from esys.escript import grad
        return np.array(grad(self.du).toListOfTuples()).reshape(self.n, 2, 2)

    def _setStressAndTangent(self, stress, tangent):
        X = self._tensor(stress, (2, 2))
        self.pde.setValue(A=self._tensor(tangentToTensor(tangent), (2, 2, 2, 2)), X=-X)
        self.internal.setValue(X=X)

    def _relativeResidual(self) -> float:
        # -R at the free dofs against the internal nodal forces (reactions included), 2-norms over
        # the dofs as in the FEniCSx driver
        free = np.array((self.pde.getRightHandSide() * (1 - self.mask)).toListOfTuples())
        internal = np.array(self.internal.getRightHandSide().toListOfTuples())
        return float(np.linalg.norm(free) / max(np.linalg.norm(internal), 1e-300))

    def _correct(self):
        self.ddu = self.pde.getSolution()
        self.du = self.du + self.ddu

    def _retract(self, fraction: float):
        self.du = self.du - fraction * self.ddu

    def _accept(self):
        self.domain.setX(self.domain.getX() + self.du)
