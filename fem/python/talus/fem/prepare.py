"""Preparing an RVE: a periodic packing consolidated to a target mean stress, saved as a
checkpoint (what the seed's prepareRVE.py does in Yade)."""

from __future__ import annotations

import os

import math

import numpy as np


def prepareRVE(path: str | os.PathLike, size: float = 1.0, rMean: float = 0.1, rRelFuzz: float = 0.3, seed: int = 1,
               sigma: float = -1e5, young: float = 1e8, poisson: float = 0.3, friction: float = 0.5,
               compactionFriction: float | None = None, density: float = 2600, damping: float = 0.2,
               maxIter: int = 200000, planar: bool = False, removeShear: bool = False,
               shearTol: float = 1e-3) -> dict:
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

    PeriTriaxController controls the normal stresses only: the packing keeps a residual shear
    stress (a few percent of the mean stress for a few hundred particles), which a Gauss point
    then carries as an anisotropy. The returned ``shear`` is the largest |sym(stress)_ij|, i != j
    (in plane for ``planar``), relative to |mean normal stress| of the controlled axes.
    ``removeShear``: after the compaction, shear the cell against that stress (the shear
    stiffness from the contact tangent; symmetric velocity gradients over 200 steps, then 200
    steps of relaxation; the normal stresses kept by the controller) until ``shear`` is below
    ``shearTol`` or 30 corrections are made (``shearCorrections``); ``shearBefore`` is the value
    before.
    """
    from talus.dem import (FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop,
                           Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, Matrix3,
                           NewtonIntegrator, PeriTriaxController, PWaveTimeStep, Scene, avgNumInteractions,
                           porosity, setContactFriction)
    from talus.dem.packing import pack
    for name, value in (("size", size), ("rMean", rMean), ("young", young), ("density", density)):
        if not 0 < float(value) < math.inf:
            raise ValueError(f"prepareRVE: {name} must be positive and finite, got {value!r}")
    if not -math.inf < float(sigma) < 0:
        raise ValueError(f"prepareRVE: sigma (the consolidation stress, compression negative) must be negative "
                         f"and finite, got {sigma!r}")
    if not 0 <= float(rRelFuzz) < 1:
        raise ValueError(f"prepareRVE: rRelFuzz must be in [0, 1), got {rRelFuzz!r}")
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
    axes = [(0, 1)] if planar else [(1, 2), (0, 2), (0, 1)]
    before, corrections = _residualShear(S, axes, planar), 0
    if removeShear:
        corrections = _removeShear(S, triax, axes, planar, shearTol, damping)
    if compactionFriction is not None and compactionFriction != friction:
        mat.frictionAngle = friction
        setContactFriction(friction, scene=S)
    S.engines = S.engines[:3] + S.engines[4:]
    S.cell.velGrad = Matrix3.Zero
    S.cell.trsf = Matrix3.Identity
    S.save(os.fspath(path))
    return {"stress": [float(x) for x in triax.stress], "porosity": float(porosity(scene=S)),
            "coordination": float(avgNumInteractions(scene=S)), "spheres": len(S.bodies), "iter": int(S.iter),
            "dt": float(S.dt), "shear": _residualShear(S, axes, planar), "shearBefore": before,
            "shearCorrections": corrections}


def _residualShear(S, axes, planar: bool) -> float:
    from talus.dem import getStress
    s = np.asarray(getStress(scene=S))
    n = 2 if planar else 3
    mean = abs(np.trace(s[:n, :n]) / n)
    return float(max(abs(0.5 * (s[i, j] + s[j, i])) for i, j in axes) / max(mean, 1e-300))


def _removeShear(S, triax, axes, planar: bool, tol: float, damping: float, steps: int = 200,
                 maxCorrections: int = 30) -> int:
    """Shear the cell against the residual shear stress (see prepareRVE); returns the number of
    corrections made. The controller keeps the normal stresses meanwhile (it drives the
    diagonal of the velocity gradient only)."""
    from talus.dem import Matrix3, getStress, getStressAndTangent
    voigt = {(1, 2): 3, (0, 2): 4, (0, 1): 5}
    triax.doneHook = ""
    for k in range(maxCorrections):
        if _residualShear(S, axes, planar) < tol:
            return k
        s = np.asarray(getStress(scene=S))
        _, C = getStressAndTangent(scene=S)
        idx = [voigt[a] for a in axes]
        tau = np.array([0.5 * (s[i, j] + s[j, i]) for i, j in axes])
        gamma = -np.linalg.solve(np.asarray(C)[np.ix_(idx, idx)], tau)   # engineering shear strains
        L = np.zeros((3, 3))
        for (i, j), g in zip(axes, gamma):
            L[i, j] = L[j, i] = 0.5 * g / (steps * S.dt)
        for _ in range(steps):       # the controller rewrites the diagonal every step
            v = np.array(S.cell.velGrad)
            for (i, j) in axes:
                v[i, j], v[j, i] = L[i, j], L[j, i]
            S.cell.velGrad = Matrix3(*v.ravel())
            S.run(1, True)
        v = np.array(S.cell.velGrad)
        for (i, j) in axes:
            v[i, j] = v[j, i] = 0.0
        S.cell.velGrad = Matrix3(*v.ravel())
        S.run(steps, True)
    return maxCorrections


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


def rveFromJSON(packing, path: str | os.PathLike, damping: float = 0.2, dt: float | None = None) -> dict:
    """An RVE checkpoint at ``path`` from a packing in :func:`exportRVE`'s JSON format (a path or
    the dict; e.g. written from Yade by a few lines reading ``O.cell.hSize``, the spheres'
    ``state.pos`` and ``shape.radius`` and the FrictMat): the periodic cell, the spheres (with
    ``blockedDOFs`` if the data has it, one string for all or one per sphere), Yade's sphere
    engine chain with ``damping``, the contacts detected and their forces computed (one step
    without motion), velGrad 0, trsf = I. Returns the packing data."""
    import json

    from talus.dem import ForceResetter, InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys
    from talus.dem import Law2_ScGeom_FrictPhys_CundallStrack, Matrix3, NewtonIntegrator, Scene
    import talus.dem as dem
    from talus.fem import rve_scene
    data = json.load(open(packing)) if not isinstance(packing, dict) else packing
    S = Scene()
    ns = {k: getattr(dem, k) for k in dir(dem) if not k.startswith("_")}
    ns["O"] = S
    rve_scene.buildRVEScene(ns, data, damping=damping, dt=dt)
    blocked = data.get("blockedDOFs")
    if blocked:
        ids = S.sphere_ids()
        for k, i in enumerate(ids):
            S.bodies[int(i)].state.blockedDOFs = blocked if isinstance(blocked, str) else blocked[k]
    S.engines = [ForceResetter(), InsertionSortCollider(),
                 InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()])]
    S.run(1, True)      # contacts and forces, nothing moves
    S.engines = S.engines + [NewtonIntegrator(damping=damping)]
    S.cell.velGrad = Matrix3.Zero
    S.cell.trsf = Matrix3.Identity
    S.save(os.fspath(path))
    return data
