"""A small periodic RVE driven in short calls, as a FEM x DEM Gauss point drives it, for speed
comparisons; the same file runs in Yade and in Talus.

    yade -n -j1 -x rve.py PACKING CALLS STEPS   |   talus run rve.py PACKING CALLS STEPS

PACKING is a text file written by cases/bench/dem_bench_kinds.py: a first line `dt young density sx sy
sz` (the cell's sides) and then `x y z r` per sphere (a dense packing, its contacts loaded).
FrictMat (poisson 0.3, friction 0.5 rad), linear Cundall-Strack with Coulomb friction, Cundall
damping 0.2, no gravity. Each of CALLS calls sets the cell's velocity gradient for a small strain
increment (1e-4 shortening along x, half of it stretching y and z, a little shear), runs STEPS
steps (O.run(STEPS, True)) and reads the stress (getStress). One step builds the contacts first.
Prints `TIMED <calls x steps> <seconds> <contacts> <cpu seconds>` (the CPU time of this process
over the calls).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))   # bench_scene.py, under Yade's -x too
from bench_scene import periodic_linear, read_packing, timed  # noqa: E402

try:
    O  # noqa: B018  (defined when Yade runs the script)
except NameError:
    from talus.dem import *  # noqa: F401,F403

packing_file, calls, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
(dt, young, density, sx, sy, sz), spheres, _ = read_packing(packing_file)

periodic_linear(O, (sx, sy, sz), young, density, spheres)
O.dt = dt
rate = 1.0 / (steps * dt)


def calls_of_steps():
    for _ in range(calls):
        O.cell.velGrad = Matrix3(-1e-4 * rate, 2e-5 * rate, 0, 0, 5e-5 * rate, 0, 0, 0, 5e-5 * rate)
        O.run(steps, True)
        getStress()


timed(O, calls * steps, calls_of_steps)
