"""NewtonIntegrator's damping per body (state.isDamped) and dampGravity, written so that the same
file runs in Yade (`yade -n -x`) and in Talus: the scene of Yade's NumericalDampingGravity.py, two
spheres thrown up that fall on a box, one of them not damped; spheres rotate too. Parameters
(TALUS_SCENARIO): dampGravity. Prints one RESULT line (tests/dem/engines/test_damping.py)."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

params = json.loads(os.environ.get("TALUS_SCENARIO", "{}"))
O.materials.append(FrictMat(young=2e8, poisson=0.3, frictionAngle=0.3, density=8000))
damped = O.bodies.append(sphere((0.025, 0.1, 0.025), 0.0025))
free = O.bodies.append(sphere((0.025, 0.1, 0.035), 0.0025))
O.bodies[free].state.isDamped = False
for i in (damped, free):
    O.bodies[i].state.vel = (0.1, 1, 0)
    O.bodies[i].state.angVel = (0, 0, 30)
O.bodies.append(box((0.025, 0.045, 0.025), (0.05, 0.005, 0.05), fixed=True))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, -9.81, 0), damping=0.2, dampGravity=params["dampGravity"])]
O.dt = 5e-6
track = []
for k in range(40):
    O.run(3000, True)
    track.append([list(O.bodies[i].state.pos) + list(O.bodies[i].state.vel) + list(O.bodies[i].state.angVel)
                  for i in (damped, free)])
print("RESULT " + json.dumps({"track": track, "isDamped": [O.bodies[i].state.isDamped for i in (damped, free)]}))
