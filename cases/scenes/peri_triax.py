"""Isotropic compaction of a periodic cloud by PeriTriaxController, for speed comparisons; the
same file runs in Yade and in Talus.

    yade -n -j1 -x peri_triax.py PACKING STEPS   |   talus run peri_triax.py PACKING STEPS

PACKING is a text file written by cases/bench/dem_bench_kinds.py: a first line `dt young density size`
(the cubic cell's side) and then `x y z r` per sphere (a loose cloud). FrictMat (poisson 0.3,
friction 0.5 rad), linear Cundall-Strack with Coulomb friction, Cundall damping 0.2, no gravity;
PeriTriaxController as in the periodic triaxial tutorial (goal -100 kPa on the three axes,
dynCell, maxStrainRate 10, maxUnbalanced 0.1, relStressTol 1e-3), which compacts the cloud and
then holds it. One step builds the contacts, then STEPS steps are timed. Prints `TIMED <steps>
<seconds> <contacts> <cpu seconds>` (the CPU time of this process over the timed steps).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # bench_scene.py, under Yade's -x too
from bench_scene import periodic_linear, read_packing, timed  # noqa: E402

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

packing_file, steps = sys.argv[1], int(sys.argv[2])
(dt, young, density, size), spheres, _ = read_packing(packing_file)

periodic_linear(O, (size, size, size), young, density, spheres,
                [PeriTriaxController(goal=(-1e5, -1e5, -1e5), stressMask=7, dynCell=True, maxStrainRate=(10, 10, 10),
                                     maxUnbalanced=0.1, relStressTol=1e-3)])
O.dt = dt
timed(O, steps)
