"""geom.facetCylinder in Yade and Talus: prints the world vertices of every facet as JSON."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
    from yade import geom
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.bodies.append(geom.facetCylinder((0.1, 0.2, 0.3), 0.5, 0.8, segmentsNumber=7, wallMask=7))
vs = [[list(b.state.pos + b.state.ori * v) for v in b.shape.vertices] for b in O.bodies]
print("RESULT " + json.dumps(vs))
