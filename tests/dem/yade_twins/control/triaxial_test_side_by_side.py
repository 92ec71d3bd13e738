"""Yade's TriaxialTest preprocessor on the packing of triax_packing.json (importFilename), then
`steps` steps: the scene's first time step and engines, the TriaxialCompressionEngine's
read-outs and the spheres' positions. Runs in Yade and in Talus
(tests/dem/control/test_triaxial_compression.py); prints RESULT."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

steps = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("steps", 200)
with open("triax_packing.json") as f:
    spheres = json.load(f)["spheres"]
packing = "triaxial_test_side_by_side.spheres"
with open(packing, "w") as f:
    f.writelines(f"{c[0]!r} {c[1]!r} {c[2]!r} {r!r}\n" for c, r in spheres)
TriaxialTest(importFilename=packing, noFiles=True, sigmaIsoCompaction=-60e3, sigmaLateralConfinement=-60e3).load()
os.remove(packing)
dt0 = O.dt
O.run(steps, True)
triax = O.engines[4]
print("RESULT " + json.dumps({
    "dt0": dt0, "dt": O.dt, "engines": [type(e).__name__ for e in O.engines],
    "walls": [triax.wall_bottom_id, triax.wall_top_id, triax.wall_left_id, triax.wall_right_id, triax.wall_back_id,
              triax.wall_front_id],
    "stress": [list(triax.stress(k)) for k in range(6)], "strain": list(triax.strain), "state": triax.currentState,
    "mass": O.bodies[6].state.mass, "pos": [list(b.state.pos) for b in O.bodies][6:]}))
