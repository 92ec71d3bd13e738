"""Stress and tangent operator of a dense packing whose contacts carry shear forces, in Yade
(`yade -n -x`, getStressAndTangent) and in Talus (form="yade" and the full form): the spheres of
periodic_packing.json without the periodic cell, each given a deterministic velocity, after one
step (fresh contacts get their first shear increment from the velocities). Prints one JSON
line `RESULT {...}` (talus.twin) (the volume is the packing's bounding box)."""
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

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # packing_scene.py, under Yade's -x too
from packing_scene import linear_engines, load_packing  # noqa: E402

data = load_packing(periodic=False)
velocities = np.sin(np.arange(3 * len(data["pos"])).reshape(-1, 3) * 1.7) * 0.05
for b, v in zip(O.bodies, velocities):
    b.state.vel = Vector3(*v) if not talus else v
linear_engines()
O.dt = 1e-5
O.run(1, True)
pos = np.array([list(b.state.pos) for b in O.bodies])
volume = float(np.prod(pos.max(axis=0) - pos.min(axis=0)))
if talus:
    stress, tangent = getStressAndTangent(volume, form="yade")
    full = getStressAndTangent(volume)[1].tolist()
    shearing = sum(1 for c in O.contacts() if np.any(c["shearForce"]))
else:
    stress, tangent = getStressAndTangent(volume, True)
    full, shearing = None, None
tangent = np.array(tangent)
tangent = np.triu(tangent) + np.triu(tangent, 1).T     # Yade fills the upper triangle only
print("RESULT " + json.dumps({"stress": np.array(stress).tolist(), "tangent": tangent.tolist(), "full": full,
                               "shearing": shearing}))
