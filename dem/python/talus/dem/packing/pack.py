"""Packings (Yade's ``pack`` module): regular lattices clipped by a predicate, random clouds
(``SpherePack.makeCloud``), dense packings by compression (``compressedCloud``; Yade's
``randomDensePack`` and ``randomPeriPack`` are in talus.dem.packing.densepack) and surfaces made of
facets (``sweptPolylines2gtsSurface``, ``gtsSurface2Facets``).

A predicate is a solid: ``pred(point, pad)`` says whether a sphere of radius ``pad`` centred at
``point`` lies inside, and ``pred.aabb()`` bounds it (talus.dem.packing.predicates, re-exported here).
"""

from __future__ import annotations

import math
import warnings
from typing import Sequence

import numpy as np

from talus import _dem
from talus.dem import distributed
from talus.dem.packing import predicates
from talus.dem.core.bodies import BodySpec, facet, sphere
from talus.dem.base.linalg import Vector3
from talus.dem.packing.predicates import *  # noqa: F401,F403  (Yade's pack module holds the predicates)
from talus.dem.core.scenes import default_scene

__all__ = [*predicates.__all__, "regularHexa", "regularOrtho", "filterSpherePack", "SpherePack", "compressedCloud",
           "sweptPolylines2gtsSurface", "gtsSurface2Facets", "revolutionSurfaceMeridians"]


MAX_SPHERES = _dem.SpherePack.maxSpheres   # the most spheres a generator makes (makeCloud's limit too)


def check_sphere_count(count: float, what: str) -> None:
    """Refuse, before anything is allocated, a packing of more than MAX_SPHERES spheres."""
    if not count <= MAX_SPHERES:
        raise ValueError(f"{what} would make {count:.3g} spheres, more than the limit of {MAX_SPHERES:.0e} "
                         "(a radius too small for the box?)")


def _lattice_points(predicate, radius: float, gap: float, kind: str) -> np.ndarray:
    """The lattice points of Yade's regularHexa / regularOrtho over the predicate's box, in
    Yade's order (x slowest)."""
    # A small negative gap is Yade's way of making the neighbours touch (overlap -gap).
    if not radius > 0 or not 2 * radius + gap > 0:
        raise ValueError(f"regular packing: radius must be positive and gap > -2 radius, got {radius}, {gap}")
    a = 2 * radius + gap
    lo, hi = (np.asarray(x, dtype=float) for x in predicate.aabb())
    dim = hi - lo
    if not np.all(np.isfinite(dim)):
        raise ValueError("regular packing: the predicate's bounding box is infinite (intersect an unbounded "
                         "predicate such as notInNotch with a bounded one: & rather than |)")
    if kind == "hexa":
        # Simple hcp lattice: rows j shifted by half a sphere on odd (j + k), layers k at
        # heights 2 sqrt(6)/3 k (a/2), odd layers shifted by a third of a row.
        hy, hz = a * math.sqrt(3) / 2, a * math.sqrt(6) / 3
        counts = np.floor(dim / (a, hy, hz)) + 1
        check_sphere_count(np.prod(counts), "regularHexa")
        i, j, k = np.meshgrid(*(np.arange(int(n)) for n in counts), indexing="ij")
        i, j, k = i.ravel(), j.ravel(), k.ravel()
        unit = np.c_[2 * i + (j + k) % 2, math.sqrt(3.0) * (j + (k % 2) / 3.0), 2.0 * math.sqrt(6.0) / 3.0 * k]
        return unit * (a / 2.0) + lo
    check_sphere_count(np.prod(np.maximum(np.ceil((dim - 2 * radius) / a), 0)), "regularOrtho")
    axes = [np.arange(lo[d] + radius, hi[d] - radius, a) for d in range(3)]
    return np.array(np.meshgrid(*axes, indexing="ij")).reshape(3, -1).T


def _lattice(predicate, radius: float, gap: float, kind: str, **kw) -> list[BodySpec]:
    spheres = [sphere(p, radius, **kw) for p in _lattice_points(predicate, radius, gap, kind) if predicate(p, radius)]
    if not spheres:
        warnings.warn(f"no spheres are produced by regular{kind.capitalize()}", RuntimeWarning, stacklevel=3)
    return spheres


def regularHexa(predicate, radius: float, gap: float, **kw) -> list[BodySpec]:
    """Spheres of ``radius`` on a hexagonal close-packed lattice with ``gap`` between
    neighbours, from the corner of the predicate's box, kept where ``predicate`` holds with the
    radius as pad (Yade's pack.regularHexa: the same spheres in the same order)."""
    return _lattice(predicate, radius, gap, "hexa", **kw)


def regularOrtho(predicate, radius: float, gap: float, **kw) -> list[BodySpec]:
    """Spheres on a simple cubic lattice of spacing 2 radius + gap starting a radius inside the
    predicate's box (Yade's pack.regularOrtho)."""
    return _lattice(predicate, radius, gap, "ortho", **kw)


def filterSpherePack(predicate, spherePack, returnSpherePack=None, **kw):
    """The spheres of ``spherePack`` inside ``predicate`` (each with its radius as pad), after
    moving the packing so that its box and the predicate's have the same centre (Yade's
    filterSpherePack; the packing passed is moved). A :class:`SpherePack` with
    ``returnSpherePack``, else a list of bodies (``kw`` go to :func:`sphere`); left out, it is
    the list, with Yade's FutureWarning. Warns when the predicate's box is larger than the
    packing's."""
    if returnSpherePack is None:
        warnings.warn("filterSpherePack/randomDensePack: the default behaviour will change; give "
                      "returnSpherePack=True for a SpherePack, False for a list of bodies", FutureWarning, stacklevel=2)
        returnSpherePack = False
    dimP, dimS = np.asarray(predicate.dim(), float), np.asarray(spherePack.dim(), float)
    if np.any(dimP > dimS):
        warnings.warn(f"the packing's size {tuple(dimS)} does not contain the predicate's {tuple(dimP)}", stacklevel=2)
    spherePack.translate(np.asarray(predicate.center(), float) - np.asarray(spherePack.center(), float))
    kept = [(c, r) for c, r in spherePack if predicate(c, r)]
    if returnSpherePack:
        return SpherePack(kept)
    return [sphere(c, r, **kw) for c, r in kept]


class SpherePack:
    """Spheres that are not a simulation yet (Yade's ``pack.SpherePack``): iterate it as
    ``(center, radius)`` pairs, fill it with :meth:`makeCloud`, put it in a scene with
    :meth:`toSimulation`. A periodic packing has a cell: ``hSize`` (edges as columns, possibly
    sheared) or, for an axis-aligned one, ``cellSize`` (Yade's); both are zero otherwise."""

    def __init__(self, spheres=None):
        self._cpp = _dem.SpherePack()
        self._clumpIds: list[int] = []  # per sphere, -1 for a free one; shorter lists end in free spheres
        self._periodicFlag = False      # periodic without a cell: a flat (2D) periodic cloud, as Yade's
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

    def hasClumps(self) -> bool:
        return bool(np.any(self.clumpIds >= 0))

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
        """Whether the packing is periodic: it has a cell, or (Yade's flat periodic cloud, or set
        by hand) it is marked periodic without one; ``toSimulation`` then makes the scene
        periodic and leaves its cell to the script."""
        return self._hasCell or self._periodicFlag

    @isPeriodic.setter
    def isPeriodic(self, value: bool):
        self._periodicFlag = bool(value)
        if not value:
            self.hSize = np.zeros((3, 3))

    @property
    def _hasCell(self) -> bool:
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

    def dim(self):
        """Sizes of the box bounding the spheres."""
        lo, hi = self.aabb()
        return Vector3(*(hi - lo))

    def center(self):
        """Centre of the box bounding the spheres."""
        lo, hi = self.aabb()
        return Vector3(*(.5 * (lo + hi)))

    def relDensity(self) -> float:
        """Volume of the spheres over the volume of the cell (periodic) or of their box."""
        volume = abs(np.linalg.det(self.hSize)) if self._hasCell else float(np.prod(self.dim()))
        return float(4 / 3 * np.pi * np.sum(np.array(self._cpp.radii) ** 3) / volume)

    def _moved(self, centers: np.ndarray, scaleRadii: float = 1.0):
        self._cpp.centers = list(centers)
        if scaleRadii != 1.0:
            self._cpp.radii = list(np.array(self._cpp.radii) * scaleRadii)

    def translate(self, shift):
        """Move every sphere by ``shift``."""
        self._moved(np.array(self._cpp.centers).reshape(-1, 3) + np.asarray(shift, float).reshape(3))

    def rotate(self, axis, angle: float):
        """Rotate the spheres by ``angle`` about ``axis`` through the centre of their box. A
        periodic packing loses its cell, as in Yade (with Yade's warning)."""
        from talus.dem.base.linalg import Quaternion
        if self._hasCell:
            warnings.warn(f"SpherePack.rotate: the periodic cell {tuple(np.diag(self.hSize))} is dropped by the rotation",
                          stacklevel=2)
            self.hSize = np.zeros((3, 3))
        R = np.asarray(Quaternion(Vector3(*axis), float(angle)).toRotationMatrix(), float).reshape(3, 3)
        mid = np.asarray(self.center(), float)
        self._moved((np.array(self._cpp.centers).reshape(-1, 3) - mid) @ R.T + mid)

    def scale(self, factor: float):
        """Scale positions about the centre of the spheres' box, radii and cell by ``factor``."""
        mid = np.asarray(self.center(), float)
        self.hSize = self.hSize * factor
        self._moved((np.array(self._cpp.centers).reshape(-1, 3) - mid) * factor + mid, abs(factor))

    def cellRepeat(self, count):
        """Repeat a periodic packing ``count`` (3 positive integers) times along the cell's axes;
        the cell grows accordingly (Yade's cellRepeat)."""
        count = [int(n) for n in count]
        if not self._hasCell or self.isSheared:
            raise ValueError("SpherePack.cellRepeat: needs a periodic packing with an axis-aligned cell")
        if min(count) <= 0:
            raise ValueError(f"SpherePack.cellRepeat: the counts must be positive, got {count}")
        check_sphere_count(len(self) * math.prod(count), "SpherePack.cellRepeat")
        size = self.cellSize
        c, r = np.array(self._cpp.centers).reshape(-1, 3), np.array(self._cpp.radii)
        # Yade's order: the original cell first, then the copies with the z offset fastest
        offsets = [size * (i, j, k) for i in range(count[0]) for j in range(count[1]) for k in range(count[2])]
        self._cpp.centers = list(np.concatenate([c + o for o in offsets]))
        self._cpp.radii = list(np.tile(r, len(offsets)))
        self._clumpIds = []
        self.cellSize = size * count

    def cellFill(self, vol):
        """Repeat a periodic packing until its cell covers the sizes ``vol`` (Yade's cellFill)."""
        if not self._hasCell:
            raise ValueError("SpherePack.cellFill: needs a periodic packing")
        self.cellRepeat(np.ceil(np.asarray(vol, float).reshape(3) / self.cellSize).astype(int))

    # -- generation ------------------------------------------------------------------------------
    def makeCloud(self, minCorner=(0, 0, 0), maxCorner=(0, 0, 0), rMean: float = -1, rRelFuzz: float = 0,
                  num: int = -1, periodic: bool = False, porosity: float = 0.65, psdSizes=(), psdCumm=(),
                  distributeMass: bool = False, seed: int = -1, hSize=None) -> int:
        """Random loose cloud of non-overlapping spheres in the box [minCorner, maxCorner], added to
        the packing (Yade's makeCloud, with its parameters and defaults). Radii: uniform in
        rMean (1 +- rRelFuzz); or num spheres sized for ``porosity`` (rMean < 0); or a size
        distribution ``psdSizes`` (diameters) / ``psdCumm`` (cumulative fractions, by mass with
        ``distributeMass``). With ``seed`` >= 0 the cloud is deterministic and identical to
        Yade's for the same arguments; without, under mpirun, every process makes the same random
        cloud (one seed drawn for all: collective). ``hSize`` (with ``periodic``): a sheared cell, edges as
        columns, filled from ``minCorner`` (``maxCorner`` unused), as Yade's; unlike Yade's, no
        sphere overlaps any periodic image of another, however sheared the cell, and the packing
        keeps the cell (``toSimulation`` sets ``O.cell.hSize``). A periodic sphere never
        reaches its own image: radii asked for (rMean, psdSizes) that cannot fit raise
        ValueError. A flat box (one size zero) with ``periodic`` makes a 2D cloud that is
        periodic without a cell (as Yade's: ``isPeriodic`` true, ``cellSize`` zero): the script
        sets ``O.cell.hSize`` after ``toSimulation``. A box whose maxCorner is below minCorner
        along an axis (not periodic, rMean given) is filled between the two as Yade fills it,
        its spheres reaching up to one radius beyond them. Returns the number of spheres created."""
        cell = np.zeros((3, 3)) if hSize is None else np.asarray(hSize, dtype=float).reshape(3, 3)
        if hSize is not None and not np.any(cell != 0):
            raise ValueError("makeCloud: hSize is zero; give the cell's edges as columns, or leave hSize out")
        made = self._cpp.makeCloud(np.asarray(minCorner, dtype=float), np.asarray(maxCorner, dtype=float), float(rMean),
                                   float(rRelFuzz), int(num), bool(periodic), float(porosity),
                                   [float(x) for x in psdSizes], [float(x) for x in psdCumm], bool(distributeMass),
                                   distributed.shared_seed(int(seed)), cell)
        if periodic:
            self._periodicFlag = True   # a flat box: a periodic 2D cloud without a cell, as Yade's
        return made

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
            if len(self) and self._hasCell and np.any(self.cellSize != size):
                raise ValueError(f"makeClumpCloud: the packing's cell {self.cellSize} differs from the box {size}")
        seed = distributed.shared_seed(int(seed))
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
    def toSimulation(self, scene=None, rot=None, **kw) -> list:
        """Append the spheres to the scene (``O`` by default); a periodic packing also makes the
        scene periodic with its cell (centres wrapped into it). ``rot`` (a Matrix3 or a
        Quaternion) rotates the spheres and the cell (Yade's). Spheres of a clump (see
        :meth:`makeClumpCloud`) become a clump (appendClumped), moved together so that the
        clump's centre is in the cell (members may stick out of it). Keyword arguments go to
        :func:`sphere` (material, fixed, ...). Returns the new ids: an id per free sphere, a
        ``(clump id, member ids)`` pair per clump (as Yade)."""
        if scene is None:
            scene = default_scene()
        R = np.eye(3)
        if rot is not None:
            R = np.asarray(rot.toRotationMatrix() if hasattr(rot, "toRotationMatrix") else rot, float).reshape(3, 3)
        if self.isPeriodic:
            scene.periodic = True
        if self._hasCell:
            scene.cell.hSize = R @ self.hSize
            scene.cell.trsf = np.eye(3)
        centers, radii = np.array(self._cpp.centers).reshape(-1, 3) @ R.T, np.array(self._cpp.radii)
        ids = self.clumpIds
        if np.all(ids < 0):
            if self._hasCell:
                centers = [scene.cell.wrap(c) for c in centers]
            return scene.bodies.append([sphere(c, r, **kw) for c, r in zip(centers, radii)])
        standalone, clumps = self.getClumps()
        groups = sorted([[k] for k in standalone] + clumps, key=lambda g: g[0])
        made = []
        for g in groups:
            x, r = centers[g], radii[g]
            if self._hasCell:
                mid = (r[:, None] ** 3 * x).sum(axis=0) / (r ** 3).sum()
                x = x + (scene.cell.wrap(mid) - mid)
            if ids[g[0]] < 0:
                made.append(scene.bodies.append(sphere(x[0], r[0], **kw)))
            else:
                made.append(scene.bodies.appendClumped([sphere(c, rr, **kw) for c, rr in zip(x, r)]))
        return made

    def fromSimulation(self, scene=None):
        """Replace the content by the scene's spheres (and its cell if periodic); under mpirun,
        every sphere of a scene split over the processes, on every process (collective)."""
        if scene is None:
            scene = default_scene()
        self.fromList(list(zip(*distributed.spheres(scene))))
        self.hSize = scene.cell.hSize if scene.periodic else np.zeros((3, 3))
        self._periodicFlag = bool(scene.periodic)

    def save(self, fileName: str):
        """Write the spheres as text, one ``x y z r`` line each (full precision), with Yade's
        ``##PERIODIC:: sx sy sz`` first line for an axis-aligned periodic packing (readable by
        Yade's SpherePack.load); a sheared cell is a ``##HSIZE::`` line of its nine entries, row
        by row (Talus only: Yade reads such a file as not periodic)."""
        with open(fileName, "w") as f:
            if self.isSheared:
                f.write("##HSIZE:: " + " ".join(repr(float(x)) for x in self.hSize.ravel()) + "\n")
            elif self._hasCell:
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
    from talus.dem.control.controllers import PeriTriaxController
    from talus.dem.step.engines import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                                   InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                                   Law2_ScGeom_FrictPhys_CundallStrack, NewtonIntegrator)
    from talus.dem.core.materials import FrictMat
    from talus.dem.analysis.measure import porosity as scene_porosity, unbalancedForce
    from talus.dem.core.scene import PWaveTimeStep, Scene
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


# ------------------------------------------------------------------------------------------------
# Surfaces (Yade's pack functions over gts surfaces)

def gtsSurface2Facets(surf, **kw) -> list[BodySpec]:
    """A facet per face of the gts surface ``surf``, its vertices in the face's order; ``kw`` go
    to :func:`facet` (material, color, ...)."""
    return [facet([v.coords() for v in face.vertices()], **kw) for face in surf.faces()]


def sweptPolylines2gtsSurface(pts, threshold: float = 0.0, capStart: bool = False, capEnd: bool = False):
    """The gts surface swept through the polylines ``pts`` (sequences of the same number of
    points): between polylines i and i+1, segment j (points a = P[i][j], b = P[i][j+1],
    c = P[i+1][j], d = P[i+1][j+1]) gives the triangles (a, d, c) and (a, b, d). ``capStart`` /
    ``capEnd`` close the first / last polyline with a fan from its first point (fine for convex
    sections). With ``threshold`` > 0, triangles with an edge shorter than it are left out and
    vertices closer than it are merged. The triangles and their vertex order are Yade's."""
    from talus.dem.geometry import gts
    if len({len(line) for line in pts}) != 1:
        raise ValueError("sweptPolylines2gtsSurface: the polylines must all have the same number of points")
    V = [[gts.Vertex(*(float(x) for x in p)) for p in line] for line in pts]

    def short(u, v):
        return threshold > 0 and math.dist(u.coords(), v.coords()) < threshold

    def keep(a, b, c):
        return not (short(a, b) or short(b, c) or short(c, a))

    surf = gts.Surface()
    for i in range(len(V) - 1):
        for j in range(len(V[i]) - 1):
            a, b, c, d = V[i][j], V[i][j + 1], V[i + 1][j], V[i + 1][j + 1]
            for tri in ((a, d, c), (a, b, d)):
                if keep(*tri):
                    surf.add(gts.Face(*tri))
    # fans: (v1, v0, v2), (v_k, v0, v_k+1) ... at the start; (v0, v_k, v_k+1) at the end
    if capStart:
        line = V[0]
        for k in range(1, len(line) - 1):
            surf.add(gts.Face(line[k], line[0], line[k + 1]))
    if capEnd:
        line = V[-1]
        for k in range(1, len(line) - 1):
            surf.add(gts.Face(line[0], line[k], line[k + 1]))
    if threshold > 0:
        surf.cleanup(threshold)
    return surf


def revolutionSurfaceMeridians(sects, angles, origin=(0.0, 0.0, 0.0), orientation=(1.0, 0.0, 0.0, 0.0)):
    """Meridians of a surface of revolution about z: section i (2D points (r, z)) turned by
    ``angles[i]``, then rotated by ``orientation`` (a quaternion) and moved to ``origin``; the
    result feeds :func:`sweptPolylines2gtsSurface`."""
    from talus.dem.base.linalg import Quaternion
    q = orientation if isinstance(orientation, Quaternion) else Quaternion(*orientation)
    R = np.asarray(q.toRotationMatrix(), float).reshape(3, 3)
    o = np.asarray(origin, float).reshape(3)
    return [[tuple(o + R @ (x * math.cos(angles[i]), x * math.sin(angles[i]), y)) for x, y in sects[i]]
            for i in range(len(sects))]
