"""Block generation (after Boon et al. 2015 and Yade's BlockGen): split an intact block by
discontinuity planes into Potential Blocks.

    joints = readJoints("joints.csv")              # Yade's joint CSV (dip;dipDir;centreX;...)
    blocks = generateBlocks(PotentialBlock.cuboid((20, 20, 20), r=0.2), joints, r=0.2)
    O.bodies.append([potentialBlock(b, material=rock) for b in blocks])

Sequential subdivision: each joint splits every current block it crosses into the two blocks on
either side (the block's planes plus the joint plane, one way and the other). Planes are in world
coordinates throughout, so the generated blocks sit where they were cut (``potentialBlock(b)``
with ``pos=None``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from talus import _dem
from talus.dem.blocks import PotentialBlock

_REQUIRED = ("dip", "dipDir", "centreX", "centreY", "centreZ")


class JointFileError(ValueError):
    """A malformed joint file; the message names the file and the line."""


@dataclass
class Joint:
    """A discontinuity plane: unit normal, a point on it, and its extent along two directions in
    the plane (``traceX``, ``traceY``; large values: persistent). ``line``: where it was read."""
    normal: np.ndarray
    centre: np.ndarray
    traceX: float = math.inf
    traceY: float = math.inf
    line: int = 0


def dipNormal(dip: float, dipDir: float) -> np.ndarray:
    """Unit normal of a plane of the given dip and dip direction (degrees), in the convention of
    Yade's WedgeYADE example (x north, y east, z down): the normal of dip 90 is horizontal."""
    dipN = math.radians(90.0 - dip)
    dipdirN = math.radians(dipDir - 180.0 if dipDir > 180.0 else dipDir + 180.0)
    return np.array([math.cos(dipdirN) * math.cos(dipN), math.sin(dipdirN) * math.cos(dipN), math.sin(dipN)])


def readJoints(path: str) -> list[Joint]:
    """Joints from Yade's semicolon-separated CSV (header line naming the columns; dip, dipDir,
    centreX, centreY, centreZ required, traceX, traceY optional; other columns, such as joint
    strengths, are read by Yade's BlockGen and ignored here).
    @raises JointFileError naming the file and line for a missing column, a short line or a value
    that is not a finite number (dip in [0, 90], dipDir in [0, 360])."""
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
        for name in _REQUIRED + ("traceX", "traceY"):
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
        joints.append(Joint(dipNormal(values["dip"], values["dipDir"]),
                            np.array([values["centreX"], values["centreY"], values["centreZ"]]),
                            values.get("traceX", math.inf), values.get("traceY", math.inf), number))
    return joints


def _faces(block: PotentialBlock) -> tuple[np.ndarray, np.ndarray]:
    """Normals (n, 3) and face offsets h = d + r of a block."""
    return np.column_stack([block.a, block.b, block.c]), np.asarray(block.d) + block.r


def _geometry(normals, h, r, which):
    return _dem.potential_block_geometry(list(normals[:, 0]), list(normals[:, 1]), list(normals[:, 2]),
                                         list(h - r), r, which)


def _crosses(joint: Joint, corners: np.ndarray, tol: float) -> bool:
    """The joint cuts the block: corners on both sides, and (for a finite joint) the block's
    section lies within the joint's rectangle (centred on its centre, traceX along the plane's
    strike, traceY along its dip line). A joint ending inside a block leaves it intact."""
    side = (corners - joint.centre) @ joint.normal
    if not (side.max() > tol and side.min() < -tol):
        return False
    if math.isinf(joint.traceX) and math.isinf(joint.traceY):
        return True
    n = joint.normal
    strike = np.cross(n, [0.0, 0.0, 1.0])
    strike = strike / np.linalg.norm(strike) if np.linalg.norm(strike) > 1e-12 else np.array([1.0, 0, 0])
    dipLine = np.cross(n, strike)
    rel = corners - joint.centre
    return bool(np.all(np.abs(rel @ strike) <= 0.5 * joint.traceX) and np.all(np.abs(rel @ dipLine) <= 0.5 * joint.traceY))


def generateBlocks(intact: PotentialBlock, joints: list[Joint], r: float | None = None,
                   minVolume: float = 0.0) -> list[PotentialBlock]:
    """Split ``intact`` (planes in world coordinates) by ``joints`` in turn; returns the blocks
    (rounding ``r``, default the intact block's), dropping pieces of volume <= ``minVolume``
    (slivers, which Yade's BlockGen drops with minSize). Planes bounding a piece only at an edge
    or a vertex are removed, so each block keeps only its faces."""
    r = intact.r if r is None else float(r)
    normals, h = _faces(intact)
    geometry = _geometry(normals, h, r, "intact block")
    scale = float(np.ptp(np.asarray(geometry["vertices"]), axis=0).max())
    tol = 1e-9 * scale
    pieces = [(normals, h, np.asarray(geometry["vertices"]))]
    for joint in joints:
        offset = float(joint.normal @ joint.centre)
        split = []
        for n, hh, corners in pieces:
            if not _crosses(joint, corners, tol):
                split.append((n, hh, corners))
                continue
            for sign in (1.0, -1.0):
                n2 = np.vstack([n, sign * joint.normal])
                h2 = np.append(hh, sign * offset)
                try:
                    g = _geometry(n2, h2, r, f"piece cut by the joint of line {joint.line}")
                except ValueError:
                    continue   # no volume on this side after all (the joint only grazes the block)
                if g["volume"] > minVolume:
                    split.append((n2, h2, np.asarray(g["vertices"])))
        pieces = split
    blocks = []
    for n, hh, corners in pieces:
        keep = [k for k in range(len(hh)) if np.sum(np.abs(corners @ n[k] - hh[k]) <= 10 * tol) >= 3]
        blocks.append(PotentialBlock(a=n[keep, 0], b=n[keep, 1], c=n[keep, 2], d=hh[keep] - r, r=r))
    return blocks


__all__ = ["Joint", "JointFileError", "dipNormal", "readJoints", "generateBlocks"]
