"""Packings (Yade's ``pack`` module): regular lattices clipped by a predicate, random clouds
(``SpherePack.makeCloud``) and dense packings by compression (``compressedCloud``).

A predicate is a solid: ``pred(point, pad)`` says whether a sphere of radius ``pad`` centred at
``point`` lies inside, and ``pred.aabb()`` bounds it.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from talus import _dem
from talus.dem.bodies import BodySpec, sphere

__all__ = ["inSphere", "inAlignedBox", "regularHexa", "regularOrtho", "SpherePack", "compressedCloud"]


class inSphere:
    """The ball of ``radius`` around ``center``."""

    def __init__(self, center: Sequence[float], radius: float):
        if not radius > 0:
            raise ValueError(f"inSphere: radius must be positive, got {radius}")
        self.center, self.radius = np.asarray(center, dtype=float), float(radius)

    def __call__(self, point, pad: float = 0.0) -> bool:
        return float(np.linalg.norm(np.asarray(point) - self.center)) <= self.radius - pad

    def aabb(self):
        return self.center - self.radius, self.center + self.radius


class inAlignedBox:
    """The axis-aligned box between corners ``minAabb`` and ``maxAabb``."""

    def __init__(self, minAabb: Sequence[float], maxAabb: Sequence[float]):
        self.lo, self.hi = np.asarray(minAabb, dtype=float), np.asarray(maxAabb, dtype=float)
        if np.any(self.hi <= self.lo):
            raise ValueError(f"inAlignedBox: maxAabb must exceed minAabb, got {minAabb}, {maxAabb}")

    def __call__(self, point, pad: float = 0.0) -> bool:
        p = np.asarray(point)
        return bool(np.all(p - pad >= self.lo) and np.all(p + pad <= self.hi))

    def aabb(self):
        return self.lo, self.hi


def _lattice(predicate, radius: float, gap: float, kind: str, **kw) -> list[BodySpec]:
    if not radius > 0 or gap < 0:
        raise ValueError(f"regular packing: radius must be positive and gap >= 0, got {radius}, {gap}")
    a = 2 * radius + gap
    lo, hi = (np.asarray(x, dtype=float) for x in predicate.aabb())
    dim = hi - lo
    if not np.all(np.isfinite(dim)):
        raise ValueError("regular packing: the predicate's bounding box must be finite")
    spheres = []
    if kind == "hexa":
        # Simple hcp lattice: layers k at heights 2 sqrt(6)/3 k (a/2), rows j shifted by half a
        # sphere on odd (j + k), odd layers shifted by a third of a row.
        hy, hz = a * math.sqrt(3) / 2, a * math.sqrt(6) / 3
        counts = (int(dim[0] / a) + 1, int(dim[1] / hy) + 1, int(dim[2] / hz) + 1)
        for i in range(counts[0]):
            for j in range(counts[1]):
                for k in range(counts[2]):
                    p = np.array([2 * i + (j + k) % 2, math.sqrt(3.0) * (j + (k % 2) / 3.0),
                                  2.0 * math.sqrt(6.0) / 3.0 * k]) * (a / 2.0) + lo
                    if predicate(p, radius):
                        spheres.append(sphere(p, radius, **kw))
    else:
        counts = tuple(int(d / a) + 1 for d in dim)
        for i in range(counts[0]):
            for j in range(counts[1]):
                for k in range(counts[2]):
                    p = lo + radius + a * np.array([i, j, k])
                    if predicate(p, radius):
                        spheres.append(sphere(p, radius, **kw))
    return spheres


def regularHexa(predicate, radius: float, gap: float, **kw) -> list[BodySpec]:
    """Spheres of ``radius`` on a hexagonal close-packed lattice with ``gap`` between
    neighbours, kept where ``predicate`` holds (Yade's pack.regularHexa)."""
    return _lattice(predicate, radius, gap, "hexa", **kw)


def regularOrtho(predicate, radius: float, gap: float, **kw) -> list[BodySpec]:
    """Spheres on a simple cubic lattice of spacing 2 radius + gap (Yade's pack.regularOrtho)."""
    return _lattice(predicate, radius, gap, "ortho", **kw)


class SpherePack:
    """Spheres that are not a simulation yet (Yade's ``pack.SpherePack``): iterate it as
    ``(center, radius)`` pairs, fill it with :meth:`makeCloud`, put it in a scene with
    :meth:`toSimulation`. A periodic packing has a cell: ``hSize`` (edges as columns, possibly
    sheared) or, for an axis-aligned one, ``cellSize`` (Yade's); both are zero otherwise."""

    def __init__(self, spheres=None):
        self._cpp = _dem.SpherePack()
        self._clumpIds: list[int] = []  # per sphere, -1 for a free one; shorter lists end in free spheres
        if spheres is not None:
            self.fromList(spheres)

    # -- content ---------------------------------------------------------------------------------
    def fromList(self, spheres):
        """Replace the content by ``[(center, radius), ...]``."""
        centers, radii = [], []
        for k, item in enumerate(spheres):
            c, r = np.asarray(item[0], dtype=float), float(item[1])
            if c.shape != (3,) or not np.all(np.isfinite(c)) or not r > 0:
                raise ValueError(f"SpherePack: sphere #{k} needs a finite centre and a positive radius, got {item!r}")
            centers.append(c)
            radii.append(r)
        self._cpp.centers, self._cpp.radii = centers, radii
        self._clumpIds = []

    def toList(self) -> list:
        return list(self)

    def add(self, center, radius: float):
        self.fromList(self.toList() + [(center, radius)])

    def __len__(self) -> int:
        return len(self._cpp.radii)

    def __iter__(self):
        return ((np.array(c), r) for c, r in zip(self._cpp.centers, self._cpp.radii))

    def __getitem__(self, i: int):
        return np.array(self._cpp.centers[i]), self._cpp.radii[i]

    @property
    def hSize(self) -> np.ndarray:
        """The periodic cell, edges as columns (as ``O.cell.hSize``); zero if not periodic."""
        return np.array(self._cpp.hSize)

    @hSize.setter
    def hSize(self, value):
        self._cpp.hSize = np.asarray(value, dtype=float).reshape(3, 3)

    @property
    def cellSize(self) -> np.ndarray:
        """Sizes of the axis-aligned periodic cell (zero if not periodic). A sheared cell has no
        such sizes: use ``hSize``."""
        h = self.hSize
        if np.any(h != np.diag(np.diag(h))):
            raise ValueError("SpherePack.cellSize: the packing's cell is sheared; use hSize")
        return np.diag(h).copy()

    @cellSize.setter
    def cellSize(self, value):
        self.hSize = np.diag(np.asarray(value, dtype=float).reshape(3))

    @property
    def isPeriodic(self) -> bool:
        return bool(np.any(self.hSize != 0))

    @property
    def isSheared(self) -> bool:
        """Whether the periodic cell is not axis-aligned."""
        h = self.hSize
        return bool(np.any(h != np.diag(np.diag(h))))

    appliedPsdScaling = property(lambda self: self._cpp.appliedPsdScaling,
                                 doc="factor by which makeCloud scaled the size distribution down (1: none)")

    def aabb(self):
        """Corners of the box bounding the spheres."""
        if len(self) == 0:
            raise ValueError("SpherePack.aabb: the packing is empty")
        c, r = np.array(self._cpp.centers), np.array(self._cpp.radii)
        return (c - r[:, None]).min(axis=0), (c + r[:, None]).max(axis=0)

    # -- generation ------------------------------------------------------------------------------
    def makeCloud(self, minCorner=(0, 0, 0), maxCorner=(0, 0, 0), rMean: float = -1, rRelFuzz: float = 0,
                  num: int = -1, periodic: bool = False, porosity: float = 0.65, psdSizes=(), psdCumm=(),
                  distributeMass: bool = False, seed: int = -1, hSize=None) -> int:
        """Random loose cloud of non-overlapping spheres in the box [minCorner, maxCorner], added to
        the packing (Yade's makeCloud, with its parameters and defaults). Radii: uniform in
        rMean (1 +- rRelFuzz); or num spheres sized for ``porosity`` (rMean < 0); or a size
        distribution ``psdSizes`` (diameters) / ``psdCumm`` (cumulative fractions, by mass with
        ``distributeMass``). With ``seed`` >= 0 the cloud is deterministic and identical to
        Yade's for the same arguments. ``hSize`` (with ``periodic``): a sheared cell, edges as
        columns, filled from ``minCorner`` (``maxCorner`` unused), as Yade's; unlike Yade's, no
        sphere overlaps any periodic image of another, however sheared the cell, and the packing
        keeps the cell (``toSimulation`` sets ``O.cell.hSize``). A periodic sphere never
        reaches its own image: radii asked for (rMean, psdSizes) that cannot fit raise
        ValueError. Returns the number of spheres created."""
        cell = np.zeros((3, 3)) if hSize is None else np.asarray(hSize, dtype=float).reshape(3, 3)
        if (periodic and hSize is None and len(self) == 0
                and np.any(np.asarray(maxCorner, float) <= np.asarray(minCorner, float))):
            raise ValueError("makeCloud: a periodic cloud needs maxCorner above minCorner in every direction")
        if hSize is not None and not np.any(cell != 0):
            raise ValueError("makeCloud: hSize is zero; give the cell's edges as columns, or leave hSize out")
        return self._cpp.makeCloud(np.asarray(minCorner, dtype=float), np.asarray(maxCorner, dtype=float), float(rMean),
                                   float(rRelFuzz), int(num), bool(periodic), float(porosity),
                                   [float(x) for x in psdSizes], [float(x) for x in psdCumm], bool(distributeMass),
                                   int(seed), cell)

    @property
    def clumpIds(self) -> np.ndarray:
        """Per sphere, the index of the clump it is a member of (from :meth:`makeClumpCloud`), -1
        for a free sphere."""
        ids = np.full(len(self), -1, dtype=int)
        ids[:len(self._clumpIds)] = self._clumpIds
        return ids

    def getClumps(self):
        """``(standalone, clumps)``: the indices of the free spheres and, per clump, the indices of
        its spheres (Yade's getClumps)."""
        ids = self.clumpIds
        return [int(k) for k in np.flatnonzero(ids < 0)], [[int(k) for k in np.flatnonzero(ids == c)]
                                                            for c in np.unique(ids[ids >= 0])]

    def makeClumpCloud(self, minCorner, maxCorner, clumps, periodic: bool = False, num: int = -1,
                       seed: int = -1) -> int:
        """Random cloud of non-overlapping clumps in the box [minCorner, maxCorner], added to the
        packing (Yade's makeClumpCloud). ``clumps`` are SpherePacks used as templates, each
        recentred on its centroid (volume-weighted); a clump is a random template at a random
        centre with a random orientation (uniform on rotations), rejected if one of its spheres
        overlaps an existing sphere (through the periodic images with ``periodic``, which also
        makes the packing periodic with that box; otherwise the clump must lie inside the box).
        Up to 200 tries per clump; without ``num`` clumps are added until one fails. The pack
        remembers which spheres form a clump (:attr:`clumpIds`) and :meth:`toSimulation` makes
        them clumps. Yade draws with C rand(), this with numpy's generator (seeded with ``seed``
        >= 0): same statistics, not the same cloud. Returns the number of clumps created."""
        lo, hi = np.asarray(minCorner, dtype=float).reshape(3), np.asarray(maxCorner, dtype=float).reshape(3)
        size = hi - lo
        if np.any(size <= 0):
            raise ValueError(f"makeClumpCloud: maxCorner {hi} must be above minCorner {lo} in every direction")
        templates = []
        for k, c in enumerate(clumps):
            c = c if isinstance(c, SpherePack) else SpherePack(c)
            if len(c) == 0:
                raise ValueError(f"makeClumpCloud: clump template #{k} is empty")
            x, r = np.array(c._cpp.centers), np.array(c._cpp.radii)
            templates.append((x - (r[:, None] ** 3 * x).sum(axis=0) / (r ** 3).sum(), r))
        if not templates:
            raise ValueError("makeClumpCloud: no clump templates given")
        if periodic:
            if len(self) and self.isPeriodic and np.any(self.cellSize != size):
                raise ValueError(f"makeClumpCloud: the packing's cell {self.cellSize} differs from the box {size}")
        rng = np.random.default_rng(seed if seed >= 0 else None)
        centers = np.array(self._cpp.centers, dtype=float).reshape(-1, 3)
        radii = np.array(self._cpp.radii, dtype=float)
        ids = list(self.clumpIds)
        nextClump = max(ids, default=-1) + 1
        maxTry, made = 200, 0
        while num < 0 or made < num:
            rel, r = templates[int(rng.integers(len(templates)))]
            for _ in range(maxTry):
                q = rng.normal(size=4)
                w, x, y, z = q / np.linalg.norm(q)
                R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                              [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                              [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
                x = lo + rng.random(3) * size + rel @ R.T
                if not periodic and (np.any(x - r[:, None] < lo) or np.any(x + r[:, None] > hi)):
                    continue
                if len(radii):
                    d = x[:, None, :] - centers[None, :, :]
                    if periodic:
                        d -= size * np.round(d / size)
                    if np.any(np.einsum("ijk,ijk->ij", d, d) < (r[:, None] + radii[None, :]) ** 2):
                        continue
                centers = np.vstack([centers, x])
                radii = np.concatenate([radii, r])
                ids += [nextClump] * len(r)
                nextClump += 1
                break
            else:
                break
            made += 1
        self._cpp.centers, self._cpp.radii = list(centers), list(radii)
        self._clumpIds = ids
        if periodic:
            self.cellSize = size
        return made

    def psd(self, bins: int = 50, mass: bool = True):
        """Particle size distribution: ``(edges, cumm)``, ``bins + 1`` diameters from the smallest to
        the largest and the cumulative fraction (by mass, or by count) below each (as Yade)."""
        if len(self) == 0:
            return [], []
        d = 2 * np.array(self._cpp.radii)
        lo, hi = d.min(), d.max()
        if lo == hi:
            lo, hi = lo - .5, hi + .5
        edges = lo + np.arange(bins + 1) * (hi - lo) / bins
        index = np.minimum((bins * (d - lo) / (hi - lo)).astype(int), bins - 1)
        weight = d ** 3 / np.sum(d ** 3) if mass else np.full(len(d), 1.0 / len(d))
        cumm = np.concatenate([[0.0], np.minimum(1.0, np.cumsum(np.bincount(index, weight, minlength=bins)))])
        return edges, cumm

    # -- simulation and files --------------------------------------------------------------------
    def toSimulation(self, scene=None, **kw) -> list:
        """Append the spheres to the scene (``O`` by default); a periodic packing also makes the
        scene periodic with its cell (centres wrapped into it). Spheres of a clump (see
        :meth:`makeClumpCloud`) become a clump (appendClumped), moved together so that the
        clump's centre is in the cell (members may stick out of it). Keyword arguments go to
        :func:`sphere` (material, fixed, ...). Returns the new ids: an id per free sphere, a
        ``(clump id, member ids)`` pair per clump (as Yade)."""
        if scene is None:
            from talus.dem import O as scene
        if self.isPeriodic:
            scene.periodic = True
            scene.cell.hSize = self.hSize
            scene.cell.trsf = np.eye(3)
        ids = self.clumpIds
        if np.all(ids < 0):
            spheres = [(scene.cell.wrap(c), r) for c, r in self] if self.isPeriodic else list(self)
            return scene.bodies.append([sphere(c, r, **kw) for c, r in spheres])
        centers, radii = np.array(self._cpp.centers).reshape(-1, 3), np.array(self._cpp.radii)
        standalone, clumps = self.getClumps()
        groups = sorted([[k] for k in standalone] + clumps, key=lambda g: g[0])
        made = []
        for g in groups:
            x, r = centers[g], radii[g]
            if self.isPeriodic:
                mid = (r[:, None] ** 3 * x).sum(axis=0) / (r ** 3).sum()
                x = x + (scene.cell.wrap(mid) - mid)
            if ids[g[0]] < 0:
                made.append(scene.bodies.append(sphere(x[0], r[0], **kw)))
            else:
                made.append(scene.bodies.appendClumped([sphere(c, rr, **kw) for c, rr in zip(x, r)]))
        return made

    def fromSimulation(self, scene=None):
        """Replace the content by the scene's spheres (and its cell if periodic)."""
        if scene is None:
            from talus.dem import O as scene
        alive = np.asarray(scene._cpp.alive(), dtype=bool)
        r = np.asarray(scene.radii())
        keep = alive & (r > 0)
        self.fromList(list(zip(np.asarray(scene.positions())[keep], r[keep])))
        self.hSize = scene.cell.hSize if scene.periodic else np.zeros((3, 3))

    def save(self, fileName: str):
        """Write the spheres as text, one ``x y z r`` line each (full precision), with Yade's
        ``##PERIODIC:: sx sy sz`` first line for an axis-aligned periodic packing (readable by
        Yade's SpherePack.load); a sheared cell is a ``##HSIZE::`` line of its nine entries, row
        by row (Talus only: Yade reads such a file as not periodic)."""
        with open(fileName, "w") as f:
            if self.isSheared:
                f.write("##HSIZE:: " + " ".join(repr(float(x)) for x in self.hSize.ravel()) + "\n")
            elif self.isPeriodic:
                f.write("##PERIODIC:: " + " ".join(repr(float(x)) for x in self.cellSize) + "\n")
            for c, r in self:
                f.write(" ".join(repr(float(x)) for x in c) + f" {float(r)!r} -1\n")

    def load(self, fileName: str):
        """Read a file written by :meth:`save` (or Yade's SpherePack.save)."""
        spheres, cell = [], np.zeros((3, 3))
        with open(fileName) as f:
            for n, line in enumerate(f, 1):
                line = line.strip()
                if line.startswith(("##PERIODIC::", "##HSIZE::")):
                    cell = _cell_line(line, f"{fileName}:{n}")
                    continue
                if not line or line.startswith("#"):
                    continue
                items = line.split()
                if len(items) < 4:
                    raise ValueError(f"{fileName}:{n}: expected 'x y z r', got {line!r}")
                spheres.append(([float(x) for x in items[:3]], float(items[3])))
        self.fromList(spheres)
        self.hSize = cell


def _cell_line(line: str, where: str) -> np.ndarray:
    """The cell of a ``##PERIODIC:: sx sy sz`` or ``##HSIZE:: h00 h01 ... h22`` line."""
    tag, *items = line.split()
    count = 3 if tag == "##PERIODIC::" else 9
    try:
        values = [float(x) for x in items]
    except ValueError:
        values = []
    if len(values) != count:
        raise ValueError(f"{where}: {tag} needs {count} numbers, got {line!r}")
    return np.diag(values) if count == 3 else np.reshape(values, (3, 3))


def compressedCloud(minCorner, maxCorner, rMean: float = -1, rRelFuzz: float = 0, num: int = -1, seed: int = -1,
                    stress: float | None = -1e5, porosity: float | None = None, young: float = 1e7,
                    frictionAngle: float = 0.0, maxUnbalanced: float = 0.01, maxIter: int = 200000) -> "SpherePack":
    """A dense periodic packing: a periodic makeCloud in [minCorner, maxCorner] (same size
    parameters) compressed in a periodic cell, either isotropically to ``stress`` (Pa, negative:
    compression) by PeriTriaxController, or, with ``porosity``, homothetically to that porosity.
    The compaction runs frictionless by default (``frictionAngle``: denser packings) with FrictMat
    ``young``, until the unbalanced force is below ``maxUnbalanced``. Returns the packing (its
    ``cellSize`` is the compressed cell); ``toSimulation`` puts it in a scene.

    :raises RuntimeError: if the target is not reached within ``maxIter`` steps
    """
    from talus.dem import (FrictMat, InsertionSortCollider, InteractionLoop, NewtonIntegrator, PeriTriaxController,
                           PWaveTimeStep, Scene, unbalancedForce)
    from talus.dem.engines import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom,
                                   Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack)
    from talus.dem.measure import porosity as scene_porosity
    if (stress is None) == (porosity is None) and porosity is not None:
        raise ValueError("compressedCloud: give either stress or porosity, not both")
    cloud = SpherePack()
    cloud.makeCloud(minCorner, maxCorner, rMean=rMean, rRelFuzz=rRelFuzz, num=num, periodic=True, seed=seed)
    scene = Scene()
    scene.materials.append(FrictMat(young=young, frictionAngle=frictionAngle))
    cloud.toSimulation(scene)
    done = []
    if porosity is not None:
        if not 0 < porosity < 1:
            raise ValueError(f"compressedCloud: porosity must be in (0, 1), got {porosity}")
        n0 = scene_porosity(scene=scene)
        if porosity >= n0:
            raise ValueError(f"compressedCloud: the cloud's porosity {n0:.3f} is already below {porosity}")
        strain = np.log((1 - n0) / (1 - porosity)) / 3.0   # per axis: log of the volume ratio / 3
        # strain control; reached when the cell's strain is the goal (a loose target has no contacts,
        # hence no unbalanced force for the doneHook to wait for); the packing relaxes afterwards
        controller = PeriTriaxController(goal=(strain,) * 3, stressMask=0, maxStrainRate=(.5, .5, .5))
        reached = lambda: bool(np.all(np.abs(np.log(np.diag(scene.cell.trsf)) - strain) < 1e-9))
    else:
        if not stress < 0:
            raise ValueError(f"compressedCloud: stress must be negative (compression), got {stress}")
        controller = PeriTriaxController(goal=(stress,) * 3, stressMask=7, dynCell=True, maxStrainRate=(1, 1, 1),
                                         maxUnbalanced=maxUnbalanced, relStressTol=1e-3,
                                         doneHook=lambda: done.append(scene.pause()))
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                     [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     controller, NewtonIntegrator(damping=.4)]
    scene.dt = .5 * PWaveTimeStep(scene)
    while not (done or (porosity is not None and reached())):
        if scene.iter >= maxIter:
            raise RuntimeError(f"compressedCloud: the target was not reached in {maxIter} steps "
                               f"(unbalanced force {unbalancedForce(scene=scene):.3g})")
        scene.run(min(1000, maxIter - scene.iter))
    if porosity is not None:
        controller.dead = True
        scene.cell.velGrad = np.zeros((3, 3))
        while not unbalancedForce(scene=scene) <= maxUnbalanced and not np.isnan(unbalancedForce(scene=scene)):
            if scene.iter >= maxIter:
                raise RuntimeError(f"compressedCloud: the packing did not settle in {maxIter} steps")
            scene.run(500)
    packed = SpherePack()
    packed.fromSimulation(scene)
    centers = [scene.cell.wrap(c) for c, _ in packed]
    packed.fromList(list(zip(centers, [r for _, r in packed])))
    packed.hSize = scene.cell.hSize
    return packed
