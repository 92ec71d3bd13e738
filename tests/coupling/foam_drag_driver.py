"""DEM side of tests/coupling/test_foam_coupling.py, run as its own process (it starts MPI and
spawns the fluid solver):
    foam_drag_driver.py CASE OUT.json [--nu NU] [--procs P] [--outside] [--small] [--interval SECONDS]
                        [--solver NAME] [--exchanges K] [--checkpoint FILE] [--leave] [--implicit]
                        [--density RHO] [--newton-gravity GZ] [--reversed] [--timeout SECONDS]
                        [--stall-after K]

Two spheres moving in the fluid at rest of CASE; after two (K) exchanges it writes the forces and
the particles' velocities of each exchange, their radii, the fluid step and where the time went
(FoamCoupling.times) to OUT.json."""
import argparse
import json
import os
import time

import numpy as np

from talus.coupling import FoamCoupling
from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere

parser = argparse.ArgumentParser()
parser.add_argument("case")
parser.add_argument("out")
parser.add_argument("--nu", type=float, default=1e-3)
parser.add_argument("--procs", type=int, default=1)
parser.add_argument("--outside", action="store_true", help="the second sphere starts out of the box")
parser.add_argument("--small", action="store_true", help="radii / 10: relaxation time below the fluid step")
parser.add_argument("--interval", type=float, default=None, help="FoamCoupling couplingInterval")
parser.add_argument("--solver", default="talusPointForceFoam")
parser.add_argument("--exchanges", type=int, default=2)
parser.add_argument("--checkpoint", default=None, help="FoamCoupling checkpoint file (every 10 exchanges)")
parser.add_argument("--implicit", action="store_true", help="FoamCoupling implicitDrag")
parser.add_argument("--density", type=float, default=2500.0, help="particle density")
parser.add_argument("--leave", action="store_true", help="the second sphere is driven up through the top at 5 m/s")
parser.add_argument("--reversed", action="store_true", help="couple the bodies as ids=[1, 0] (not one run of ids)")
parser.add_argument("--timeout", type=float, default=20.0, help="FoamCoupling timeout")
parser.add_argument("--stall-after", type=int, default=None,
                    help="after K exchanges the DEM process sleeps (in Python, between two exchanges) for good")
parser.add_argument("--newton-gravity", type=float, default=-9.81,
                    help="the NewtonIntegrator's gravity along z (FoamCoupling is told -9.81)")
args = parser.parse_args()
case, out, nu, n_procs, outside = args.case, args.out, args.nu, args.procs, args.outside

s = Scene()
s.materials.append(FrictMat(density=args.density))
scale = 0.1 if args.small else 1.0
s.bodies.append([sphere((0.0011, -0.0013, 0.0031), 5e-4 * scale),
                 sphere((-0.002, 0.0021, 0.0172 if outside else 0.0072), 6e-4 * scale)])
s.bodies[0].state.vel = (0.01, -0.02, -0.05)
s.bodies[1].state.vel = (-0.03, 0.0, 0.02)
if args.leave:
    s.bodies[1].state.blockedDOFs = "xyz"
    s.bodies[1].state.vel = (0.0, 0.0, 5.0)
s.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, args.newton_gravity), damping=0.0)]
s.dt = 1e-6
coupling = FoamCoupling(s, case, rhoFluid=1000.0, nu=nu, gravity=(0, 0, -9.81), nProcs=n_procs, timeout=args.timeout,
                        couplingInterval=args.interval, solver=args.solver, checkpoint=args.checkpoint,
                        checkpointInterval=10, implicitDrag=args.implicit, ids=[1, 0] if args.reversed else None)
coupling.start()
forces, velocities = [], []
print("DEM process", os.getpid(), "started the fluid", flush=True)
for k in range(args.exchanges):
    if k == args.stall_after:
        print("DEM process stalls", flush=True)
        time.sleep(1e6)
    velocities.append(s.velocities()[:2].tolist())  # as the next exchange sends them
    s.run(coupling.substeps, True)
    forces.append(coupling.lastForces.tolist())
coupling.stop()
json.dump({"forces": forces, "velocities": velocities, "radii": s.radii()[:2].tolist(),
           "masses": s.masses()[:2].tolist(),
           "positions": s.positions()[:2].tolist(), "substeps": coupling.substeps, "dt": s.dt, "fluidProcs": coupling.link.fluidProcs,
           "nCells": coupling.link.nCells, "times": vars(coupling.times)}, open(out, "w"))
