"""Bonded spheres with rolling and twisting moments (CohFrictMat, Yade's
Law2_ScGeom6D_CohFrictPhys_CohesionMoment, total-rotation form): a fixed sphere and a bonded
one set spinning and vibrating, then a third sphere hits and bonds on contact, the pull of
gravity breaks a bond later. Written so that the same file runs in Yade (`yade -n -x`) and in
Talus. Prints positions and angular velocities every 20 steps as JSON."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(CohFrictMat(young=1e8, poisson=0.3, frictionAngle=0.5, density=2600, normalCohesion=4e4,
                               shearCohesion=4e4, momentRotationLaw=True, etaRoll=0.2, etaTwist=0.1))
O.bodies.append([sphere((0, 0, 0), 0.05, fixed=True), sphere((0.01, 0.0, 0.099), 0.05),
                 sphere((0.1, 0.02, 0.14), 0.04)])
O.bodies[1].state.angVel = (3.0, -2.0, 5.0)
O.bodies[1].state.vel = (0.05, 0.02, 0.0)
O.bodies[2].state.vel = (-0.6, 0.0, 0.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D()],
                    [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=True)],
                    [Law2_ScGeom6D_CohFrictPhys_CohesionMoment()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0),
    PyRunner(command="track.append([list(O.bodies[i].state.pos) + list(O.bodies[i].state.angVel) for i in (1, 2)])",
             iterPeriod=20),
]
O.dt = 1e-6
track = []
O.run(60001, True)
print("RESULT " + json.dumps({"dt": O.dt, "x": track}))
