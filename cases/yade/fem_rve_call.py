"""Scenario: the Gauss-point call on one RVE packing, timed, in Yade and in Talus (talus.twin).
Parameters ($TALUS_SCENARIO): `packing` (JSON of talus.fem.exportRVE), `points`, `calls`, `nSteps`,
`rveSceneDir` (talus.fem.rve_scene.FOLDER: the scene builder shared with cases/yade/fem_rve_tangent.py).

Each call deforms every Gauss point's RVE from its committed state by a small gradient over
nSteps DEM steps and reads the stress and tangent; then the trial is rejected (rollback), as in a
Newton iteration. Yade does what the seed's simDEM-style call does: restore the scene
(O.loadTmp), set O.cell.velGrad, O.run(nSteps), getStressAndTangent. Talus: MultiscaleRVEs.run /
getStressAndTangent / rollback (all points in one C++ call). Under mpirun (Talus) the points are
spread over the ranks. Prints `RESULT {seconds, calls_per_s (Gauss-point calls per second)}`."""
import json
import os
import sys
import time

import numpy as np

try:
    O  # noqa: B018  (defined when Yade runs the script)
    talus = False
except NameError:
    from talus.dem import *  # noqa: F401,F403
    talus = True

P = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
points, calls, n = int(P["points"]), int(P["calls"]), int(P["nSteps"])
sys.path.append(P["rveSceneDir"])
from rve_scene import buildRVEScene  # noqa: E402  (the shared builder, talus/fem/rve_scene.py)

data = buildRVEScene(globals(), P["packing"])
O.run(1, True)                       # contacts exist before the calls
G = np.array([[-1e-3, 2e-4, 0], [0, 5e-4, 0], [0, 0, 5e-4]])
comm = None
if talus:
    from talus.fem import MultiscaleRVEs
    if "OMPI_COMM_WORLD_SIZE" in os.environ:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    rves = MultiscaleRVEs([O] * points, nSteps=n, comm=comm)
    grads = np.array([G] * points)
    start = time.perf_counter()
    for c in range(calls):
        rves.run(grads)
        rves.getStressAndTangent()
        rves.rollback()
else:
    O.saveTmp("rve")
    start = time.perf_counter()
    for c in range(calls):
        for p in range(points):
            O.loadTmp("rve")
            O.cell.velGrad = Matrix3(*(G / (n * O.dt)).ravel())
            O.run(n, True)
            getStressAndTangent(O.cell.volume, True)
seconds = time.perf_counter() - start
if comm is None or comm.rank == 0:
    print("RESULT " + json.dumps({"seconds": seconds, "calls_per_s": calls * points / seconds,
                                  "spheres": len(data["radius"])}))
