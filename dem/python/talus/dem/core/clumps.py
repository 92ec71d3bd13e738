"""Yade's clump operations on a body container: clump templates, ``replaceByClumps``,
``getRoundness``, ``addToClump`` and ``releaseFromClump`` (``O.bodies.<name>`` call these).

    templates = [clumpTemplate(relRadii=[1, 1], relPositions=[[1, 0, 0], [-1, 0, 0]])]
    O.bodies.replaceByClumps(templates, [0.5])     # half the free spheres become dyads
    O.bodies.getRoundness()                        # 1 for spheres only, < 1 with clumps

Mass and inertia of a clump follow Yade's Clump::updateProperties (talus.dem C++ core): members
summed whole, or, with ``discretization`` > 0 and overlapping spheres, their union integrated on
a grid."""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Sequence

import numpy as np

from talus import _dem
from talus.dem.core.bodies import sphere
from talus.dem.core.scenes import default_scene

if TYPE_CHECKING:
    from talus.dem.core.body_container import BodyContainer


class clumpTemplate:
    """A clump shape for :func:`replaceByClumps`: member radii and positions, relative (Yade's
    utils.clumpTemplate). At least two members, no two at the same position."""

    def __init__(self, relRadii=(), relPositions=([], [])):
        if len(relRadii) != len(relPositions):
            raise ValueError(f"clumpTemplate: {len(relRadii)} relRadii but {len(relPositions)} relPositions; "
                             "give one radius per position")
        if len(relRadii) < 2:
            raise ValueError(f"clumpTemplate: a clump needs at least 2 members, got {len(relRadii)}")
        for k, p in enumerate(relPositions):
            if len(p) != 3:
                raise ValueError(f"clumpTemplate: relPositions[{k}] = {p!r} is not 3 coordinates")
        for k in range(len(relPositions)):
            for j in range(k + 1, len(relPositions)):
                if list(relPositions[k]) == list(relPositions[j]):
                    raise ValueError(f"clumpTemplate: relPositions[{k}] and relPositions[{j}] are the same point")
        self.numCM = len(relRadii)
        self.relRadii = relRadii
        self.relPositions = relPositions

    def __repr__(self):
        return f"clumpTemplate(relRadii={self.relRadii!r}, relPositions={self.relPositions!r})"


def _templateVolume(radii: np.ndarray, positions: np.ndarray) -> float:
    """Volume of the union of the template's spheres, counted on a grid of cubes of edge
    rmin / 5 over their bounding box (as Yade's replaceByClumps, so that a clump gets the
    volume of the sphere it replaces as Yade measures it)."""
    dx = radii.min() / 5
    lo = (positions - radii[:, None]).min(axis=0)
    hi = (positions + radii[:, None]).max(axis=0)
    # The cube centres lo + dx/2 + k dx below hi, axis by axis (Yade's loop bounds).
    axes = [lo[d] + dx / 2 + dx * np.arange(int(math.ceil((hi[d] - lo[d] - dx / 2) / dx)) + 1) for d in range(3)]
    axes = [a[a < hi[d]] for d, a in enumerate(axes)]
    inside = np.zeros((len(axes[0]), len(axes[1]), len(axes[2])), dtype=bool)
    for r, p in zip(radii, positions):
        d2 = ((axes[0] - p[0]) ** 2)[:, None, None] + ((axes[1] - p[1]) ** 2)[None, :, None] \
            + ((axes[2] - p[2]) ** 2)[None, None, :]
        inside |= d2 < r * r
    return float(inside.sum()) * dx ** 3


def _randomOrientation(rng: np.random.Generator) -> np.ndarray:
    """A rotation drawn as Yade's replaceByClumps draws it: angle 2 pi u about the axis
    (u, u, u), u uniform in [-1, 1] (the quaternion normalised). Rotation matrix."""
    u = rng.uniform(-1.0, 1.0, 4)
    angle, axis = 2 * math.pi * u[0], u[1:]
    q = np.array([math.cos(angle / 2), *(math.sin(angle / 2) * axis)])
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def replaceByClumps(bodies: "BodyContainer", ctList: Sequence[clumpTemplate], amounts: Sequence[float],
                    discretization: int = 0, seed: int | None = None) -> list:
    """Replace the fraction ``amounts[k]`` of the free spheres by clumps of template
    ``ctList[k]`` (Yade's O.bodies.replaceByClumps): each clump has the volume of the sphere it
    replaces, sits at its centre (the template's mean position there), turned at random, with
    the sphere's material. The spheres are taken evenly spread over the id order, template by
    template. Returns ``[(clumpId, [memberIds]), ...]``. ``seed`` (Talus only) makes the
    orientations reproducible; Yade seeds them from the clock."""
    amounts = [float(a) for a in amounts]
    if any(a < 0 for a in amounts):
        raise ValueError(f"replaceByClumps: amounts must not be negative, got {amounts}")
    if sum(amounts) > 1.0:
        raise ValueError(f"replaceByClumps: the amounts sum to {sum(amounts):g}, more than 1")
    if len(ctList) != len(amounts):
        raise ValueError(f"replaceByClumps: {len(amounts)} amounts for {len(ctList)} clump templates")
    scene = bodies._scene
    rng = np.random.default_rng(seed)
    free = [b.id for b in bodies if b.isStandalone and scene._cpp.shapeKind(b.id) == "Sphere"]
    total = len(free)
    made = []
    for template, amount in zip(ctList, amounts):
        radii = np.asarray(template.relRadii, dtype=float).reshape(-1)
        positions = np.asarray(template.relPositions, dtype=float).reshape(-1, 3)
        volume = _templateVolume(radii, positions)
        centre = positions.mean(axis=0)
        count = int(math.floor(total * amount + 0.5))
        # Spread over the spheres still free: the a-th taken is the (a len / count)-th (Yade's pick).
        chosen = []
        for c, i in enumerate(free):
            if len(chosen) < count and c == len(chosen) * len(free) // count:
                chosen.append(i)
        taken = set(chosen)
        free = [i for i in free if i not in taken]
        for id in chosen:
            old = bodies[id]
            r = old.shape.radius
            scale = (4 / 3 * math.pi * r ** 3 / volume) ** (1 / 3)
            R = _randomOrientation(rng)
            where = (positions - centre) @ R.T * scale + np.asarray(old.state.pos)
            material = old.material
            made.append(bodies.appendClumped([sphere(p, rr * scale, material=material, color=_randomColor(rng))
                                              for p, rr in zip(where, radii)], discretization))
            bodies.erase(id)
    return made


def _randomColor(rng: np.random.Generator):
    c = rng.uniform(0, 1, 3)
    return tuple(c / np.linalg.norm(c))


def getRoundness(bodies: "BodyContainer", excludeList: Sequence[int] = ()) -> float:
    """Yade's roundness coefficient: the mean over free spheres (1 each) and clumps (R1 / R2:
    R1 the radius of the sphere of the clump's volume, mass / density of its sphere members,
    R2 the radius of the smallest sphere about its centroid that holds it) of the bodies not in
    ``excludeList``; 0 if a clump's R2 < R1 (with a warning, as Yade)."""
    excluded = {int(i) for i in excludeList}
    total, count = 0.0, 0
    for b in bodies:
        if b.id in excluded:
            continue
        if b.isStandalone and b._scene._cpp.shapeKind(b.id) == "Sphere":
            total += 1.0
            count += 1
        elif b.isClump:
            R2, density = 0.0, 0.0
            centre = np.asarray(b.state.pos)
            for m in b.shape.members:
                member = bodies[m]
                if b._scene._cpp.shapeKind(m) == "Sphere":
                    R2 = max(R2, float(np.linalg.norm(np.asarray(member.state.pos) - centre)) + member.shape.radius)
                    density = member.material.density
            volume = b.state.mass / density if density > 0 else 0.0
            R1 = (3 * volume / (4 * math.pi)) ** (1 / 3)
            if R2 < R1:
                warnings.warn(f"getRoundness: clump {b.id} is smaller than a sphere of its volume (R2 < R1)", UserWarning,
                              stacklevel=3)
                return 0.0
            total += R1 / R2
            count += 1
    return total / max(count, 1)


def addToClump(bodies: "BodyContainer", bids, cid: int, discretization: int = 0) -> None:
    """Yade's O.bodies.addToClump: body ``bids`` (or a list of them) joins clump ``cid``; a clump,
    or a member of another clump, brings that whole clump along (which is erased). The clump
    itself, or one of its members, is not added (a warning, as Yade)."""
    ids = [int(bids)] if isinstance(bids, (int, np.integer)) else [int(i) for i in bids]
    cid = int(cid)
    _requireClump(bodies, cid)
    joining = []
    for i in ids:
        if i == cid:
            warnings.warn(f"addToClump: body {i} is clump {cid} itself; it was not added", UserWarning, stacklevel=3)
        elif bodies[i] is not None and bodies[i].clumpId == cid:
            warnings.warn(f"addToClump: body {i} is already a member of clump {cid}; it was not added", UserWarning,
                          stacklevel=3)
        else:
            joining.append(i)
    if joining:
        bodies._scene._views.before_adding(bodies._scene._cpp)
        _dem.add_to_clump(bodies._scene._cpp, cid, joining, int(discretization))


def releaseFromClump(bodies: "BodyContainer", bid: int, cid: int, discretization: int = 0) -> None:
    """Yade's O.bodies.releaseFromClump: member ``bid`` leaves clump ``cid`` and moves on its own;
    the clump's mass properties are recomputed. Refused with a warning (as Yade) when ``bid`` is
    not a member of ``cid`` or the clump would keep fewer than 2 members."""
    bid, cid = int(bid), int(cid)
    _requireClump(bodies, cid)
    body = bodies[bid]
    if body is None:
        raise IndexError(f"releaseFromClump: no body with id {bid}")
    if not body.isClumpMember:
        warnings.warn(f"releaseFromClump: body {bid} is not a clump member; it was not released", UserWarning,
                      stacklevel=3)
    elif body.clumpId != cid:
        warnings.warn(f"releaseFromClump: body {bid} is a member of clump {body.clumpId}, not of clump {cid}; "
                      "it was not released", UserWarning, stacklevel=3)
    elif len(bodies[cid].shape.members) <= 2:
        warnings.warn(f"releaseFromClump: body {bid} was not released from clump {cid}, which would be left with "
                      "fewer than 2 members (erase the clump instead)", UserWarning, stacklevel=3)
    else:
        bodies._scene._views.before_adding(bodies._scene._cpp)
        _dem.release_from_clump(bodies._scene._cpp, bid, cid, int(discretization))


def _requireClump(bodies: "BodyContainer", cid: int):
    body = bodies[cid]
    if body is None or not body.isClump:
        raise TypeError(f"body {cid} is not a clump")


__all__ = ["clumpTemplate"]


def exportTextClumps(filename: str, format: str = "x_y_z_r_clumpId", comment: str = "", mask: int = -1,
                     scene=None) -> tuple[int, int]:
    """Write the sphere members of every clump as ``x y z r clumpId`` lines (Yade's
    export.textClumps, same text); returns (number of clumps, number of spheres)."""
    O = default_scene()
    scene = scene or O
    if format != "x_y_z_r_clumpId":
        raise ValueError(f"textClumps: format={format!r} is not supported; only 'x_y_z_r_clumpId'")
    if mask != -1:
        raise ValueError(f"textClumps: mask={mask!r} is not supported (Talus bodies have no mask); use mask=-1")
    lines = ["#format x_y_z_r_clumpId\n"] + ([f"# {comment}\n"] if comment else [])
    clumps = spheres = 0
    for c in scene.bodies:
        if not c.isClump:
            continue
        clumps += 1
        for m in c.shape.members:
            if scene._cpp.shapeKind(m) == "Sphere":
                p = scene.bodies[m].state.pos
                lines.append("%g\t%g\t%g\t%g\t%g\n" % (p[0], p[1], p[2], scene.bodies[m].shape.radius, c.id))
                spheres += 1
    with open(filename, "w") as out:
        out.writelines(lines)
    return clumps, spheres


def importTextClumps(fileName: str, shift=(0.0, 0.0, 0.0), discretization: int = 0, orientation=None,
                     scale: float = 1.0, scene=None, **kw) -> list:
    """Read ``x y z r clumpId`` lines (Yade's ymport.textClumps): consecutive lines of one clump
    id become one clump (appendClumped), its spheres at ``shift + scale * orientation * (x, y,
    z)`` with radius ``scale * r``; ``kw`` goes to ``sphere`` (material, color). Lines starting
    with ``#`` are comments. Returns ``[(clumpId, [memberIds]), ...]``."""
    O = default_scene()
    from talus.dem.base.linalg import Quaternion, Vector3
    scene = scene or O
    turn = Quaternion((0, 1, 0), 0.0) if orientation is None else orientation
    shift = Vector3(shift)
    groups: list[list] = []
    last = None
    with open(fileName) as f:
        for number, line in enumerate(f, 1):
            data = line.split()
            if not data or data[0].startswith("#"):
                continue
            if len(data) < 5:
                raise ValueError(f"textClumps: {fileName}, line {number}: needs x y z r clumpId, got {line.strip()!r}")
            x, y, z, r = (float(v) for v in data[:4])
            clump = int(float(data[4]))
            if clump != last:
                groups.append([])
                last = clump
            groups[-1].append(sphere(shift + scale * (turn * Vector3(x, y, z)), scale * r, **kw))
    return [scene.bodies.appendClumped(g, discretization=discretization) for g in groups]
