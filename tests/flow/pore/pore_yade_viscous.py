# Yade side of the viscous-force comparison (tests/flow/pore/test_pore_viscous.py): run with
#   cd tests/flow/pore && yade -n -x pore_yade_viscous.py packing.txt out.json
# The spheres of packing.txt (x y z r per line) in the walls of their bounding box, fixed, each
# with a velocity and an angular velocity drawn from random.Random(5) (written to the output so
# that Talus uses the same). No integrator in the engine list: the spheres keep their positions
# and velocities. For each option set below FlowEngine runs two steps (the normal lubrication
# spring's load changes between them); after each, the shear force, its torque and the normal
# lubrication force on every sphere (Yade's shearLubForce, shearLubTorque, normalLubForce).
import json
import random
import sys

args = [a for a in sys.argv[1:] if not a.startswith("-")]
packing, out = args[0], args[1]
DT = 1e-4
OPTIONS = {
    "viscousShear": dict(viscousShear=True),
    "shearLubrication": dict(shearLubrication=True),
    "normalLubrication": dict(normalLubrication=True),
    "normalLubricationNoSpring": dict(normalLubrication=True, stiffness=0),
}
spheres = [tuple(map(float, l.split())) for l in open(packing) if l.strip() and not l.startswith("#")]
rng = random.Random(5)
vel = [[rng.uniform(-1, 1) for _ in range(3)] for _ in spheres]
angVel = [[rng.uniform(-10, 10) for _ in range(3)] for _ in spheres]
lo = [min(s[k] - s[3] for s in spheres) for k in range(3)]
hi = [max(s[k] + s[3] for s in spheres) for k in range(3)]
res = {"dt": DT, "velocities": vel, "angularVelocities": angVel, "viscosity": 0.5}
for name, options in OPTIONS.items():
    O.reset()
    O.bodies.append(aabbWalls([Vector3(*lo), Vector3(*hi)], thickness=0))
    ids = []
    for (x, y, z, r), v, w in zip(spheres, vel, angVel):
        b = sphere((x, y, z), r, fixed=True)
        b.state.vel = Vector3(*v)
        b.state.angVel = Vector3(*w)
        ids.append(O.bodies.append(b))
    flow = FlowEngine(useSolver=3, viscosity=res["viscosity"], **options)
    flow.bndCondIsPressure = [0, 0, 1, 1, 0, 0]
    flow.bndCondValue = [0, 0, 1, 0, 0, 0]
    flow.meshUpdateInterval = 10 ** 9
    O.engines = [flow]
    O.dt = DT
    steps = []
    for _ in range(2):
        O.step()
        steps.append({
            "shearLubForce": [list(flow.shearLubForce(i)) for i in ids],
            "shearLubTorque": [list(flow.shearLubTorque(i)) for i in ids],
            "normalLubForce": [list(flow.normalLubForce(i)) for i in ids],
        })
    res[name] = steps
json.dump(res, open(out, "w"))
print("wrote", out, "for", len(ids), "spheres")
