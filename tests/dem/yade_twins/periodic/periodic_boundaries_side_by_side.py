"""Spheres landing and rolling on facets (or a box across the cell) in a periodic cell, crossing
its boundaries, written so that the same file runs in Yade (`yade -n -x`) and in Talus. The
spheres start outside the cell and the facets stick out of it: contacts go through periodic
images. Parameters (TALUS_SCENARIO): "shape" "facet" or "box". Prints the spheres' positions
every 500 steps, the last step's force on the floor and its contact count (one RESULT line)."""
import json
import os

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

shape = json.loads(os.environ.get("TALUS_SCENARIO", "{}")).get("shape", "facet")
O.periodic = True
O.cell.setBox(1.0, 1.0, 1.0)
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.4, density=2600))
if shape == "facet":
    # A floor of triangles at z = 0.1 over x in [-0.2, 1.0], y in [0.05, 0.85], some out of the
    # cell (each under half the cell wide, as Yade's collider needs).
    floor = []
    for x in (-0.2, 0.2, 0.6):
        for y in (0.05, 0.45):
            a, b, c, d = (x, y, 0.1), (x + 0.4, y, 0.1), (x + 0.4, y + 0.4, 0.1), (x, y + 0.4, 0.1)
            floor += O.bodies.append([facet([a, b, c]), facet([a, c, d])])
    bounds = [Bo1_Facet_Aabb()]
    geometry = Ig2_Facet_Sphere_ScGeom()
    bigger = False
else:
    # A floor box much wider than the cell (Yade's allowBiggerThanPeriod).
    floor = [O.bodies.append(box((0.5, 0.5, 0.05), (50.0, 50.0, 0.05), fixed=True))]
    bounds = [Bo1_Box_Aabb()]
    geometry = Ig2_Box_Sphere_ScGeom()
    bigger = True
spheres = O.bodies.append([sphere((1.85, 0.3, 0.17), 0.05), sphere((-0.8, 0.5, 0.2), 0.06),
                           sphere((0.1, 1.7, 0.16), 0.04), sphere((0.95, 0.55, 0.18), 0.05)])
for i, v in zip(spheres, [(-1.0, 0.2, 0.0), (0.8, 0.0, -0.5), (0.3, -0.6, 0.0), (0.7, 0.1, 0.0)]):
    O.bodies[i].state.vel = v
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), *bounds], allowBiggerThanPeriod=bigger),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), geometry], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2),
]
O.dt = 2e-5
positions = []
for k in range(40):
    O.run(500, True)
    positions.append([float(x) for i in spheres for x in O.bodies[i].state.pos])
force = [float(x) for i in floor for x in O.forces.f(i)]
contacts = sum(1 for i in O.interactions if i.isReal)
print("RESULT " + json.dumps({"positions": positions, "force": force, "contacts": contacts}))
