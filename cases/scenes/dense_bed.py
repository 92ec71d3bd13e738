"""A dense, contact-dominated bed for speed comparisons; the same file runs in Yade and in Talus.

    yade -n -j1 -x dense_bed.py PACKING STEPS     |   talus run dense_bed.py PACKING STEPS

PACKING is a text file written by cases/11_bench_dense.py: a first line `dt young density box_x
box_y` and then `x y z r` per sphere. Spheres of FrictMat (poisson 0.3, friction 0.5 rad) rest
on the floor of a box of five walls (linear Cundall-Strack with Coulomb friction, Cundall damping
0.2, gravity -9.81 along z, Verlet skin half the smallest radius, Yade's default). One step
builds the contacts, then STEPS steps are timed. Prints `TIMED <steps> <seconds> <contacts>`.
"""
import sys
import time

try:
    O  # noqa: B018  (defined when Yade runs the script)
    import yade.utils as _utils
    _wall = _utils.wall
except NameError:
    from talus.dem import *  # noqa: F401,F403
    _wall = wall

packing_file, steps = sys.argv[1], int(sys.argv[2])
with open(packing_file) as source:
    dt, young, density, box_x, box_y = (float(v) for v in source.readline().split())
    spheres = [tuple(float(v) for v in line.split()) for line in source if line.strip()]

material = O.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))
O.bodies.append([sphere((x, y, z), r, material=material) for x, y, z, r in spheres])
O.bodies.append([_wall(0, axis=2, sense=1), _wall(0, axis=0, sense=1), _wall(box_x, axis=0, sense=-1),
                 _wall(0, axis=1, sense=1), _wall(box_y, axis=1, sense=-1)])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = dt
O.run(1, True)
start = time.perf_counter()
O.run(steps, True)
seconds = time.perf_counter() - start
contacts = sum(1 for i in O.interactions if i.isReal) if hasattr(O, "interactions") else O._cpp.realContactCount()
print(f"TIMED {steps} {seconds:.6f} {contacts}")
