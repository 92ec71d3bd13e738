"""Spheres landing, sliding and rolling in an open facet box (friction on facet faces and edges),
written so that the same file runs in Yade (`yade -n -x`) and in Talus: prints the positions every
500 steps as JSON (one TRAJECTORY line)."""
import json

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

O.bodies.append(geom.facetBox((.5, .5, .5), (.5, .5, .5), wallMask=31))
spheres = O.bodies.append([sphere((0.2, 0.3, 0.06), 0.05), sphere((0.7, 0.2, 0.3), 0.04), sphere((0.95, 0.5, 0.2), 0.04)])
for i, v in zip(spheres, [(1.0, 0.6, -0.5), (-0.5, 1.0, -1.0), (1.0, 0.0, -1.0)]):
    O.bodies[i].state.vel = v
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.4),
]
O.dt = 2e-5
positions = []
for k in range(60):
    O.run(500, True)
    positions.append([float(x) for i in spheres for x in O.bodies[i].state.pos])
print("RESULT " + json.dumps(positions))
