"""Compress a periodic cloud of 1200 spheres with a sheared velocity gradient and print a hash
of the final state (positions, velocities, spins and the cell); run by test_threads.py.
Option --engines-one-by-one: Yade's sub-steps, each engine's own run() in turn instead of the
scheduler's shared stages."""
import hashlib
import sys

import numpy as np

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, O,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator,
                       PWaveTimeStep)
from talus.dem.packing import pack

O.periodic = True
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
cloud = pack.SpherePack()
cloud.makeCloud((0, 0, 0), (1, 1, 1), rMean=0.04, rRelFuzz=0.2, num=1200, periodic=True, seed=3)
cloud.toSimulation()
O.engines = [ForceResetter(), InsertionSortCollider(),
             InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.2)]
O.cell.velGrad = np.array([[-0.5, 0.2, 0], [0, -0.5, 0], [0, 0, -0.5]])
O.dt = 0.5 * PWaveTimeStep()
if "--engines-one-by-one" in sys.argv:
    O.subStepping = True   # a step is the engines' count plus two sub-steps: its start and its end
    for _ in range(2000 * (len(O.engines) + 2)):
        O.step()
else:
    O.run(2000)
state = np.concatenate([O.positions().ravel(), O.velocities().ravel(), O.angular_velocities().ravel(),
                        np.asarray(O.cell.hSize).ravel()])
print("contacts", O._cpp.realContactCount())
print("hash", hashlib.sha256(state.tobytes()).hexdigest())
print("fused", O.fusedSteps)
