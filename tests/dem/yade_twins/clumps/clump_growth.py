"""Growing clumps (growParticles) in flight and while resting on a wall: a clump of three unequal
spheres and a free sphere dropped on a wall (FrictMat E = 1e7, friction 0.5 rad, damping 0.2),
grown by 1.5 % every 2000 steps (the fourth time without updating masses). Runs unchanged in
Yade (`yade -n -x`) and in Talus; prints, after each growth, the clump's mass and principal
moments, its members' radii and offsets from its centroid, and every 200 steps the member and
free sphere positions, as JSON."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.materials.append(FrictMat(young=1e7, poisson=0.25, density=1000, frictionAngle=0.5))
O.bodies.append(wall(0, axis=2, sense=1))
clumpId, memberIds = O.bodies.appendClumped([sphere((0, 0, 0.12), 0.1), sphere((0.15, 0, 0.17), 0.08),
                                            sphere((0, 0.12, 0.24), 0.06)])
freeId = O.bodies.append(sphere((0.4, 0.05, 0.1), 0.07))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2),
    PyRunner(command="record()", iterPeriod=200),
]
O.dt = 1e-5  # about 0.06 PWaveTimeStep(), written out so both programs use the same bits
track = {"members": [], "free": [], "grown": []}


def record():
    track["members"].append([list(O.bodies[i].state.pos) for i in memberIds])
    track["free"].append(list(O.bodies[freeId].state.pos))


for k in range(8):
    O.run(2000, True)
    growParticles(1.015, updateMass=(k != 3))
    c = O.bodies[clumpId].state
    track["grown"].append({"mass": c.mass, "inertia": sorted(list(c.inertia)), "pos": list(c.pos),
                           "radii": [O.bodies[i].shape.radius for i in memberIds],
                           "offsets": [list(O.bodies[i].state.pos - c.pos) for i in memberIds],
                           "freeMass": O.bodies[freeId].state.mass})
O.run(4001, True)
print("RESULT " + json.dumps(track))
