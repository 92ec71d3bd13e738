"""SpherePack.makeCloud: counts, size distributions, no overlaps, determinism, and the same
clouds as Yade's for the same seed; save/load and toSimulation."""
import itertools
import shutil
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.dem import *  # noqa: F401,F403

TWINS = Path(__file__).parents[1] / "yade_twins" / "engines"  # the scripts Yade and Talus both run


def arrays(sp):
    c = np.array([s[0] for s in sp])
    r = np.array([s[1] for s in sp])
    return c, r


def min_gap(c, r, cell=None):
    """Smallest surface gap between two spheres (periodic images with ``cell``)."""
    d = c[:, None, :] - c[None, :, :]
    if cell is not None:
        d -= np.round(d / cell) * cell
    dist = np.linalg.norm(d, axis=2) - (r[:, None] + r[None, :])
    np.fill_diagonal(dist, np.inf)
    return dist.min()


def test_uniform_cloud_inside_box_no_overlap_and_radii():
    sp = pack.SpherePack()
    n = sp.makeCloud((0, 0, 0), (2, 1, 1), rMean=.06, rRelFuzz=.3, seed=4)
    c, r = arrays(sp)
    assert n == len(sp) > 100
    assert np.all(r >= .06 * .7 - 1e-15) and np.all(r <= .06 * 1.3 + 1e-15)
    assert np.all(c - r[:, None] >= -1e-12) and np.all(c + r[:, None] <= np.array([2, 1, 1]) + 1e-12)
    assert min_gap(c, r) > 0


def test_num_gives_exact_count_and_deterministic_radii():
    sp = pack.SpherePack()
    assert sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=.05, rRelFuzz=.5, num=150, seed=1) == 150
    _, r = arrays(sp)
    # radii decrease linearly from rMean (1 + fuzz (N - 1)/(N + 1)) ... as Yade's deterministic sizes
    N = 150
    expected = .05 * (2 * ((N - np.arange(N) + .5) / (N + 1.) - .5) * .5 + 1)
    assert np.allclose(r, expected, rtol=1e-14)


def test_porosity_mode_reaches_num_and_target_porosity():
    sp = pack.SpherePack()
    assert sp.makeCloud((0, 0, 0), (1, 1, 1), rRelFuzz=.2, num=300, porosity=.8, seed=2) == 300
    c, r = arrays(sp)
    solid = np.sum(4 / 3 * np.pi * r ** 3)
    assert abs((1 - solid) - .8) < .02     # the radius follows from the porosity asked for


def test_psd_by_count_follows_the_distribution():
    sp = pack.SpherePack()
    sizes, cumm = [.04, .06, .1], [0, .5, 1]
    sp.makeCloud((0, 0, 0), (1, 1, 1), psdSizes=sizes, psdCumm=cumm, num=400, seed=3)
    assert len(sp) == 400
    _, r = arrays(sp)
    d = 2 * r / sp.appliedPsdScaling
    # by count: half of the spheres below the middle sieve size
    assert abs(np.mean(d < .06 - 1e-12) - .5) < 0.01
    edges, passing = sp.psd(bins=20, mass=False)
    assert len(edges) == 21 and passing[0] == 0 and abs(passing[-1] - 1) < 1e-12
    assert np.all(np.diff(passing) >= 0)


def test_psd_of_equal_spheres_is_one_bin():
    sp = pack.SpherePack([((0, 0, 0), .1), ((1, 0, 0), .1)])
    edges, cumm = sp.psd(bins=4)
    assert np.allclose(edges, [-.3, -.05, .2, .45, .7]) and np.allclose(cumm, [0, 0, 0, 1, 1])  # d = .2 falls in bin int(4 * .5 / 1) = 2


def test_periodic_cloud_has_no_overlap_across_the_boundary():
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=.08, rRelFuzz=.3, periodic=True, seed=9)
    c, r = arrays(sp)
    assert np.allclose(sp.cellSize, 1) and len(sp) > 50
    assert min_gap(c, r, cell=np.ones(3)) > 0
    scene = Scene()
    ids = sp.toSimulation(scene)
    assert scene.periodic and len(ids) == len(sp) and np.allclose(scene.cell.hSize, np.eye(3))
    assert abs(porosity(scene=scene) - (1 - np.sum(4 / 3 * np.pi * r ** 3))) < 1e-12


def test_seed_is_deterministic_and_seeds_differ():
    def cloud(seed):
        sp = pack.SpherePack()
        sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=.07, rRelFuzz=.4, seed=seed)
        return np.array([list(c) + [r] for c, r in sp])
    a, b, c = cloud(5), cloud(5), cloud(6)
    assert np.array_equal(a, b)
    assert a.shape != c.shape or not np.array_equal(a, c)


def test_bad_arguments_are_named():
    sp = pack.SpherePack()
    with pytest.raises(ValueError, match="psdCumm"):
        sp.makeCloud((0, 0, 0), (1, 1, 1), psdSizes=[.1, .2], psdCumm=[0, .5])
    with pytest.raises(ValueError, match="rMean"):
        sp.makeCloud((0, 0, 0), (1, 1, 1))
    with pytest.raises(ValueError, match="maxCorner"):
        sp.makeCloud((0, 0, 0), (-1, 1, 1), rMean=.1, periodic=True)   # a plain box may be inverted, as Yade's
    with pytest.raises(ValueError, match="sphere #1"):
        pack.SpherePack([((0, 0, 0), .1), ((1, 0, 0), -1)])


def test_save_load_round_trip(tmp_path):
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=.1, rRelFuzz=.3, periodic=True, seed=1)
    sp.save(tmp_path / "cloud.txt")
    back = pack.SpherePack()
    back.load(tmp_path / "cloud.txt")
    assert np.array_equal(back.cellSize, sp.cellSize)
    assert all(np.array_equal(a[0], b[0]) and a[1] == b[1] for a, b in itertools.zip_longest(sp, back))


@pytest.mark.skipif(shutil.which("yade") is None, reason="yade is not installed")
def test_seeded_clouds_equal_yades():
    ours, theirs = (twin.run(TWINS / "cloud_side_by_side.py", {}, who) for who in ("talus", "yade"))
    for name in theirs:
        assert ours[name]["n"] == theirs[name]["n"], name
        a, b = np.array(ours[name]["spheres"]), np.array(theirs[name]["spheres"])
        assert a.shape == b.shape and np.max(np.abs(a - b)) <= 1e-14, name


def test_compressed_cloud_to_porosity_and_to_stress():
    dense = pack.compressedCloud((0, 0, 0), (1, 1, 1), rRelFuzz=.3, num=100, seed=3, porosity=.42, stress=None)
    assert len(dense) == 100 and dense.isPeriodic
    c, r = arrays(dense)
    solid = np.sum(4 / 3 * np.pi * r ** 3)
    assert 1 - solid / np.prod(dense.cellSize) == pytest.approx(.42, abs=1e-6)
    assert np.all(c >= 0) and np.all(c < dense.cellSize)
    stressed = pack.compressedCloud((0, 0, 0), (1, 1, 1), rRelFuzz=.3, num=100, seed=3, stress=-2e4)
    scene = Scene()
    stressed.toSimulation(scene)
    scene.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                     [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator()]
    scene.dt = 1e-6
    scene.step()
    assert np.trace(getStress(scene=scene)) / 3 == pytest.approx(-2e4, rel=.02)
    with pytest.raises(ValueError, match="compression"):
        pack.compressedCloud((0, 0, 0), (1, 1, 1), rRelFuzz=.3, num=20, seed=3, stress=1e4)


def periodic_overlap(c, r, h):
    """Largest overlap between two spheres, or between a sphere and its own image, over the
    periodic images of the lattice ``h`` (edges as columns), by brute force over offsets -3..3."""
    worst = -np.inf
    for k in itertools.product(range(-3, 4), repeat=3):
        dist = np.linalg.norm(c[None, :, :] - c[:, None, :] + h @ np.array(k, dtype=float), axis=2)
        if k == (0, 0, 0):
            np.fill_diagonal(dist, np.inf)
        worst = max(worst, np.max(r[:, None] + r[None, :] - dist))
    return worst


# A sheared cell (three shear terms), its shortest period (0.917) below its shortest edge (1).
SHEARED = np.array([[1, .9, .3], [0, 1, -.6], [0, 0, .8]])


def test_sheared_periodic_cloud_has_no_overlap_through_any_image():
    sp = pack.SpherePack()
    n = sp.makeCloud((.2, -.1, 0), rMean=.07, rRelFuzz=.3, periodic=True, seed=6, hSize=SHEARED)
    c, r = arrays(sp)
    assert n == len(sp) > 80 and sp.isPeriodic and sp.isSheared
    assert np.array_equal(sp.hSize, SHEARED)
    assert periodic_overlap(c, r, SHEARED) < 0
    # centres fill the parallelepiped minCorner + hSize u, u in [0, 1)^3
    u = np.linalg.solve(SHEARED, (c - (.2, -.1, 0)).T).T
    assert np.all(u >= 0) and np.all(u < 1) and np.all(u.min(axis=0) < .1) and np.all(u.max(axis=0) > .9)
    with pytest.raises(ValueError, match="sheared; use hSize"):
        sp.cellSize


def test_sheared_cloud_reaches_the_count_and_porosity_asked_for():
    sp = pack.SpherePack()
    assert sp.makeCloud(rRelFuzz=.2, num=150, porosity=.75, periodic=True, seed=2, hSize=SHEARED) == 150
    c, r = arrays(sp)
    solid = np.sum(4 / 3 * np.pi * r ** 3) / np.linalg.det(SHEARED)
    assert 1 - solid == pytest.approx(.75, abs=.02)    # rMean follows from the cell's volume det(hSize)
    assert periodic_overlap(c, r, SHEARED) < 0


def test_sheared_cloud_to_simulation_keeps_the_cell_and_makes_no_contact(tmp_path):
    sp = pack.SpherePack()
    sp.makeCloud(rMean=.08, rRelFuzz=.2, periodic=True, seed=3, hSize=SHEARED)
    scene = Scene()
    scene.materials.append(FrictMat())
    ids = sp.toSimulation(scene)
    assert scene.periodic and np.array_equal(scene.cell.hSize, SHEARED) and len(ids) == len(sp)
    scene.engines = [ForceResetter(), InsertionSortCollider(),
                     InteractionLoop([], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                     NewtonIntegrator()]
    scene.dt = 1e-5
    scene.step()
    assert scene._cpp.realContactCount() == 0      # the collider agrees: nothing touches through the boundary
    sp.save(tmp_path / "sheared.txt")
    back = pack.SpherePack()
    back.load(tmp_path / "sheared.txt")
    assert np.array_equal(back.hSize, SHEARED) and len(back) == len(sp)


def test_impossible_sheared_clouds_are_refused_with_the_reason():
    sp = pack.SpherePack()
    # the shortest period is |(0.2, 0.4, 0.8)| = 0.917 (edge 3 + edge 2 - edge 1): a 0.5-radius sphere meets its own image
    with pytest.raises(ValueError, match=r"radius up to 0.50* .* shortest period is 0.9165.*own image"):
        sp.makeCloud(rMean=.5, periodic=True, hSize=SHEARED)
    with pytest.raises(ValueError, match="positive determinant"):
        sp.makeCloud(rMean=.1, periodic=True, hSize=[[1, 1, 0], [1, 1, 0], [0, 0, 1]])
    with pytest.raises(ValueError, match="needs periodic=True"):
        sp.makeCloud(rMean=.1, hSize=SHEARED)
    with pytest.raises(ValueError, match="hSize is zero"):
        sp.makeCloud(rMean=.1, periodic=True, hSize=np.zeros((3, 3)))
    assert len(sp) == 0
