"""Yade's ServoPIDController, written so that the same file runs in Yade (`yade -n -x`) and in
Talus: a facet plate pressed on a layer of spheres is driven down by the controller until the
spheres push it with the target force, combined (engine + engine) with a slow rotation, as in
Yade's PIDController.py. Prints the plate's position and velocity and the controller's state
(one RESULT line)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

mat = O.materials.append(ViscElMat(frictionAngle=0.3, density=2000, tc=1e-3, en=0.3, et=0.3))
floor = O.bodies.append([facet([(-1, -1, 0), (1, -1, 0), (1, 1, 0)], material=mat),
                         facet([(-1, -1, 0), (1, 1, 0), (-1, 1, 0)], material=mat)])
plate = O.bodies.append([facet([(-1, -1, 0.205), (1, -1, 0.205), (1, 1, 0.205)], material=mat),
                         facet([(-1, -1, 0.205), (1, 1, 0.205), (-1, 1, 0.205)], material=mat)])
O.bodies.append([sphere((0.3 * i - 0.6, 0.3 * j - 0.6, 0.1), 0.1, material=mat) for i in range(5) for j in range(5)])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
    ServoPIDController(axis=(0, 0, 1), maxVelocity=0.5, iterPeriod=20, ids=plate, target=2e4, kP=1e-5, kI=2e-6,
                       kD=1e-6, label='servo')
    + RotationEngine(rotationAxis=(0, 0, 1), angularVelocity=0.5, rotateAroundZero=True, zeroPoint=(0, 0, 0)),
]
O.dt = 2e-5
rows = []
for k in range(20):
    O.run(200, True)
    p = O.bodies[plate[0]].state
    rows.append(list(p.pos) + list(p.vel) + list(servo.current) + [servo.curVel, servo.errorCur, servo.iTerm,
                                                                  servo.iterPrevStart])
print("RESULT " + json.dumps(rows))
