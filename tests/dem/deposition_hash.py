"""Settle a small random packing in a box of walls and print a hash of the final state
(run by test_threads.py with different OMP_NUM_THREADS)."""
import hashlib
import sys

import numpy as np

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, O, PWaveTimeStep, sphere, wall)

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 3000
rng = np.random.default_rng(7)
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
O.bodies.append([wall(0, axis=2, sense=1), wall(0, axis=0, sense=1), wall(1, axis=0, sense=-1),
                 wall(0, axis=1, sense=1), wall(1, axis=1, sense=-1)])
grid = np.stack(np.meshgrid(np.arange(12), np.arange(12), np.arange(8), indexing="ij"), -1).reshape(-1, 3)
centres = (grid + 0.5) / 12 + rng.uniform(-0.005, 0.005, grid.shape)
radii = rng.uniform(0.025, 0.04, len(grid))
O.bodies.append([sphere(c, r) for c, r in zip(centres, radii)])
O.engines = [ForceResetter(), InsertionSortCollider(),
             InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3)]
O.dt = 0.5 * PWaveTimeStep()
O.run(steps)
state = np.concatenate([O.positions().ravel(), O.velocities().ravel(), O.angular_velocities().ravel()])
print("contacts", O._cpp.realContactCount())
print("hash", hashlib.sha256(state.tobytes()).hexdigest())
