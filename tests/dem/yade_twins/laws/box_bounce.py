"""Spheres bouncing and rolling on boxes (a face, an edge, a tilted box) with frictional linear
contacts and Yade's non-viscous damping: Yade's simple-scene on more than one face. Written so
that the same file runs in Yade (`yade -n -x`) and in Talus. Prints the spheres' positions and
angular velocities every 50 steps as JSON."""
import json
import math

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.1, gravity=(0, 0, -9.81)),
    PyRunner(command="track.append([list(O.bodies[i].state.pos) + list(O.bodies[i].state.angVel) for i in (2, 3, 4)])",
             iterPeriod=50),
]
tilt = Quaternion((1, 0, 0), 0.3)
O.bodies.append(box(center=(0, 0, 0), extents=(0.5, 0.5, 0.5), fixed=True))
O.bodies.append(box(center=(3, 0, 0), extents=(0.5, 0.5, 0.5), orientation=tilt, fixed=True))
O.bodies.append(sphere((0, 0, 2), 1))                       # on the top face, as simple-scene.py
O.bodies.append(sphere((0.65, 0.2, 0.9), 0.3))              # on the edge
O.bodies.append(sphere((3, 0.1, 1.1), 0.2))                 # rolling down the tilted box
O.dt = 0.2 * PWaveTimeStep()
track = []
O.run(6000, True)
print("RESULT " + json.dumps({"dt": O.dt, "x": track}))
