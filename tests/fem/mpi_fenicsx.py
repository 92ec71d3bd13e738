"""Run under mpirun: the FEniCSx driver with the RVEs spread over the ranks (the FE problem, on
COMM_SELF, replicated on every rank) gives the same stress path as with all RVEs in one process.
argv: RVE file. Rank 0 prints `err <max relative difference>` and `iterations <per step>`."""
import sys

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from talus.fem import MultiscaleRVEs
from talus.fem.fenicsx import Dirichlet, MultiscaleSolver, Traction


def run(comm):
    msh = dmesh.create_rectangle(MPI.COMM_SELF, [np.zeros(2), np.array([2.0, 1.0])], [2, 1],
                                 dmesh.CellType.quadrilateral)
    rves = MultiscaleRVEs(sys.argv[1], numPoints=8, nSteps=10, comm=comm)
    solver = MultiscaleSolver(
        msh, rves, tol=1e-6,
        dirichlet=[Dirichlet(lambda x: np.isclose(x[0], 0), 0), Dirichlet(lambda x: np.isclose(x[1], 0), 1),
                   Dirichlet(lambda x: x[1] > 0.5, 1, lambda t: -0.004 * t)],
        tractions=[Traction(lambda x: x[0] > 1.5, lambda t: (-1e5, 0.0))])
    solver.step(1.0)
    return np.array([r.stress for r in solver.history]), [r.iterations for r in solver.history]


spread, iterations = run(MPI.COMM_WORLD)
alone, _ = run(None)
err = MPI.COMM_WORLD.allreduce(float(np.abs(spread - alone).max() / np.abs(alone).max()), op=MPI.MAX)
if MPI.COMM_WORLD.rank == 0:
    print(f"err {err}", flush=True)
    print(f"iterations {iterations}", flush=True)
