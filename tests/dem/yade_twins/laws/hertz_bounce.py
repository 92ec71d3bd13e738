"""An oblique collision of two spheres with Hertz-Mindlin contacts (restitution 0.7, friction),
then the second sphere bounces on a fixed one under gravity. Written so that the same file runs
in Yade (`yade -n -x`) and in Talus. Prints positions and angular velocities every 20 steps as
JSON."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(FrictMat(young=1e9, poisson=0.3, frictionAngle=0.4, density=2600))
O.bodies.append([sphere((0, 0, 0), 0.05, fixed=True), sphere((0.03, 0.01, 0.15), 0.05),
                 sphere((-0.08, 0.005, 0.21), 0.04)])
O.bodies[2].state.vel = (1.0, 0, 0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(algo='val', val=0.7),
                                                       es=MatchMaker(algo='val', val=0.7))],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0),
    PyRunner(command="track.append([list(O.bodies[i].state.pos) + list(O.bodies[i].state.angVel) for i in (1, 2)])",
             iterPeriod=20),
]
O.dt = 2e-6
track = []
O.run(60001, True)
print("RESULT " + json.dumps({"dt": O.dt, "x": track}))
