"""makeCloud in a box whose maxCorner is below minCorner along y (Yade's funnel.py), written so
that the same file runs in Yade (`yade -n -x`) and in Talus. Prints one RESULT line
(tests/yade/test_inverted_cloud.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403
from yade import pack

sp = pack.SpherePack()
count = sp.makeCloud(Vector3(-1, -9, 30), Vector3(1, -13, 32), .2, rRelFuzz=.3, seed=1)
print("RESULT " + json.dumps({"count": count, "spheres": [list(c) + [r] for c, r in sp]}))
