"""Random dense packings (Yade's ``pack.randomDensePack`` and ``pack.randomPeriPack``): a random
cloud in a periodic cell compressed by PeriIsoCompressor with Yade's settings, or a packing
remembered from an earlier run (``memoizeDb``), then, for randomDensePack, repeated over the
predicate's box and clipped by the predicate.

Where Talus differs from Yade on purpose: randomDensePack without ``spheresInCell`` (an
aperiodic packing) compresses a periodic cell holding as many spheres as Yade's TriaxialTest
would (0.6 of the box's volume) instead of running that test between six walls: the packing
has no wall layering at its faces and is made by the same code as the periodic one.

The memoization database is Yade's: an sqlite file with a table ``packings`` (radius, rRelFuzz,
dimx, dimy, dimz, N, timestamp, periodic, pack), the pack a pickled list of (centre, radius).
Talus writes the centres as plain tuples (Yade reads them) and reads Yade's (pickled minieigen
Vector3) without importing Yade; nothing else is unpickled. A packing is reused on Yade's
criteria (the smallest suitable one, scaled to the radius asked for); Talus compares the
relative radius fuzz as it is (Yade scales it with the radius, which only matters when the
radius differs).
"""

from __future__ import annotations

import io
import math
import os
import pickle
import sqlite3
import sys
import time

import numpy as np

from talus.dem.packing.pack import SpherePack, check_sphere_count, filterSpherePack
from talus.dem.split import shares

__all__ = ["randomDensePack", "randomPeriPack"]

# What Yade's randomDensePack / randomPeriPack compress with: FrictMat(young=30e9, poisson=.3,
# density=1e3) and PeriIsoCompressor(stresses=[-100e9, -1e8], charLen=2 radius, maxUnbalanced=1e-2).
_YOUNG, _POISSON, _DENSITY = 30e9, .3, 1e3
_STRESSES = (-100e9, -1e8)


def _compress(size, radius: float, rRelFuzz: float, num: int, seed: int, frictionAngle: float, damping: float,
              globalUpdateInt: int) -> SpherePack:
    """A periodic cloud in the cell ``size`` compressed as Yade's randomDensePack does, in a
    scene of its own (the user's scene is left alone)."""
    from talus.dem.control.controllers import PeriIsoCompressor
    from talus.dem.step.engines import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                                   InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                                   Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator)
    from talus.dem.core.materials import FrictMat
    from talus.dem.core.scene import PWaveTimeStep, Scene
    cloud = SpherePack()
    cloud.makeCloud((0, 0, 0), tuple(size), rMean=radius, rRelFuzz=rRelFuzz, num=num, periodic=True, seed=seed)
    scene = Scene()
    # Yade's compressor goes through a deep over-compression (its first stress), where contacts
    # overlap by more than Talus's safety limit; it is meant, and the packing relaxes afterwards
    scene.maxOverlapRatio = 2.0
    scene.materials.append(FrictMat(young=_YOUNG, poisson=_POISSON, density=_DENSITY, frictionAngle=frictionAngle))
    cloud.toSimulation(scene)
    done = []
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=.05 * radius),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                     [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     PeriIsoCompressor(charLen=2 * radius, stresses=_STRESSES, maxUnbalanced=1e-2,
                                       globalUpdateInt=globalUpdateInt, keepProportions=True,
                                       doneHook=lambda: done.append(scene.pause())),
                     NewtonIntegrator(damping=damping)]
    scene.dt = PWaveTimeStep(scene)
    maxIter = 1000000
    while not done:
        if scene.iter >= maxIter:
            raise RuntimeError(f"randomDensePack: the periodic compression did not finish in {maxIter} steps")
        scene.run(1000)
    packed = SpherePack()
    packed.fromSimulation(scene)
    packed.fromList([(scene.cell.wrap(c), r) for c, r in packed])
    packed.hSize = scene.cell.hSize
    return packed


# -- memoization ---------------------------------------------------------------------------------

class _PackUnpickler(pickle.Unpickler):
    """Reads the pickled packings of Yade's database: a minieigen Vector3 becomes a tuple;
    any other class is refused."""

    def find_class(self, module, name):
        if name == "Vector3" and module.split(".")[-1] in ("_minieigenHP", "minieigenHP", "minieigen", "_minieigen"):
            return lambda *xyz: tuple(float(x) for x in xyz)
        raise pickle.UnpicklingError(f"memoizeDb: a packing holds an unexpected object {module}.{name}")


def _store(memoizeDb, sp: SpherePack, radius: float, rRelFuzz: float, wantPeri: bool, fullDim, noPrint=False):
    if not memoizeDb:
        return
    blob = pickle.dumps([(tuple(float(x) for x in c), float(r)) for c, r in sp], protocol=2)
    dims = sp.cellSize if wantPeri else fullDim
    # under mpirun the packing once, by process 0, the others waiting (a later search finds it)
    shares.once(_insert, memoizeDb, radius, rRelFuzz, dims, len(sp), wantPeri, blob)
    if not noPrint:
        print("Packing saved to the database", memoizeDb)


def _insert(memoizeDb, radius, rRelFuzz, dims, count, wantPeri, blob):
    with sqlite3.connect(memoizeDb) as db:
        db.execute("create table if not exists packings (radius real, rRelFuzz real, dimx real, dimy real, "
                   "dimz real, N integer, timestamp real, periodic integer, pack blob)")
        db.execute("insert into packings values (?,?,?,?,?,?,?,?,?)",
                   (radius, rRelFuzz, *(float(d) for d in dims), count, time.time(), int(wantPeri), blob))
    db.close()


def _find(memoizeDb, radius, rRelFuzz, x1, y1, z1, fullDim, wantPeri, fillPeriodic, spheresInCell, memoDbg=False,
          noPrint=False):
    """The smallest suitable packing of the database (scaled to ``radius``), or None."""
    say = print if memoDbg and not noPrint else (lambda *a: None)
    if not memoizeDb or not os.path.exists(memoizeDb):
        if memoizeDb:
            say(f"Database {memoizeDb} does not exist.")
        return None
    db = sqlite3.connect(memoizeDb)
    try:
        try:
            rows = db.execute("select radius, rRelFuzz, dimx, dimy, dimz, N, timestamp, periodic from packings "
                              "order by N").fetchall()
        except sqlite3.DatabaseError as e:
            raise RuntimeError(f"memoizeDb: {memoizeDb} is not a packing database of randomDensePack ({e})") from None
        for R, fuzz, X, Y, Z, N, stamp, isPeri in rows:
            scale = radius / R
            X, Y, Z = X * scale, Y * scale, Z * scale
            say(f"Considering packing (radius={R:g}±{fuzz:g}, N={N}, dim={X:g}×{Y:g}×{Z:g}, "
                f"{'periodic' if isPeri else 'non-periodic'}, scale={scale:g})")
            if wantPeri and not isPeri:
                say("REJECT: is not periodic, which is requested.")
                continue
            if wantPeri and not 0.6 <= X / x1 <= 0.9:
                say("REJECT: initSize differs too much from scaled packing size.")
                continue
            if (rRelFuzz == 0) != (fuzz == 0) or (rRelFuzz != 0 and abs((fuzz - rRelFuzz) / rRelFuzz) > 1e-2):
                say(f"REJECT: radius fuzz differs too much ({fuzz:g}, {rRelFuzz:g} desired)")
                continue
            if isPeri and wantPeri:
                if spheresInCell > N and spheresInCell > 0:
                    say("REJECT: Number of spheres in the packing too small")
                    continue
                if abs((y1 / x1) / (Y / X) - 1) > 0.3 or abs((z1 / x1) / (Z / X) - 1) > 0.3:
                    say("REJECT: proportions differ too much from what is desired.")
                    continue
            elif X < fullDim[0] or Y < fullDim[1] or Z < fullDim[2]:
                say("REJECT: not large enough")
                continue
            say("ACCEPTED")
            if not noPrint:
                print(f"Found suitable packing in {memoizeDb} (radius={R:g}±{fuzz:g}, N={N}, dim={X:g}×{Y:g}×{Z:g}, "
                      f"{'periodic' if isPeri else 'non-periodic'}, scale={scale:g}), created "
                      f"{time.asctime(time.gmtime(stamp))}")
            blob = db.execute("select pack from packings where timestamp=?", (stamp,)).fetchone()[0]
            sp = SpherePack(_PackUnpickler(io.BytesIO(blob)).load())
            sp.scale(scale)
            if isPeri and wantPeri:
                sp.cellSize = (X, Y, Z)
                if fillPeriodic:
                    sp.cellFill(fullDim)
            return sp
        return None
    finally:
        db.close()


# -- the two generators --------------------------------------------------------------------------

def randomPeriPack(radius: float, initSize, rRelFuzz: float = 0.0, memoizeDb=None, noPrint: bool = False,
                   seed: int = -1) -> SpherePack:
    """A dense periodic packing: the cell ``initSize`` filled with as many spheres of radius
    ``radius`` (1 +- ``rRelFuzz``) as makeCloud places, compressed (Yade's randomPeriPack).
    Returns the SpherePack with its cell."""
    size = np.asarray(initSize, float).reshape(3)
    if not radius > 0 or np.any(size <= 0):
        raise ValueError(f"randomPeriPack: radius and initSize must be positive, got {radius}, {tuple(size)}")
    sp = _find(memoizeDb, radius, rRelFuzz, *size, fullDim=(0, 0, 0), wantPeri=True, fillPeriodic=False,
               spheresInCell=-1, memoDbg=True, noPrint=noPrint)
    if sp is not None:
        return sp
    sp = _compress(size, radius, rRelFuzz, -1, seed, frictionAngle=.1, damping=.8, globalUpdateInt=20)
    _store(memoizeDb, sp, radius, rRelFuzz, True, (0, 0, 0), noPrint)
    return sp


def randomDensePack(predicate, radius: float, material=-1, dim=None, cropLayers: int = 0, rRelFuzz: float = 0.,
                    spheresInCell: int = 0, memoizeDb=None, useOBB: bool = False, memoDbg: bool = False, color=None,
                    returnSpherePack=None, seed: int = -1):
    """A random dense packing of spheres of ``radius`` (1 +- ``rRelFuzz``) filling ``predicate``
    (Yade's randomDensePack). With ``spheresInCell`` a periodic cell of about that many spheres
    is compressed and repeated over the predicate's box (or ``dim``); without, a cell of the
    whole box (grown by ``cropLayers`` layers of spheres) is. Then the spheres inside the
    predicate are kept (:func:`filterSpherePack`: ``returnSpherePack``, ``material``,
    ``color``). ``memoizeDb``: an sqlite file of packings to reuse and to add to (periodic
    ones are reused, as in Yade). ``useOBB`` (an oriented box for a gts surface) is not
    available: it raises."""
    if useOBB:
        raise NotImplementedError("randomDensePack: useOBB (an oriented bounding box of a gts surface) is not "
                                  "available in Talus; leave it False")
    if not radius > 0:
        raise ValueError(f"randomDensePack: radius must be positive, got {radius}")
    dim = np.asarray(predicate.dim() if dim is None else dim, float).reshape(3)
    if not np.all(np.isfinite(dim)):
        raise ValueError("randomDensePack: the predicate is unbounded; give dim")
    check_sphere_count(0.6 * np.prod(dim + 4 * cropLayers * radius) / (4 / 3 * math.pi * radius ** 3), "randomDensePack")
    wantPeri = spheresInCell > 0
    if wantPeri:
        fullDim = dim
        N = spheresInCell
    else:
        fullDim = dim + 4 * cropLayers * radius
        # as many spheres as Yade's TriaxialTest would put in the box: 0.6 of its volume
        N = int(0.6 * np.prod(fullDim) / (4 / 3 * math.pi * radius ** 3))
    # Yade's initial cell: N spheres at a cloud porosity of 0.75, of the box's proportions, at
    # least 8 largest radii wide (the number of spheres grows with the cell then)
    beta, gamma = fullDim[1] / fullDim[0], fullDim[2] / fullDim[0]
    x1 = radius * (N / 0.25 * 4 / 3 * math.pi / (beta * gamma)) ** (1 / 3)
    size0 = np.array([x1, beta * x1, gamma * x1])
    size = np.maximum(size0, 8 * radius * (1 + rRelFuzz))
    num = int(N * np.prod(size) / np.prod(size0)) if wantPeri else N
    if wantPeri:
        sp = _find(memoizeDb, radius, rRelFuzz, *size, fullDim=fullDim, wantPeri=True, fillPeriodic=True,
                   spheresInCell=spheresInCell, memoDbg=memoDbg)
        if sp is not None:
            return filterSpherePack(predicate, sp, material=material, returnSpherePack=returnSpherePack)
        print("No suitable packing in database found, running PERIODIC compression")
        sys.stdout.flush()
    sp = _compress(size, radius, rRelFuzz, num, seed, frictionAngle=.5, damping=.6, globalUpdateInt=5)
    _store(memoizeDb, sp, radius, rRelFuzz, wantPeri, fullDim)
    sp.cellFill(fullDim)
    kw = {} if color is None else {"color": color}
    return filterSpherePack(predicate, sp, material=material, returnSpherePack=returnSpherePack, **kw)
