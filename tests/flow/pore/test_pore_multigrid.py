"""The multigrid pressure solvers (FlowEngine.useSolver=4: conjugate gradients preconditioned by
smoothed-aggregation algebraic multigrid; useSolver=5: by hypre's BoomerAMG) against CHOLMOD's
factor (useSolver=3) on the same networks: same pressures to their tolerance, in steady and
transient solves."""
import numpy as np
import pytest

from talus.dem.packing.pack import SpherePack
from talus.flow import FlowEngine


def cloud(num=2000):
    # large enough for several multigrid levels (the coarsest is solved densely below 400 rows)
    sp = SpherePack()
    side = (num / 1000) ** (1 / 3)
    sp.makeCloud((0, 0, 0), (side, side, side), rMean=0.035, rRelFuzz=0.3, num=num, seed=7)
    pos = np.array([c for c, _ in sp])
    rad = np.array([r for _, r in sp])
    return pos, rad


def engine(solver, pos, rad, **kw):
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], useSolver=solver, **kw)
    flow.triangulate(pos, rad)
    flow.solve()
    return flow


# (multigridTolerance, the bounds against CHOLMOD's of the pressures, relative to the largest,
# and of the boundary fluxes): the default, and a tighter one the errors follow down (measured at
# the default: pressures 7.2e-7 with useSolver=4, 4.0e-8 with 5; the outlet's flux 4.6e-8 and 2.5e-8)
TOLERANCES = [(None, 1e-6, 1e-7), (1e-10, 1e-8, 1e-9)]


@pytest.mark.parametrize("solver", [4, 5])
@pytest.mark.parametrize("tolerance, pressure_bound, flux_bound", TOLERANCES)
def test_same_pressures_and_fluxes_as_cholmod_without_a_factor(solver, tolerance, pressure_bound, flux_bound):
    pos, rad = cloud()
    direct = engine(3, pos, rad)
    mg = engine(solver, pos, rad, **({} if tolerance is None else {"multigridTolerance": tolerance}))
    assert mg.nCells() > 10000
    p, q = direct.pressures, mg.pressures
    assert np.max(np.abs(q - p)) < pressure_bound * np.max(np.abs(p))
    for k in (2, 3):
        assert mg.getBoundaryFlux(k) == pytest.approx(direct.getBoundaryFlux(k), rel=flux_bound)
    stats = mg.solverStats()
    assert stats["factorizations"] == 0 and stats["analyses"] == 0
    assert stats["multigridSetups"] == 1 and 0 < stats["multigridIterations"] < 100
    # the same system again: conjugate gradients start from the last pressures, the answer
    iterations = stats["multigridIterations"]
    mg.solve()
    stats = mg.solverStats()
    assert stats["multigridSetups"] == 1 and stats["multigridIterations"] == iterations
    assert np.max(np.abs(mg.pressures - q)) == 0


@pytest.mark.parametrize("solver", [4, 5])
def test_moving_spheres_and_a_compressible_fluid_match_cholmod(solver):
    pos, rad = cloud()
    rng = np.random.default_rng(3)
    moved = pos + rng.uniform(-1e-3, 1e-3, pos.shape) * rad[:, None]
    for bulk in (0.0, 1e3):
        direct, mg = engine(3, pos, rad), engine(solver, pos, rad)
        for flow in (direct, mg):
            flow.fluidBulkModulus = bulk
            flow.moveVertices(moved, 1e-4)
            flow.solve()
        p, q = direct.pressures, mg.pressures
        assert np.max(np.abs(q - p)) < 1e-6 * np.max(np.abs(p)), bulk
        forces = direct._flow.vertexForces(), mg._flow.vertexForces()
        assert np.max(np.abs(forces[1] - forces[0])) < 1e-6 * np.max(np.abs(forces[0])), bulk
        # a compressible fluid changes the matrix at every solve: a new hierarchy each time
        assert mg.solverStats()["multigridSetups"] == (1 if bulk == 0 else 2), bulk


@pytest.mark.parametrize("tolerance", [0.0, -1e-8, 1.0])
def test_a_tolerance_outside_zero_one_is_refused_naming_it(tolerance):
    pos, rad = cloud(200)
    flow = FlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], bndCondValue=[0, 0, 1, 0, 0, 0], useSolver=5,
                      multigridTolerance=tolerance)
    flow.triangulate(pos, rad)
    with pytest.raises(ValueError, match="multigridTolerance must be in \\(0, 1\\)"):
        flow.solve()


def test_unknown_solver_is_refused_naming_the_choices():
    with pytest.raises(ValueError, match="4 \\(multigrid\\) or 5 \\(hypre's BoomerAMG\\)"):
        FlowEngine(useSolver=6)
