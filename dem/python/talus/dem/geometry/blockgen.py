"""Block generation (after Boon et al. 2015 and Yade's BlockGen): split an intact block by
discontinuity planes into Potential Blocks.

    joints = readJoints("joints.csv")              # Yade's joint CSV (dip;dipDir;centreX;...)
    blocks = generateBlocks(PotentialBlock.cuboid((20, 20, 20), r=0.2), joints, r=0.2)
    O.bodies.append([potentialBlock(b, material=rock) for b in blocks])

Sequential subdivision: each joint splits every current block it crosses into the two blocks on
either side (the block's planes plus the joint plane, one way and the other). Planes are in world
coordinates throughout, so the generated blocks sit where they were cut (``potentialBlock(b)``
with ``pos=None``).

Non-persistent joints (finite traces), as Yade's BlockGen: a joint whose rectangle meets a block
cuts it along its whole plane (the seed's "more constraints": the joint's persistence planes in
the linear program that finds whether it touches the block). The part of the cut the joint does
not cover is a rock bridge: the new faces carry the strength of both parts, weighted by area,
as intact rock, and the contact law (Ip2_FrictMat_FrictMat_KnKsPBPhys(useFaceProperties=True))
bonds them until the bridge breaks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from talus import _dem
from talus.dem.geometry.blocks import PotentialBlock

_REQUIRED = ("dip", "dipDir", "centreX", "centreY", "centreZ")
# Optional columns: the trace half-lengths and the strengths Yade's BlockGen reads (Yade's
# spelling; phi_b, phi_r, JRC, JSC, asperity and simgaC are read and checked, not used).
_OPTIONAL = ("traceX", "traceY", "phi_b", "phi_r", "JRC", "JSC", "asperity", "simgaC", "cohesion", "tension",
             "jointType")


class JointFileError(ValueError):
    """A malformed joint file; the message names the file and the line."""


@dataclass
class Joint:
    """A discontinuity plane: unit normal, a point on it, and its half-extents from the centre
    along its strike and dip line in the plane (``traceX``, ``traceY``, as Yade's persistence
    planes; large values: persistent). ``cohesion``, ``tension``: the joint's strengths
    (stresses); ``jointType``: Yade's joint class. ``line``: where it was read."""
    normal: np.ndarray
    centre: np.ndarray
    traceX: float = math.inf
    traceY: float = math.inf
    line: int = 0
    cohesion: float = 0.0
    tension: float = 0.0
    jointType: int = 0


def dipNormal(dip: float, dipDir: float) -> np.ndarray:
    """Unit normal of a plane of the given dip and dip direction (degrees), in the convention of
    Yade's WedgeYADE example (x north, y east, z down): the normal of dip 90 is horizontal."""
    dipN = math.radians(90.0 - dip)
    dipdirN = math.radians(dipDir - 180.0 if dipDir > 180.0 else dipDir + 180.0)
    return np.array([math.cos(dipdirN) * math.cos(dipN), math.sin(dipdirN) * math.cos(dipN), math.sin(dipN)])


def readJoints(path: str) -> list[Joint]:
    """Joints from Yade's semicolon-separated CSV (header line naming the columns; dip, dipDir,
    centreX, centreY, centreZ required; traceX, traceY, cohesion, tension, jointType and Yade's
    other strength columns optional, an empty value taking the default).
    @raises JointFileError naming the file and line for a missing column, a short line or a value
    that is not a finite number (dip in [0, 90], dipDir in [0, 360], traces > 0, cohesion and
    tension >= 0, jointType an integer)."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    if not lines:
        raise JointFileError(f"{path}: empty file (expected a header line dip;dipDir;centreX;centreY;centreZ;...)")
    header = [h.strip() for h in lines[0].split(";")]
    missing = [c for c in _REQUIRED if c not in header]
    if missing:
        raise JointFileError(f"{path} line 1: the header lacks the column(s) {', '.join(missing)}")
    column = {name: k for k, name in enumerate(header) if name}
    joints = []
    for number, text in enumerate(lines[1:], start=2):
        if not text.strip() or text.lstrip().startswith("#"):
            continue
        fields = [x.strip() for x in text.split(";")]
        values = {}
        for name in _REQUIRED + _OPTIONAL:
            if name not in column:
                continue
            k = column[name]
            if k >= len(fields) or fields[k] == "":
                if name in _REQUIRED:
                    raise JointFileError(f"{path} line {number}: no value for {name} (column {k + 1})")
                continue
            try:
                values[name] = float(fields[k])
            except ValueError:
                raise JointFileError(f"{path} line {number}: {name} {fields[k]!r} is not a number") from None
            if not math.isfinite(values[name]):
                raise JointFileError(f"{path} line {number}: {name} is not finite")
        if not 0 <= values["dip"] <= 90:
            raise JointFileError(f"{path} line {number}: dip must be in [0, 90] degrees, got {values['dip']}")
        if not 0 <= values["dipDir"] <= 360:
            raise JointFileError(f"{path} line {number}: dipDir must be in [0, 360] degrees, got {values['dipDir']}")
        for name in ("traceX", "traceY"):
            if name in values and not values[name] > 0:
                raise JointFileError(f"{path} line {number}: {name} must be > 0, got {values[name]}")
        for name in ("cohesion", "tension"):
            if name in values and values[name] < 0:
                raise JointFileError(f"{path} line {number}: {name} must be >= 0, got {values[name]}")
        if "jointType" in values and values["jointType"] != int(values["jointType"]):
            raise JointFileError(f"{path} line {number}: jointType must be an integer, got {values['jointType']}")
        joints.append(Joint(dipNormal(values["dip"], values["dipDir"]),
                            np.array([values["centreX"], values["centreY"], values["centreZ"]]),
                            values.get("traceX", math.inf), values.get("traceY", math.inf), number,
                            values.get("cohesion", 0.0), values.get("tension", 0.0), int(values.get("jointType", 0))))
    return joints


def _faces(block: PotentialBlock) -> tuple[np.ndarray, np.ndarray]:
    """Normals (n, 3) and face offsets h = d + r of a block."""
    return np.column_stack([block.a, block.b, block.c]), np.asarray(block.d) + block.r


def _geometry(normals, h, r, which):
    return _dem.potential_block_geometry(list(normals[:, 0]), list(normals[:, 1]), list(normals[:, 2]),
                                         list(h - r), r, which)


def _planeAxes(joint: Joint) -> tuple[np.ndarray, np.ndarray]:
    """Unit strike and dip-line directions in the joint's plane (the axes of its trace)."""
    n = joint.normal
    strike = np.cross(n, [0.0, 0.0, 1.0])
    strike = strike / np.linalg.norm(strike) if np.linalg.norm(strike) > 1e-12 else np.array([1.0, 0, 0])
    return strike, np.cross(n, strike)


def _clip(polygon: np.ndarray, g: np.ndarray, limit: float) -> np.ndarray:
    """The part of a convex polygon (k, 2) where g . p <= limit (Sutherland-Hodgman)."""
    out = []
    for k in range(len(polygon)):
        p, q = polygon[k], polygon[(k + 1) % len(polygon)]
        fp, fq = g @ p - limit, g @ q - limit
        if fp <= 0:
            out.append(p)
        if fp * fq < 0:
            out.append(p + fp / (fp - fq) * (q - p))
    return np.array(out).reshape(-1, 2)


def _area(polygon: np.ndarray) -> float:
    if len(polygon) < 3:
        return 0.0
    x, y = polygon[:, 0], polygon[:, 1]
    return 0.5 * abs(float(x @ np.roll(y, -1) - y @ np.roll(x, -1)))


def _section(joint: Joint, normals: np.ndarray, h: np.ndarray, size: float) -> tuple[float, float]:
    """Areas of the block's section by the joint's plane and of its part inside the joint's
    rectangle (the joint's trace): the block's planes, then the trace's four persistence
    planes, clip a square of side 4 size on the plane (coordinates along strike and dip line
    from the joint's centre)."""
    strike, dipLine = _planeAxes(joint)
    poly = 2 * size * np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
    for n, hk in zip(normals, h):
        poly = _clip(poly, np.array([n @ strike, n @ dipLine]), hk - n @ joint.centre)
        if not len(poly):
            return 0.0, 0.0
    section = _area(poly)
    for g, limit in (((1.0, 0.0), joint.traceX), ((-1.0, 0.0), joint.traceX), ((0.0, 1.0), joint.traceY),
                     ((0.0, -1.0), joint.traceY)):
        if math.isfinite(limit):
            poly = _clip(poly, np.array(g), limit)
    return section, _area(poly)


@dataclass
class _Piece:
    """A block being cut: its planes (normals, face offsets h = d + r), corners, and per plane
    the face's strengths, intact-rock flag and joint type."""
    normals: np.ndarray
    h: np.ndarray
    corners: np.ndarray
    cohesion: list
    tension: list
    intactRock: list
    jointType: list


def _inscribedDiameter(normals: np.ndarray, h: np.ndarray, vertices: np.ndarray) -> float:
    """Diameter of the largest ball inside {x : n_i . x <= h_i} (unit normals; the Chebyshev
    centre, by the linear program block contacts solve); 0 if the region is empty. The piece's
    corners bound the program."""
    bound = 2.0 * float(np.abs(vertices).max()) + 1.0
    depth, _ = _dem.deepest_point(list(normals), list(h), bound)
    return 2.0 * max(depth, 0.0)


def _tooSmall(normals: np.ndarray, h: np.ndarray, vertices: np.ndarray, minSize: float, maxRatio: float) -> bool:
    """Yade's BlockGen test of a piece: inscribed diameter below minSize, or an extent along x, y
    or z above maxRatio times it."""
    diameter = _inscribedDiameter(normals, h, vertices)
    return diameter < minSize or diameter <= 0 or float(np.ptp(vertices, axis=0).max()) > maxRatio * diameter


def generateBlocks(intact: PotentialBlock, joints: list[Joint], r: float | None = None, minVolume: float = 0.0,
                   rockCohesion: float = 0.0, rockTension: float = 0.0,
                   intactRockDegradation: bool = False, minSize: float = 0.0,
                   maxRatio: float = math.inf) -> list[PotentialBlock]:
    """Split ``intact`` (planes in world coordinates) by ``joints`` in turn; returns the blocks
    (rounding ``r``, default the intact block's), dropping pieces of volume <= ``minVolume``
    (slivers; Yade's BlockGen avoids them instead, see minSize). Planes bounding a piece only at an edge
    or a vertex are removed, so each block keeps only its faces.

    A joint cuts every block whose interior its rectangle meets (Yade's BlockGen), along the
    whole section. Strengths of the faces it makes, with k the fraction of the section the
    joint covers: cohesion = k c_joint + (1 - k) ``rockCohesion``, tension likewise with
    ``rockTension`` (the rock bridge is intact rock), where the joint's own c and t (the
    file's columns) count only with ``intactRockDegradation`` (Yade's BlockGen option); faces
    with a strength are intact rock. The intact block's own faces are frictional.

    ``minSize``, ``maxRatio``: Yade's BlockGen pruning. A joint leaves a block uncut when
    either piece would have an inscribed ball of diameter D < ``minSize``, or an extent along
    x, y or z above ``maxRatio`` D (so no block is thinner than minSize: the joint ends there,
    as a joint does in the rock mass)."""
    r = intact.r if r is None else float(r)
    for name, value in (("rockCohesion", rockCohesion), ("rockTension", rockTension), ("minSize", minSize)):
        if not (math.isfinite(value) and value >= 0):
            raise ValueError(f"generateBlocks: {name} must be finite and >= 0, got {value}")
    if not maxRatio > 0:
        raise ValueError(f"generateBlocks: maxRatio must be > 0, got {maxRatio}")
    prune = minSize > 0 or math.isfinite(maxRatio)
    normals, h = _faces(intact)
    geometry = _geometry(normals, h, r, "intact block")
    corners = np.asarray(geometry["vertices"])
    scale = float(np.ptp(corners, axis=0).max())
    tol = 1e-9 * scale
    m = len(h)
    pieces = [_Piece(normals, h, corners, [0.0] * m, [0.0] * m, [False] * m, [0] * m)]
    for joint in joints:
        offset = float(joint.normal @ joint.centre)
        split = []
        for piece in pieces:
            side = (piece.corners - joint.centre) @ joint.normal
            if not (side.max() > tol and side.min() < -tol):
                split.append(piece)
                continue
            size = float(np.abs(piece.corners - joint.centre).max())
            section, covered = _section(joint, piece.normals, piece.h, size)
            if covered <= tol * scale:
                split.append(piece)   # the joint's trace ends before this block
                continue
            k = min(covered / section, 1.0)
            c = k * (joint.cohesion if intactRockDegradation else 0.0) + (1 - k) * rockCohesion
            t = k * (joint.tension if intactRockDegradation else 0.0) + (1 - k) * rockTension
            children = []
            for sign in (1.0, -1.0):
                n2 = np.vstack([piece.normals, sign * joint.normal])
                h2 = np.append(piece.h, sign * offset)
                try:
                    g = _geometry(n2, h2, r, f"piece cut by the joint of line {joint.line}")
                except ValueError:
                    continue   # no volume on this side after all (the joint only grazes the block)
                children.append((n2, h2, np.asarray(g["vertices"]), g["volume"]))
            if prune and (len(children) < 2
                          or any(_tooSmall(n2, h2, v, minSize, maxRatio) for n2, h2, v, _ in children)):
                split.append(piece)   # Yade's pruning: the joint stops before this block
                continue
            for n2, h2, vertices, volume in children:
                if volume > minVolume:
                    split.append(_Piece(n2, h2, vertices, piece.cohesion + [c], piece.tension + [t],
                                        piece.intactRock + [c > 0 or t > 0], piece.jointType + [joint.jointType]))
        pieces = split
    blocks = []
    for p in pieces:
        keep = [k for k in range(len(p.h)) if np.sum(np.abs(p.corners @ p.normals[k] - p.h[k]) <= 10 * tol) >= 3]
        blocks.append(PotentialBlock(a=p.normals[keep, 0], b=p.normals[keep, 1], c=p.normals[keep, 2],
                                     d=p.h[keep] - r, r=r, cohesion=[p.cohesion[k] for k in keep],
                                     tension=[p.tension[k] for k in keep],
                                     intactRock=[p.intactRock[k] for k in keep],
                                     jointType=[p.jointType[k] for k in keep]))
    return blocks


__all__ = ["Joint", "JointFileError", "dipNormal", "readJoints", "generateBlocks"]
