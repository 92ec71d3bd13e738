"""A clump of three unequal spheres dropped on a wall (FrictMat E = 1e9, frictionless unless asked, damping 0.2): it lands
on one sphere, tips over and settles, so translation, exact aspherical rotation and member
forces all matter. Runs unchanged in Yade (`yade -n -x`) and in Talus (`talus run`); prints the
clump's centroid, member positions and the clump's mass and principal moments as JSON."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

# Frictionless by default: the landing, tipping and rocking are decided by normal forces, member
# torques and the aspherical rotation alone. With {"friction": true} in $TALUS_SCENARIO
# (talus.twin), FrictMat's default friction: the shear history at the wall then matters too.
friction = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("friction", False)
O.materials.append(FrictMat(young=1e9, poisson=0.25, density=1000, frictionAngle=0.5 if friction else 0.0))
O.bodies.append(wall(0, axis=2, sense=1))
clumpId, memberIds = O.bodies.appendClumped([sphere((0, 0, 0.5), 0.1), sphere((0.15, 0, 0.55), 0.08),
                                            sphere((0, 0.12, 0.62), 0.06)])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2),
    PyRunner(command="record()", iterPeriod=200),
]
O.dt = 1e-5  # about 0.17 PWaveTimeStep(), written out so both programs use the same bits
track = {"centroid": [], "members": []}


def record():
    track["centroid"].append(list(O.bodies[clumpId].state.pos))
    track["members"].append([list(O.bodies[i].state.pos) for i in memberIds])


O.run(40001, True)
c = O.bodies[clumpId].state
track.update(dt=O.dt, mass=c.mass, inertia=sorted(list(c.inertia)))
print("RESULT " + json.dumps(track))
