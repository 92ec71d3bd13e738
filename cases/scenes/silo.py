"""A silo discharging through its floor's orifice, for speed comparisons; the same file runs in
Yade and in Talus.

    yade -n -j1 -x silo.py PACKING STEPS [SAVE]   |   talus run silo.py PACKING STEPS [SAVE]

PACKING is a text file written by cases/bench/dem_bench_kinds.py: a first line `dt young density exit_z`,
then the silo's triangles (`F x1 y1 z1 x2 y2 z2 x3 y3 z3`: a square box of facets open at the top,
its floor with a square orifice) and the spheres (`S x y z r`, a loose lattice filling it).
FrictMat (poisson 0.3, friction 0.5 rad), Hertz-Mindlin, Cundall damping 0.2, gravity -9.81
along z. Every 100 steps a PyRunner erases the spheres that have fallen below exit_z. One step
builds the contacts, then STEPS steps are timed. Prints `TIMED <steps> <seconds> <spheres left>
<cpu seconds>` (the CPU time of this process over the timed steps). With SAVE, the spheres
left are written there as `S x y z r` lines (the case settles the fill with the orifice plugged).
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
(dt, young, density, exit_z), spheres, triangles = read_packing(packing_file)
falling = set(frictional_bodies(O, young, density, spheres, triangles)[1])


def eraseFallen():
    gone = [i for i in falling if O.bodies[i].state.pos[2] < exit_z]
    for i in gone:
        O.bodies.erase(i)
        falling.discard(i)


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys()],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
    PyRunner(command="eraseFallen()", iterPeriod=100),
]
O.dt = dt
timed(O, steps, figure=lambda O: len(falling))
if len(sys.argv) > 3:
    write_spheres(O, sys.argv[3], sorted(falling))
