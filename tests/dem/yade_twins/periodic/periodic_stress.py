"""A dense periodic packing (150 spheres, stored in periodic_packing.json, sheared cell): one
step of contact forces and the homogenised stress, written so the same file runs in Yade
(`yade -n -x`) and in Talus. Prints getStress() and the number of contacts as `RESULT {...}` (talus.twin)."""
import json
import os
import sys

import numpy as np

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # packing_scene.py, under Yade's -x too
from packing_scene import linear_engines, load_packing  # noqa: E402

load_packing()
linear_engines()
O.dt = 1e-12
O.step()
print("RESULT " + json.dumps({"stress": np.array(getStress()).tolist(), "contacts": avgNumInteractions()}))
