"""A straight shear band fitted to a cellwise strain field (2D), for the shear-band cases.

Two stages. (1) A Radon scan finds the band's line: over angles and offsets, the line along
which the excess strain (field minus its mean over the sample) integrates to the most; each
cell is spread across the line by a Gaussian of the cell size. Lines crossing the sample win
over short chords across a corner cluster, but the scan leans towards the longest chords (the
sample's diagonal) by a few degrees. (2) So the band is then fitted as a band: strain =
background + amplitude x exp(-d^2 / 2 w^2), d the distance to the line, least squares over the
cells (weighted by their area) for the background, amplitude, width, angle and offset, started
from the scan. A truncated band (leaving through the sides) does not bias this fit, as the
model is compared only where the sample is. A homogeneous field has no band: its amplitude is
the noise, and the contrast (background + amplitude) / background is about 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Band:
    inclination: float      # degrees from the x axis, in [0, 90]
    angle: float            # the line's direction, degrees in [0, 180) (the sense of the dip)
    point: np.ndarray       # a point of the line
    direction: np.ndarray   # unit vector along the line
    width: float            # the Gaussian width w of the band profile
    contrast: float         # (background + amplitude) / background: ~1 for no band


def polygonAreasAndCentroids(polygons: np.ndarray):
    """Areas (n,) and centroids (n, 2) of convex polygons (n, k, 2), shoelace formula."""
    p, q = polygons, np.roll(polygons, -1, axis=1)
    cross = p[..., 0] * q[..., 1] - q[..., 0] * p[..., 1]
    area = 0.5 * cross.sum(axis=1)
    centroid = ((p + q) * cross[..., None]).sum(axis=1) / (6 * area[:, None])
    return np.abs(area), centroid


def _normal(angle):
    return np.array([-np.sin(angle), np.cos(angle)])


def _radonLine(x, area, excess, h, angleStep):
    """(angle, offset) of the line maximising the line integral of `excess` (cells at x)."""
    angles = np.radians(np.arange(0.0, 180.0, angleStep))
    distance = x @ np.stack([_normal(a) for a in angles], axis=1)    # (cells, angles)
    offsets = np.arange(distance.min(), distance.max() + h / 8, h / 8)
    best = (-np.inf, 0.0, 0.0)
    for k, a in enumerate(angles):    # one angle at a time: a (cells x offsets) kernel
        kernel = np.exp(-0.5 * ((distance[:, k, None] - offsets[None, :]) / h) ** 2)
        score = excess @ kernel
        o = int(np.argmax(score))
        if score[o] > best[0]:
            best = (score[o], a, offsets[o])
    return best[1], best[2]


def fitBand(polygons: np.ndarray, strain: np.ndarray, angleStep: float = 0.5) -> Band:
    """The straight band of the cellwise field ``strain`` (n,) on the cells ``polygons`` (n, k, 2)."""
    from scipy.optimize import least_squares
    polygons = np.asarray(polygons, dtype=float)
    strain = np.asarray(strain, dtype=float)
    if len(strain) != len(polygons) or not np.all(np.isfinite(strain)):
        raise ValueError(f"fitBand: {len(polygons)} cells but {len(strain)} strain values, or non-finite values")
    area, c = polygonAreasAndCentroids(polygons)
    mean = float((strain * area).sum() / area.sum())
    if mean <= 0:
        raise ValueError("fitBand: the strain field has no positive mean")
    h = np.sqrt(area.mean())                              # the cell size
    origin = (c * area[:, None]).sum(axis=0) / area.sum()
    x = c - origin
    angle, offset = _radonLine(x, area, (strain - mean) * area, h, angleStep)
    weight = np.sqrt(area / area.mean())
    size = np.ptp(c, axis=0).max()

    def residuals(q):
        background, amplitude, width, a, o = q
        d = x @ _normal(a) - o
        return weight * (background + amplitude * np.exp(-0.5 * (d / width) ** 2) - strain)

    # the width is bounded below by a quarter of a cell: a band is wider than one noisy cell
    start = [float(np.median(strain)), max(float(strain.max()) - mean, 1e-12 * mean), h, angle, offset]
    fit = least_squares(residuals, start, x_scale=[mean, mean, h, 0.1, h],
                        bounds=([-np.inf, 0.0, h / 4, angle - np.pi / 4, -size],
                                [np.inf, np.inf, size, angle + np.pi / 4, size]))
    background, amplitude, width, a, o = fit.x
    degrees = float(np.degrees(a % np.pi))
    return Band(inclination=min(degrees, 180.0 - degrees), angle=degrees, point=origin + o * _normal(a),
                direction=np.array([np.cos(a), np.sin(a)]), width=float(width),
                contrast=float((background + amplitude) / max(background, 1e-30 * mean)))
