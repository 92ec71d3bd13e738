"""Run under mpirun: the Gauss-point calls with the RVEs spread over the ranks give the same
stress and tangent as one process holding them all, over two committed increments and a
rollback. Rank 0 prints `points <local count of each rank>` and `err <max relative difference>`."""
import sys

import numpy as np
from mpi4py import MPI

from talus.fem import MultiscaleRVEs

path, comm = sys.argv[1], MPI.COMM_WORLD
rng = np.random.default_rng(3)
grads = [rng.uniform(-1e-3, 1e-3, (5, 3, 3)) for _ in range(3)]
spread = MultiscaleRVEs(path, numPoints=5, nSteps=10, comm=comm)
alone = MultiscaleRVEs(path, numPoints=5, nSteps=10)
err = 0.0
for k, g in enumerate(grads):
    for rves in (spread, alone):
        rves.run(g)
        if k == 1:                      # a rejected trial, then the accepted one
            rves.rollback()
            rves.run(g * 0.5)
        rves.commit()
    (s1, c1), (s2, c2) = spread.getStressAndTangent(), alone.getStressAndTangent()
    err = max(err, np.abs(s1 - s2).max() / np.abs(s2).max(), np.abs(c1 - c2).max() / np.abs(c2).max(),
              np.abs(spread.getVoidRatio() - alone.getVoidRatio()).max())
try:                                     # an error names the global Gauss point on any rank
    MultiscaleRVEs([path] * 4 + ["/nonexistent/rve.h5"], comm=comm)
    message = ""
except ValueError as e:
    message = str(e)
messages = comm.gather(message)
counts = comm.gather(len(spread.localPoints))      # printed by rank 0 only: ranks' lines could interleave
err = comm.allreduce(err, op=MPI.MAX)
if comm.rank == 0:
    print("points " + " ".join(map(str, counts)), flush=True)
    print(f"err {err}", flush=True)
    print(f"errors {messages}", flush=True)
