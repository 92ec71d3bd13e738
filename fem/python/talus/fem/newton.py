"""The Newton-Raphson and load-stepping rules of the FEM x DEM drivers (seed chapter 13.3), shared by
:mod:`talus.fem.fenicsx` and :mod:`talus.fem.escript` so that the two drivers take the same path
through the RVEs' non-smooth response (same convergence measure, stall rule, correction
backtracking, step cutting, commit and rollback): their difference then measures the drivers.

A driver supplies the finite element side: the loads and the prescribed increment of a step, the
Gauss-point gradients of the current increment du, the stress and tangent at the Gauss points, the
relative residual, the Newton correction, and the move of the mesh.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class StepReport:
    t: float
    iterations: int
    residuals: list = field(default_factory=list)
    cut: bool = False
    gradients: np.ndarray | None = None   # the converged grad du at every Gauss point
    stress: np.ndarray | None = None      # and the RVEs' stress
    nSteps: int = 0                       # the DEM steps of its RVE calls (fewer for a part of a cut step)


class NewtonDivergence(RuntimeError):
    """A load step could not be solved even at the smallest allowed size; the RVEs and the
    mesh hold the last converged state."""


class NewtonLoadStepping:
    """Load stepping with Newton-Raphson on the increment du from the last converged configuration.

    Convergence: the relative residual (the driver's: |R| at the free dofs / |internal nodal
    forces|) below ``tol``. A step whose residual has not reached a new minimum for ``stall``
    iterations, or has not converged in ``maxIter``, or whose RVE runs fail, is rolled back and
    halved, down to ``minStepFraction`` of the step; then :class:`NewtonDivergence` is raised with
    the last converged state kept. A Newton correction that makes an RVE run fail is halved up to
    ``backtrack`` times first."""

    def __init__(self, rves, tol: float = 1e-6, maxIter: int = 50, minStepFraction: float = 1 / 64,
                 stall: int = 8, backtrack: int = 4):
        self.rves, self.tol, self.maxIter, self.minStepFraction = rves, tol, maxIter, minStepFraction
        self.stall, self.backtrack, self.backtracks = stall, backtrack, 0
        self.t = 0.0
        self.history: list[StepReport] = []
        self.newtonIterations = 0

    # -- the driver's side ----------------------------------------------------------------------
    def _start(self, t0: float, t1: float):
        """Set the loads of t1 and du to the prescribed increment t0 -> t1 (zero elsewhere)."""
        raise NotImplementedError

    def gaussGradients(self) -> np.ndarray:
        """grad du at every Gauss point, (numPoints, d, d), in the RVEs' order."""
        raise NotImplementedError

    def _setStressAndTangent(self, stress: np.ndarray, tangent: np.ndarray):
        raise NotImplementedError

    def _relativeResidual(self) -> float:
        raise NotImplementedError

    def _correct(self):
        """Solve K ddu = -R (prescribed dofs fixed) and add ddu to du."""
        raise NotImplementedError

    def _retract(self, fraction: float):
        """du -= fraction x the last correction."""
        raise NotImplementedError

    def _accept(self):
        """The step converged: move the mesh by du (updated Lagrangian)."""
        raise NotImplementedError

    # -- the shared rules ------------------------------------------------------------------------
    def _evaluate(self):
        self._grads = self.gaussGradients()
        self.rves.run(self._grads)
        stress, tangent = self.rves.getStressAndTangent()
        self._stress = stress
        # The Love-Weber stress of an RVE not quite in equilibrium is slightly asymmetric (1 % of
        # the shear stress of a 63-disk RVE after 40 DEM steps); the continuum balance takes its
        # symmetric part, as the seed's Yade call does (getStressAndTangent(symmetry=True)), in
        # both drivers (FEniCSx's Voigt vector would take sigma_xy, escript's X the full tensor).
        self._setStressAndTangent(0.5 * (stress + stress.transpose(0, 2, 1)), tangent)

    def _evaluate_backtracking(self, it: int):
        """Evaluate the RVEs at du; when a Newton correction makes an RVE fail (crushed, inverted:
        near a limit point the tangent is nearly singular and a full correction overshoots),
        halve the correction, up to ``backtrack`` times, before giving up on the iteration."""
        for halving in range(self.backtrack + 1):
            try:
                self._evaluate()
                return
            except RuntimeError:
                if it == 0 or halving == self.backtrack:
                    raise
                self.rves.rollback()
                self._retract(0.5 ** (halving + 1))     # du = du0 + ddu / 2, then + ddu / 4, ...
                self.backtracks += 1

    def _try_step(self, t0: float, t1: float) -> StepReport:
        report = StepReport(t1, 0)
        self._start(t0, t1)
        for it in range(self.maxIter + 1):
            self._evaluate_backtracking(it)
            res = self._relativeResidual()
            report.residuals.append(float(res))
            if res < self.tol:
                report.iterations, report.gradients, report.stress = it, self._grads, self._stress
                return report
            # The RVE response is not smooth: a residual that has not reached a new minimum for
            # `stall` iterations will not converge, so give up early and let the step be cut.
            if it - int(np.argmin(report.residuals)) >= self.stall:
                raise NewtonDivergence(f"Newton stalled for {self.stall} iterations (relative residuals "
                                       f"{report.residuals})")
            self._correct()
            self.newtonIterations += 1
        raise NewtonDivergence(f"Newton did not converge in {self.maxIter} iterations "
                               f"(relative residuals {report.residuals})")

    def step(self, t1: float, _span: float | None = None) -> StepReport:
        """Solve the load step from the current load factor to t1, cutting it when Newton fails
        (or an RVE run fails); on success the RVEs are committed and the mesh moves by du.

        The parts of a cut step keep the RVEs' loading rate: each runs over ``rves.nSteps`` times
        its share of the step (rounded, at least 1), so a DEM step strains the RVEs by as much as
        in an uncut step. With the whole ``nSteps`` per part, a part would be loaded at a fraction
        of the rate, and small RVEs answer that: a step cut in two at nSteps 50 ended 6.9 % lower
        in axial stress (cases/fem/fem_speed_accuracy.py). ``_span``: the size of the step asked (the
        recursion for the rest of a cut step)."""
        t0 = self.t
        span = t1 - t0 if _span is None else _span
        nSteps = self.rves.nSteps
        target, cut = t1, False
        try:
            while True:
                self.rves.nSteps = max(1, round(nSteps * (target - t0) / span))
                try:
                    report = self._try_step(t0, target)
                    break
                except (NewtonDivergence, RuntimeError) as e:
                    self.rves.rollback()
                    if (target - t0) / 2 < self.minStepFraction * (t1 - t0):
                        raise NewtonDivergence(f"load step {t0:g} -> {t1:g} failed down to a step of {target - t0:g}: "
                                               f"{e}; the last converged state (t = {t0:g}) is kept") from e
                    target, cut = t0 + (target - t0) / 2, True
            report.nSteps = self.rves.nSteps
        finally:
            self.rves.nSteps = nSteps
        self.rves.commit()
        self._accept()
        self.t = target
        report.cut = cut
        self.history.append(report)
        if target < t1:
            rest = self.step(t1, span)
            rest.cut = True
            return rest
        return report
