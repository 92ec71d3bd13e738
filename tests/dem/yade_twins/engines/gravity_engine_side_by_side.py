"""GravityEngine on free spheres and a clump, with energy tracking, written so that the same file
runs in Yade (`yade -n -x`) and in Talus: prints the positions and O.energy['gravWork'] every 50
steps (one RESULT line; tests/dem/impose/test_gravity_engine.py)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(FrictMat(density=2000, young=1e7, poisson=0.3, frictionAngle=0.5))
ids = O.bodies.append([sphere((0, 0, 0), 0.1), sphere((1, 0, 0), 0.2, fixed=True)])
clump, members = O.bodies.appendClumped([sphere((3, 0, 0), 0.1), sphere((3.15, 0, 0), 0.1)])
O.bodies[ids[0]].state.vel = (0.5, 0, 2.0)
O.engines = [ForceResetter(), GravityEngine(gravity=(1.0, -2.0, -9.81), warnOnce=False),
             NewtonIntegrator(damping=0.1)]
O.dt = 1e-3
O.trackEnergy = True
rows = []
for k in range(6):
    O.run(50, True)
    rows.append([float(x) for i in ids + [clump] for x in O.bodies[i].state.pos] + [O.energy["gravWork"]])
print("RESULT " + json.dumps(rows))
