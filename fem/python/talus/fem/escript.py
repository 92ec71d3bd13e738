"""escript client of the Gauss-point calls (the seed's msFEM2D procedure, run with `run-escript`).

A LinearPDE for the Newton correction of the displacement increment du, per iteration:
A = the RVE tangent (fourth-order, from :func:`talus.fem.tangentToTensor`), X = -stress,
y = the boundary traction, q/r = the prescribed displacement mask and values; escript's weak form
int A : grad(d) : grad(v) = int X : grad(v) + int y . v is then K d = -R. Plane strain, updated
Lagrangian (the domain moves by the converged du), as :mod:`talus.fem.fenicsx`.
"""

from __future__ import annotations

import numpy as np

from talus.fem.rves import tangentToTensor


class MultiscaleEscript2D:
    """``domain``: an escript (finley) 2D domain; ``rves``: :class:`talus.fem.MultiscaleRVEs`
    with one RVE per data point of ``Function(domain)``."""

    def __init__(self, domain, rves, tol: float = 1e-6, maxIter: int = 50):
        from esys.escript import Function
        from esys.escript.linearPDEs import LinearPDE
        self.domain, self.rves, self.tol, self.maxIter = domain, rves, tol, maxIter
        self.n = Function(domain).getX().getNumberOfDataPoints()
        if rves.numPoints != self.n:
            raise ValueError(f"MultiscaleEscript2D: the domain has {self.n} Gauss points, but {rves.numPoints} RVEs")
        self.pde = LinearPDE(domain, numEquations=2)
        self.pde.getSolverOptions().setTolerance(1e-12)
        self.iterations = []

    def _tensor(self, values, shape):
        from esys.escript import Data, Function
        d = Data(0, shape, Function(self.domain), True)   # expanded: one value per point
        for p in range(self.n):
            d.setValueOfDataPoint(p, values[p])
        return d

    def _evaluate(self, du):
        from esys.escript import grad
        self.rves.run(np.array(grad(du).toListOfTuples()).reshape(self.n, 2, 2))
        stress, tangent = self.rves.getStressAndTangent()
        return self._tensor(stress, (2, 2)), self._tensor(tangentToTensor(tangent), (2, 2, 2, 2))

    def step(self, mask, increment, traction=None) -> int:
        """One load step: du = `increment` where `mask` is 1 (escript Data on the nodes, one
        value per component), the traction `traction` (a vector on FunctionOnBoundary, or None)
        elsewhere. Returns the number of Newton iterations; commits the RVEs and moves the
        domain. On divergence the RVEs are rolled back and RuntimeError is raised."""
        from esys.escript import Lsup, Solution, Vector
        from esys.escript.linearPDEs import LinearPDE
        du = increment * mask
        internal = LinearPDE(self.domain, numEquations=2, numSolutions=2)
        for it in range(self.maxIter + 1):
            X, A = self._evaluate(du)
            self.pde.setValue(A=A, X=-X, q=mask, r=Vector(0, Solution(self.domain)))
            if traction is not None:
                self.pde.setValue(y=traction)
            internal.setValue(X=X)
            # -R at the free nodes against the internal nodal forces (reactions included).
            residual = Lsup(self.pde.getRightHandSide() * (1 - mask)) / max(Lsup(internal.getRightHandSide()), 1e-300)
            if residual < self.tol:
                self.iterations.append(it)
                self.rves.commit()
                self.domain.setX(self.domain.getX() + du)
                return it
            du = du + self.pde.getSolution()
        self.rves.rollback()
        raise RuntimeError(f"escript Newton did not converge in {self.maxIter} iterations (residual {residual:g})")
