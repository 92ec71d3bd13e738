"""Settle a small random packing in a box of walls and print a hash of the final state
(run by test_threads.py with different OMP_NUM_THREADS). Options: --clumps (every other
sphere in a clump with its neighbour), --engines-one-by-one (Yade's sub-steps: each engine's
own run() in turn, instead of the scheduler's shared stages), --timing (O.timingEnabled), --verlet=D (the collider's verletDist; 0 re-detects at every
step), --moving-wall (the wall at x = 1 moves inwards at 5 cm/s), --lifted (the packing starts
0.1 above the floor), --other-engines (a PyRunner before the usual engines, gravity from a
GravityEngine between the loop and the integrator, and a PyRunner after them nudging a sphere
every 250 steps), --overlap-counts (two spheres overlapping by 1.5 radii, O.overlapStops
off: the run goes on and counts the steps with such an overlap), --energy (O.trackEnergy: the
energy terms printed too)."""
import hashlib
import sys

import numpy as np

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       GravityEngine, NewtonIntegrator, O, PWaveTimeStep, PyRunner, sphere, wall)

options = [a for a in sys.argv[1:] if a.startswith("--")]
numbers = [a for a in sys.argv[1:] if not a.startswith("--")]
steps = int(numbers[0]) if numbers else 3000
rng = np.random.default_rng(7)
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
O.bodies.append([wall(0, axis=2, sense=1), wall(0, axis=0, sense=1), wall(1, axis=0, sense=-1),
                 wall(0, axis=1, sense=1), wall(1, axis=1, sense=-1)])
grid = np.stack(np.meshgrid(np.arange(12), np.arange(12), np.arange(8), indexing="ij"), -1).reshape(-1, 3)
centres = (grid + 0.5) / 12 + rng.uniform(-0.005, 0.005, grid.shape)
if "--lifted" in options:
    centres[:, 2] += 0.1  # the cloud falls 0.1 (eight skins) onto the floor
radii = rng.uniform(0.025, 0.04, len(grid))
if "--clumps" in options:
    # neighbours along z: each pair one rigid body
    for k in range(0, len(grid) - 1, 2):
        r = min(radii[k], radii[k + 1], 0.5 * np.linalg.norm(centres[k + 1] - centres[k]))
        O.bodies.appendClumped([sphere(centres[k], r), sphere(centres[k + 1], r)])
else:
    O.bodies.append([sphere(c, r) for c, r in zip(centres, radii)])
if "--overlap-counts" in options:
    O.bodies[-1].state.pos = O.bodies[-2].state.pos + (0, 0, 0.5 * min(radii[-2:]))
    O.overlapStops = False
verlet = [float(a.split("=")[1]) for a in options if a.startswith("--verlet=")]
collider = InsertionSortCollider(verletDist=verlet[0]) if verlet else InsertionSortCollider()
O.engines = [ForceResetter(), collider,
             InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3)]
if "--other-engines" in options:
    calls = []

    def nudge():  # moves a sphere between steps: the skin must be checked again, not ahead
        O.bodies[len(O.bodies) - 1].state.pos += (0.002, 0, 0)

    O.engines = ([PyRunner(command="calls.append(O.iter)", iterPeriod=1)] + O.engines[:3]
                 + [GravityEngine(gravity=(0, 0, -9.81)), NewtonIntegrator(gravity=(0, 0, 0), damping=0.3),
                    PyRunner(command="nudge()", iterPeriod=250)])
O.dt = 0.5 * PWaveTimeStep()
if "--moving-wall" in options:
    O.velocities()[2] = (-0.05, 0, 0)  # the wall at x = 1 pushes into the packing
O.timingEnabled = "--timing" in options
O.trackEnergy = "--energy" in options
if "--engines-one-by-one" in options:
    O.subStepping = True   # a step is the engines' count plus two sub-steps: its start and its end
    for _ in range(steps * (len(O.engines) + 2)):
        O.step()
else:
    O.run(steps)
state = np.concatenate([O.positions().ravel(), O.velocities().ravel(), O.angular_velocities().ravel()])
print("contacts", O._cpp.realContactCount())
print("hash", hashlib.sha256(state.tobytes()).hexdigest())
print("fused", O.fusedSteps)
print("rebuilds", collider.rebuilds)
print("overlapSteps", O.overlapSteps)
if O.trackEnergy:
    print("energy", " ".join(f"{k}={v!r}" for k, v in sorted(O.energy.items())))
