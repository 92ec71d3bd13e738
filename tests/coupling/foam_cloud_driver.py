"""DEM side of the envelope-method tests (tests/coupling/test_foam_envelope_method.py), run as its
own process (it starts MPI and spawns talusVolumeAveragedFoam):
    foam_cloud_driver.py CASE OUT.json [--n N] [--procs P] [--exchanges K] [--wall | --centres]

N spheres (r = 0.35 mm, seed 1) at random positions inside the meshed CASE's box (45 x 45 x 90 mm,
cfd_settling_sphere's) with random velocities, no contacts, one DEM step per fluid step; --wall:
every sphere within one cell (4.5 mm) of the wall x = -22.5 mm; --centres: one sphere at each
centre of the 10 x 10 x 20 cells (a uniform particle field). Writes the forces of each exchange
and the positions and radii to OUT.json."""
import argparse
import json

import numpy as np

from talus.coupling import FoamCoupling
from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere

parser = argparse.ArgumentParser()
parser.add_argument("case")
parser.add_argument("out")
parser.add_argument("--n", type=int, default=3000)
parser.add_argument("--procs", type=int, default=1)
parser.add_argument("--exchanges", type=int, default=1)
parser.add_argument("--wall", action="store_true")
parser.add_argument("--centres", action="store_true")
args = parser.parse_args()

RADIUS = 3.5e-4
rng = np.random.default_rng(1)
low, high = np.array([-0.022, -0.022, 0.001]), np.array([0.022, 0.022, 0.089])
if args.wall:
    high[0] = -0.018
x = rng.uniform(low, high, size=(args.n, 3))
v = rng.uniform(-0.02, 0.02, size=(args.n, 3))
if args.centres:
    cells, h = (10, 10, 20), 0.0045
    x = np.array([-0.0225, -0.0225, 0.0]) + h * (
        np.stack(np.meshgrid(*[np.arange(k) for k in cells], indexing="ij"), -1).reshape(-1, 3) + 0.5)
    v = np.zeros_like(x)
s = Scene()
s.materials.append(FrictMat(density=2500.0))
s.bodies.append([sphere(tuple(p), RADIUS) for p in x])
for b, vi in zip(s.bodies, v):
    b.state.vel = tuple(vi)
s.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.0)]
s.dt = 2e-5
coupling = FoamCoupling(s, args.case, rhoFluid=1000.0, nu=1e-3, gravity=(0, 0, -9.81), nProcs=args.procs, solver="talusVolumeAveragedFoam",
                        timeout=60).start()
forces = []
for _ in range(args.exchanges):
    s.run(coupling.substeps, True)
    forces.append(coupling.lastForces.tolist())
coupling.stop()
json.dump({"forces": forces, "positions": x.tolist(), "radius": RADIUS, "fluidProcs": coupling.link.fluidProcs},
          open(args.out, "w"))
