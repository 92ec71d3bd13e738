"""Hertz-Mindlin restitution per pair of materials (Ip2_FrictMat_FrictMat_MindlinPhys with
MatchMakers for en and es, as Yade's spheresFactory.py), written so that the same file runs in
Yade (`yade -n -x`) and in Talus: three spheres of two materials collide with each other and
with a facet. Prints the bodies' motion (one RESULT line)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

shots = O.materials.append(FrictMat(young=50e9, density=6000, poisson=.2, frictionAngle=0.5, label='shots'))
steel = O.materials.append(FrictMat(young=210e9, density=7800, poisson=.3, frictionAngle=0.3, label='steel'))
r = 1e-3
ids = O.bodies.append([sphere((0, 0, 0.999 * r), r, material=shots), sphere((2.1 * r, 0.3 * r, 1.05 * r), r, material=shots),
                       sphere((-2.05 * r, -0.2 * r, 1.02 * r), r, material=steel)])
O.bodies.append(facet([(-1e-2, -1e-2, 0), (1e-2, -1e-2, 0), (0, 1e-2, 0)], material=steel))
O.bodies[ids[1]].state.vel = (-3, 0.5, -1)
O.bodies[ids[2]].state.vel = (2, 0, 0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(matches=((steel, shots, .4), (shots, shots, 1), (steel, steel, .7))),
                                                       es=MatchMaker(algo='val', val=0.5, matches=((steel, shots, .8),)))],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-8
motion = []
for k in range(20):
    O.run(200, True)
    motion.append([float(x) for i in ids for x in tuple(O.bodies[i].state.pos) + tuple(O.bodies[i].state.vel)])
print("RESULT " + json.dumps(motion))
