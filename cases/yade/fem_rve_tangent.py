"""Scenario (talus.twin): an exported RVE packing (parameter `packing`: the JSON of
talus.fem.exportRVE; `rveSceneDir`: talus.fem.rve_scene.FOLDER) built as a periodic scene in Yade
and in Talus, each sphere given a deterministic velocity, one step
(fresh contacts get a first shear increment, so Yade's shear term is exercised; the method of
tests/dem/yade_twins/periodic/packing_tangent.py on a periodic RVE). Yade prints its getStressAndTangent; Talus hands
the scene to talus.fem.MultiscaleRVEs (a C++ RVE holding a copy of it) and prints the Gauss-point
getStressAndTangent with form="yade". Output: `RESULT {stress, tangent, shearing}`."""
import json
import os
import sys

import numpy as np

try:
    O  # noqa: B018  (defined when Yade runs the script)
    talus = False
except NameError:
    from talus.dem import *  # noqa: F401,F403
    talus = True

P = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
sys.path.append(P["rveSceneDir"])
from rve_scene import buildRVEScene  # noqa: E402  (the shared builder, talus/fem/rve_scene.py)

data = buildRVEScene(globals(), P["packing"], dt=1e-5)
velocities = np.sin(np.arange(3 * len(data["pos"])).reshape(-1, 3) * 1.7) * 0.05
for b, v in zip(O.bodies, velocities):
    b.state.vel = Vector3(*v) if not talus else v
O.run(1, True)
if talus:
    from talus.fem import MultiscaleRVEs
    rves = MultiscaleRVEs([O], form="yade")
    stress, tangent = (x[0] for x in rves.getStressAndTangent())
    shearing = sum(1 for c in O.contacts() if np.any(c["shearForce"]))
else:
    stress, tangent = getStressAndTangent(O.cell.volume, True)
    tangent = np.array(tangent)
    tangent = np.triu(tangent) + np.triu(tangent, 1).T     # Yade fills the upper triangle only
    shearing = None
print("RESULT " + json.dumps({"stress": np.array(stress).tolist(), "tangent": np.array(tangent).tolist(),
                              "shearing": shearing}))
