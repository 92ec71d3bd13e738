"""A rotating drum, for speed comparisons; the same file runs in Yade and in Talus.

    yade -n -j1 -x drum.py PACKING STEPS [SAVE]   |   talus run drum.py PACKING STEPS [SAVE]

PACKING is a text file written by cases/bench/dem_bench_kinds.py: a first line `dt young density
omega`, then the drum's triangles (`F x1 y1 z1 x2 y2 z2 x3 y3 z3`: a closed cylinder of facets,
axis z through the origin) and the spheres (`S x y z r`, a lattice filling its lower part).
A RotationEngine turns the facets at omega rad/s about z; FrictMat (poisson 0.3, friction
0.5 rad), linear Cundall-Strack with Coulomb friction, Cundall damping 0.2, gravity -9.81 along
y. One step builds the contacts, then STEPS steps are timed. Prints `TIMED <steps> <seconds>
<contacts> <cpu seconds>` (the CPU time of this process over the timed steps). With SAVE, the
spheres where they end are written there as `S x y z r` lines (the case settles the bed with the
drum at rest, omega 0, and times the settled bed turning).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # bench_scene.py, under Yade's -x too
from bench_scene import frictional_bodies, read_packing, timed, write_spheres  # noqa: E402

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

packing_file, steps = sys.argv[1], int(sys.argv[2])
(dt, young, density, omega), spheres, triangles = read_packing(packing_file)
drum, balls = frictional_bodies(O, young, density, spheres, triangles)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    RotationEngine(ids=drum, rotationAxis=(0, 0, 1), angularVelocity=omega, rotateAroundZero=True, zeroPoint=(0, 0, 0)),
    NewtonIntegrator(damping=0.2, gravity=(0, -9.81, 0)),
]
O.dt = dt
timed(O, steps)
if len(sys.argv) > 3:
    write_spheres(O, sys.argv[3], balls)
