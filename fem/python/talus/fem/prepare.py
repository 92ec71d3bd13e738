"""Preparing an RVE: a periodic packing consolidated to a target mean stress, saved as a
checkpoint (what the seed's prepareRVE.py does in Yade)."""

from __future__ import annotations

import os

import numpy as np


def prepareRVE(path: str | os.PathLike, size: float = 1.0, rMean: float = 0.1, rRelFuzz: float = 0.3, seed: int = 1,
               sigma: float = -1e5, young: float = 1e8, poisson: float = 0.3, friction: float = 0.5,
               compactionFriction: float | None = None, density: float = 2600, damping: float = 0.2,
               maxIter: int = 200000, planar: bool = False) -> dict:
    """Generate a periodic cloud of spheres (makeCloud) in a cube of edge ``size``, compact it
    isotropically to the mean stress ``sigma`` (compression negative) with PeriTriaxController,
    and save it to ``path`` (O.save). ``compactionFriction`` (default ``friction``): the friction
    angle during compaction (lower gives a denser packing); the contacts get ``friction``
    before saving. Returns the final stress, porosity, coordination and sphere count.

    ``planar``: the seed's 2D-like RVE (its prepareRVE.py): one layer of spheres in the plane
    z = const of a periodic cell 4 maximum diameters thick, moving only in that plane
    (blockedDOFs "zXY"), compacted in x and y only (the z edge is kept); for plane-strain
    Gauss points (2x2 gradients). Its stresses are per that cell thickness.

    The saved scene has velGrad 0 and trsf = I, so an RVE's strains count from this state.
    """
    from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                           Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, Matrix3,
                           NewtonIntegrator, PeriTriaxController, PWaveTimeStep, Scene, avgNumInteractions, pack,
                           porosity, setContactFriction)
    S = Scene()
    S.periodic = True
    phi0 = friction if compactionFriction is None else compactionFriction
    mat = FrictMat(young=young, poisson=poisson, frictionAngle=phi0, density=density)
    S.materials.append(mat)
    if planar:
        from talus.dem import sphere
        thickness = 8 * rMean * (1 + rRelFuzz)
        S.cell.hSize = Matrix3(*np.diag([size, size, thickness]).ravel())
        centres, radii = _flatCloud(size, rMean, rRelFuzz, seed)
        S.bodies.append([sphere((x, y, thickness / 2), r) for (x, y), r in zip(centres, radii)])
        for b in S.bodies:
            b.state.blockedDOFs = "zXY"
    else:
        sp = pack.SpherePack()
        sp.makeCloud((0, 0, 0), (size,) * 3, rMean=rMean, rRelFuzz=rRelFuzz, periodic=True, seed=seed)
        sp.toSimulation(scene=S)
    done = {}
    goal, mask, rate = ((sigma, sigma, 0.0), 3, (10, 10, 0)) if planar else ((sigma,) * 3, 7, (10,) * 3)
    triax = PeriTriaxController(goal=goal, stressMask=mask, dynCell=True, maxStrainRate=rate,
                                maxUnbalanced=1e-3, relStressTol=1e-3, doneHook=lambda: (done.setdefault("iter", S.iter),
                                                                                         S.pause()))
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 triax, NewtonIntegrator(damping=damping)]
    S.dt = 0.5 * PWaveTimeStep(scene=S)
    S.run(maxIter, True)
    if not done:
        raise RuntimeError(f"prepareRVE: the packing did not reach {sigma} Pa within {maxIter} steps "
                           f"(stress {triax.stress}); raise maxIter")
    if compactionFriction is not None and compactionFriction != friction:
        mat.frictionAngle = friction
        setContactFriction(friction, scene=S)
    S.engines = S.engines[:3] + S.engines[4:]
    S.cell.velGrad = Matrix3.Zero
    S.cell.trsf = Matrix3.Identity
    S.save(os.fspath(path))
    return {"stress": [float(x) for x in triax.stress], "porosity": float(porosity(scene=S)),
            "coordination": float(avgNumInteractions(scene=S)), "spheres": len(S.bodies), "iter": int(S.iter),
            "dt": float(S.dt)}


def _flatCloud(size: float, rMean: float, rRelFuzz: float, seed: int, fill: float = 0.55, tries: int = 100000):
    """Random non-overlapping disks (centres, radii) in the periodic square of edge `size`,
    added one by one until they cover `fill` of the area (or `tries` placements failed)."""
    rng = np.random.default_rng(seed)
    centres, radii, covered = np.zeros((0, 2)), np.zeros(0), 0.0
    for _ in range(tries):
        if covered >= fill * size * size:
            break
        r = rMean * (1 + rRelFuzz * rng.uniform(-1, 1))
        p = rng.uniform(0, size, 2)
        d = centres - p
        d -= size * np.round(d / size)                  # nearest periodic image
        if len(radii) and np.any(np.hypot(d[:, 0], d[:, 1]) < radii + r):
            continue
        centres, radii = np.vstack([centres, p]), np.append(radii, r)
        covered += np.pi * r * r
    return centres, radii


def exportRVE(path: str | os.PathLike, jsonPath: str | os.PathLike | None = None) -> dict:
    """The packing of an RVE file as plain data (for Yade or another code): cell edges
    ``hSize`` (rows of the matrix), sphere centres wrapped into the cell, radii, the first
    material's FrictMat parameters and the time step. Contact history is not exported: a code
    building the packing from it starts with fresh contacts. Written to ``jsonPath`` if given."""
    import json

    from talus.dem import Scene
    S = Scene()
    S.load(os.fspath(path))
    if not S.periodic:
        raise ValueError(f"exportRVE: '{path}' is not periodic")
    h = np.array(S.cell.hSize)
    radii = S.radii()
    spheres = S.sphere_ids()
    frac = np.linalg.solve(h, S.positions()[spheres].T).T
    pos = (h @ (frac - np.floor(frac)).T).T
    m = S.materials[0]
    data = {"hSize": h.tolist(), "pos": pos.tolist(), "radius": radii[spheres].tolist(), "dt": float(S.dt),
            "young": float(m.young), "poisson": float(m.poisson), "frictionAngle": float(m.frictionAngle),
            "density": float(m.density)}
    if jsonPath is not None:
        with open(jsonPath, "w") as f:
            json.dump(data, f)
    return data
