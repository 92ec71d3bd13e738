"""The straight-band fit of cellwise shear strain (talus.fem.band) on synthetic fields: a band at a
known angle and position is found within a degree, also next to corner clusters off the band (the
case that misled the principal axis of the strongest cells) and in a conjugate pair, and a
homogeneous field is no band."""
import numpy as np
import pytest

from talus.fem.band import fitBand, polygonAreasAndCentroids


def grid(nx, ny, W=1.0, H=2.0, skew=0.0):
    """The cells of a W x H rectangle, nx x ny quadrilaterals, optionally sheared (x += skew * y)."""
    xs, ys = np.linspace(0, W, nx + 1), np.linspace(0, H, ny + 1)
    cells = np.array([[(xs[i], ys[j]), (xs[i + 1], ys[j]), (xs[i + 1], ys[j + 1]), (xs[i], ys[j + 1])]
                      for j in range(ny) for i in range(nx)])
    cells[..., 0] += skew * cells[..., 1]
    return cells


def band_field(cells, degrees, through, halfWidth=0.15, peak=5.0, noise=0.05, seed=0):
    """Cell averages (5 x 5 points per cell) of 1 + a tent of strain, `peak` high and `halfWidth`
    wide each side, along the line at `degrees` through `through`; plus 5 % noise per cell. The
    tent is not the fit's Gaussian profile, so the test does not measure the model against itself."""
    s = (np.arange(5) + 0.5) / 5
    u, v = [w.ravel() for w in np.meshgrid(s, s)]
    p = ((1 - u) * (1 - v))[None, :, None] * cells[:, None, 0] + (u * (1 - v))[None, :, None] * cells[:, None, 1] \
        + (u * v)[None, :, None] * cells[:, None, 2] + ((1 - u) * v)[None, :, None] * cells[:, None, 3]
    a = np.radians(degrees)
    d = (p - np.asarray(through)) @ np.array([-np.sin(a), np.cos(a)])
    field = 1.0 + peak * np.maximum(0.0, 1 - np.abs(d) / halfWidth).mean(axis=1)
    return field * (1 + noise * np.random.default_rng(seed).standard_normal(len(cells)))


def test_areas_and_centroids_of_a_unit_square():
    area, c = polygonAreasAndCentroids(np.array([[(0, 0), (2, 0), (2, 1), (0, 1)]], dtype=float))
    assert area[0] == pytest.approx(2.0) and c[0] == pytest.approx([1.0, 0.5])


@pytest.mark.parametrize("mesh", [(4, 8), (6, 12), (8, 16)])
@pytest.mark.parametrize("degrees, through", [(60, (0.5, 1.0)), (125, (0.4, 1.1)), (50, (0.6, 0.8))])
def test_a_band_is_found_at_its_angle(mesh, degrees, through):
    cells = grid(*mesh)
    band = fitBand(cells, band_field(cells, degrees, through))
    assert band.angle == pytest.approx(degrees, abs=1.5)
    assert band.inclination == pytest.approx(min(degrees, 180 - degrees), abs=1.5)
    # the fitted line passes through the band's point
    offset = np.cross(band.direction, np.asarray(through) - band.point)
    assert abs(offset) < 0.05
    assert band.contrast > 2.0 and 0.03 < band.width < 0.15


@pytest.mark.parametrize("degrees", [48, 58, 125])
def test_a_band_is_found_on_an_irregular_mesh(degrees):
    # The shear-band case fits unstructured quadrilaterals: here the 8 x 16 grid with every
    # interior node moved at random by up to 0.3 of a cell, so that no cell edge or diagonal
    # runs at one angle.
    cells = grid(8, 16)
    corners = cells.reshape(-1, 2)
    nodes, index = np.unique(np.round(corners, 12), axis=0, return_inverse=True)
    interior = (nodes[:, 0] > 0) & (nodes[:, 0] < 1) & (nodes[:, 1] > 0) & (nodes[:, 1] < 2)
    nodes[interior] += 0.3 * 0.125 * np.random.default_rng(5).uniform(-1, 1, (interior.sum(), 2))
    cells = nodes[index.ravel()].reshape(cells.shape)
    band = fitBand(cells, band_field(cells, degrees, (0.5, 1.0)))
    assert band.inclination == pytest.approx(min(degrees, 180 - degrees), abs=1.5)


def test_corner_clusters_off_the_band_do_not_tilt_it():
    cells = grid(6, 12, skew=0.05)
    _, c = polygonAreasAndCentroids(cells)
    field = band_field(cells, 58, (0.5, 1.0), peak=3.0)
    for corner in ((1.0, 0.0), (0.0, 2.0)):      # clusters in the other two corners
        field += 3.0 * np.exp(-0.5 * (np.linalg.norm(c - corner, axis=1) / 0.15) ** 2)
    band = fitBand(cells, field)
    assert band.inclination == pytest.approx(58, abs=2.0)


@pytest.mark.parametrize("mesh, within", [((4, 8), 4.0), ((8, 16), 1.0)])
@pytest.mark.parametrize("degrees", [52, 58])
@pytest.mark.parametrize("other", [1.0, 0.5])
def test_a_conjugate_pair_gives_the_inclination_of_its_bands(mesh, within, degrees, other):
    # An imperfection at the centre may start two crossing bands, at +- the same inclination: the
    # fit follows one of them (the other is left in the residual) and its inclination is theirs
    # (on the coarse mesh, cells wider than the bands, the crossing arm pulls the fit flatter by up to
    # 3.4 degrees; within 0.6 on the fine mesh).
    cells = grid(*mesh)
    field = band_field(cells, degrees, (0.5, 1.0)) + other * (band_field(cells, 180 - degrees, (0.5, 1.0), seed=1) - 1)
    assert fitBand(cells, field).inclination == pytest.approx(degrees, abs=within)


def test_a_homogeneous_field_is_no_band():
    cells = grid(6, 12)
    field = 1.0 + 0.1 * np.random.default_rng(3).standard_normal(len(cells))
    assert fitBand(cells, field).contrast < 1.15
    assert fitBand(cells, np.ones(len(cells))).contrast == pytest.approx(1.0)


def test_bad_fields_are_reported():
    cells = grid(2, 2)
    with pytest.raises(ValueError, match="4 cells but 3"):
        fitBand(cells, np.ones(3))
    with pytest.raises(ValueError, match="non-finite"):
        fitBand(cells, np.array([1.0, np.nan, 1.0, 1.0]))
