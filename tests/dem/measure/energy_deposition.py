"""A damped, frictional deposition with the energy tracker on; prints the energies (as exact
reprs) so that runs with different thread counts can be compared. Usage: energy_deposition.py
[linear|viscoelastic|hertz] [steps] [m (m^3 spheres)]."""
import json
import sys

import numpy as np

from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_FrictPhys, Ip2_FrictMat_FrictMat_MindlinPhys,
                       Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       Law2_ScGeom_MindlinPhys_Mindlin, Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator,
                       PWaveTimeStep, Scene, ViscElMat, facet, sphere, wall)


def scene(law: str, m: int = 6, damping: float = 0.3, track: bool = True) -> Scene:
    """m^3 spheres falling from a loose grid into a box (facet floor, four walls)."""
    S = Scene()
    rng = np.random.default_rng(3)
    if law == "viscoelastic":
        S.materials.append(ViscElMat(tc=2e-3, en=0.5, et=0.5, frictionAngle=0.5, density=2600))
        laws = ([Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()])
    else:
        S.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
        laws = (([Ip2_FrictMat_FrictMat_MindlinPhys(en=0.5)], [Law2_ScGeom_MindlinPhys_Mindlin()]) if law == "hertz"
                else ([Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]))
    S.bodies.append([facet([(-0.1, -0.1, 0), (1.1, -0.1, 0), (1.1, 1.1, 0)]),
                     facet([(-0.1, -0.1, 0), (1.1, 1.1, 0), (-0.1, 1.1, 0)]),
                     wall(0, axis=0, sense=1), wall(1, axis=0, sense=-1), wall(0, axis=1, sense=1),
                     wall(1, axis=1, sense=-1)])
    grid = np.stack(np.meshgrid(np.arange(m), np.arange(m), np.arange(m), indexing="ij"), -1).reshape(-1, 3)
    centres = (grid + 0.5 + rng.uniform(-0.1, 0.1, grid.shape)) / m * np.array([1, 1, 1.5])
    S.bodies.append([sphere(c, r) for c, r in zip(centres, rng.uniform(0.3, 0.4, len(grid)) / m)])
    S.engines = [ForceResetter(), InsertionSortCollider(), InteractionLoop([], *laws),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=damping)]
    # Dashpot dissipation is taken with the half-step velocity the force used: first order in
    # dt / tc, so the visco-elastic and Hertz runs take finer steps.
    S.dt = {"linear": 0.5 * PWaveTimeStep(S), "viscoelastic": 4e-5, "hertz": 0.1 * PWaveTimeStep(S)}[law]
    S.trackEnergy = track
    return S


if __name__ == "__main__":
    law = sys.argv[1] if len(sys.argv) > 1 else "linear"
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 1500
    S = scene(law, m=int(sys.argv[3]) if len(sys.argv) > 3 else 6)
    S.run(steps)
    print("ENERGY " + json.dumps({k: repr(v) for k, v in S.energy.items()}))
    print("CONTACTS", S._cpp.realContactCount(), S._cpp.contactCount())
