"""Yade's Serializable.dict() of materials, states and shapes, written so that the same file runs
in Yade (`yade -n -x`) and in Talus. Values as numbers and lists; prints one RESULT line
(tests/yade/test_serializable_dict.py)."""
import json
import math

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403


def plain(value):
    """A dict value as JSON: numbers (nan as a string), lists of them."""
    if isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return "nan" if math.isnan(value) else value
    if isinstance(value, (tuple, list)):
        return [plain(v) for v in value]
    if isinstance(value, Quaternion):
        return [plain(v) for v in value]     # minieigen's order: x, y, z, w
    return [plain(v) for v in value]         # Vector3


def as_json(d):
    return {k: plain(v) for k, v in d.items()}


out = {}
for M in (FrictMat, ViscElMat, CohFrictMat, ElastMat):
    out[M.__name__] = as_json(M().dict())
O.materials.append(FrictMat(young=1e6, label="soft"))
out["appended"] = as_json(O.materials[0].dict())
bodies = [sphere((1, 2, 3), 0.5, color=(1, 0, 0)), box((0, 0, 5), (1, 2, 3), color=(0, 1, 0)),
          wall(-1, axis=1, color=(0, 0, 1)), facet([(0, 0, 0), (2, 0, 0), (0, 1, 1)], color=(1, 1, 0))]
O.bodies.append(bodies)
O.bodies[0].state.vel = (1, 2, 3)
for b in bodies:
    out["shape %d" % b.id] = as_json(b.shape.dict())
out["state"] = as_json(O.bodies[0].state.dict())
clump, members = O.bodies.appendClumped([sphere((5, 0, 0), 1), sphere((6, 0, 0), 1)])
out["clump material"] = [O.bodies[clump].mat is None, O.bodies[members[0]].mat.id]
print("RESULT " + json.dumps(out))
