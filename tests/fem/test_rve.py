"""Gauss-point calls (talus.fem.MultiscaleRVEs): the batched C++ RVEs against a direct talus.dem
run of the same packing under the same cell deformation, commit/rollback, per-point outputs and
bad input."""
import numpy as np
import pytest

from talus.dem import Scene, avgNumInteractions, fabricTensor, getStressAndTangent, porosity

N_STEPS = 40
G1 = np.array([[-2e-3, 5e-4, 0], [1e-4, 1e-3, -3e-4], [0, 2e-4, 5e-4]])   # stretch and rotation
G2 = np.array([[1e-3, 0, 2e-4], [-6e-4, -2e-3, 0], [0, 0, 8e-4]])


def direct(path, grads):
    """The reference: the RVE file in a talus.dem Scene driven through O.cell.velGrad."""
    from talus.fem.direct import replay
    return replay(path, grads, N_STEPS)[0]


def rel(a, b):
    return np.abs(np.asarray(a) - np.asarray(b)).max() / np.abs(np.asarray(b)).max()


@pytest.fixture
def rves(rve_file):
    from talus.fem import MultiscaleRVEs
    return MultiscaleRVEs(str(rve_file[0]), numPoints=3, nSteps=N_STEPS)


def test_prepared_rve_is_consolidated(rve_file):
    path, info = rve_file
    assert np.abs(np.array(info["stress"]) / -1e5 - 1).max() < 1e-3
    assert info["spheres"] > 50 and 0.3 < info["porosity"] < 0.5


def test_calls_equal_a_direct_dem_run_with_commit(rve_file, rves):
    path = rve_file[0]
    rves.run(np.array([G1] * 3))
    rves.commit()
    rves.run(np.array([G2, G1, G2]))
    stress, tangent = rves.getStressAndTangent()
    S = direct(path, [G1, G2])
    s_ref, c_ref = getStressAndTangent(scene=S)
    assert rel(stress[0], s_ref) < 1e-10 and rel(stress[2], s_ref) < 1e-10
    assert rel(tangent[0], c_ref) < 1e-10
    assert rel(stress[1], getStressAndTangent(scene=direct(path, [G1, G1]))[0]) < 1e-10   # its own path
    np.testing.assert_allclose(rves.getPorosity()[0], porosity(scene=S), rtol=1e-12)
    np.testing.assert_allclose(rves.getVoidRatio()[0], porosity(scene=S) / (1 - porosity(scene=S)), rtol=1e-12)
    np.testing.assert_allclose(rves.getCoordination()[0], avgNumInteractions(scene=S), rtol=1e-12)
    np.testing.assert_allclose(rves.getFabric()[0], fabricTensor(scene=S), rtol=1e-12)


def test_cell_ends_exactly_at_the_imposed_gradient(rves):
    h0 = rves._cpp.cellSize(0)
    rves.run(np.array([G1, G2, G1]))
    np.testing.assert_allclose(rves._cpp.cellSize(1), (np.eye(3) + G2) @ h0, rtol=0, atol=1e-14 * np.abs(h0).max())


def test_rollback_returns_to_the_committed_state(rves):
    rves.run(np.array([G1] * 3))
    first, _ = rves.getStressAndTangent()
    rves.run(np.array([G2] * 3))          # another trial from the same committed state
    rves.rollback()
    assert not rves._cpp.hasTrial(0)
    rves.run(np.array([G1] * 3))
    again, _ = rves.getStressAndTangent()
    assert rel(again, first) < 1e-12


def test_rigid_rotation_turns_the_stress(rves):
    s0, _ = rves.getStressAndTangent()
    a = 0.02
    R = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rves.run(np.array([R - np.eye(3)] * 3))
    s1, _ = rves.getStressAndTangent()
    rotated = R @ s0[0] @ R.T
    assert rel(s1[0], rotated) < 0.02                  # close to the turned stress ...
    assert rel(s0[0], rotated) > 0.01 * rel(s1[0], rotated)   # ... not merely unchanged
    rot = rves.getRotation()[0]
    assert rot[2] == pytest.approx(a, rel=0.3)       # particles turn with the cell on average


def test_plane_strain_gradients(rves):
    g2 = G1[:2, :2]
    rves.run(np.array([g2] * 3))
    s2, c2 = rves.getStressAndTangent()
    assert s2.shape == (3, 2, 2) and c2.shape == (3, 3, 3)
    padded = np.zeros((3, 3))
    padded[:2, :2] = g2
    rves.run(np.array([padded] * 3))
    s3, c3 = rves.getStressAndTangent()
    assert np.array_equal(s2[0], s3[0][:2, :2])
    assert np.array_equal(c2[0], c3[0][np.ix_([0, 1, 5], [0, 1, 5])])


def test_failed_dem_run_keeps_the_committed_state(rves):
    s0, _ = rves.getStressAndTangent()
    crush = np.array([np.zeros((3, 3)), np.diag([-0.6, -0.6, -0.6]), np.zeros((3, 3))])
    rves.nSteps = 2                       # the second step sees overlaps of about a radius
    with pytest.raises(RuntimeError, match=r"^Gauss point 1: RVE .* DEM step failed .*overlap.*committed state was restored"):
        rves.run(crush)
    assert not rves._cpp.hasTrial(1)
    rves.nSteps = N_STEPS
    rves.run(np.zeros((3, 3, 3)))
    s1, _ = rves.getStressAndTangent()
    assert rel(s1[1], s0[1]) < 0.05                     # back near the committed stress, not crushed


def test_bad_input(rve_file, tmp_path):
    from talus.fem import MultiscaleRVEs
    rves = MultiscaleRVEs(str(rve_file[0]), numPoints=2, nSteps=2)
    with pytest.raises(ValueError, match="Gauss-point count mismatch"):
        rves.run(np.zeros((3, 3, 3)))
    g = np.zeros((2, 3, 3))
    g[1, 0, 2] = np.nan
    with pytest.raises(ValueError, match="Gauss point 1 is not finite"):
        rves.run(g)
    with pytest.raises(ValueError, match="Gauss point 1: displacement gradient is not finite"):   # the C++ check
        rves._cpp.deform(g, 2)
    missing = tmp_path / "nothing.h5"
    with pytest.raises(ValueError, match=f"Gauss point 1: RVE file '{missing}' does not exist"):
        MultiscaleRVEs([str(rve_file[0]), str(missing)])
    S = Scene()
    S.save(str(tmp_path / "plain.h5"))
    with pytest.raises(ValueError, match="plain.h5 is not periodic"):
        MultiscaleRVEs(str(tmp_path / "plain.h5"), numPoints=1)
    (tmp_path / "junk.h5").write_text("not hdf5")
    with pytest.raises(ValueError, match="junk.h5' is not a readable Talus checkpoint"):
        MultiscaleRVEs(str(tmp_path / "junk.h5"), numPoints=1)
    from talus import _fem
    with pytest.raises(ValueError, match="Gauss point 1: no scene \\(None\\) and no checkpoint path"):   # the raw binding
        _fem.GaussPointRVEs([str(rve_file[0]), None], "Law2_ScGeom_FrictPhys_CundallStrack", 0.2)


@pytest.fixture(scope="module")
def planar_rve(tmp_path_factory):
    from talus.fem import prepareRVE
    path = tmp_path_factory.mktemp("planar") / "rve2d.h5"
    return path, prepareRVE(path, size=0.8, rMean=0.03, planar=True, sigma=-1e5, young=1e8)


def test_planar_rve(planar_rve):
    """The seed's 2D-like RVE: one layer of spheres moving in a plane, compacted in x and y."""
    from talus.fem import MultiscaleRVEs
    from talus.fem.direct import replay
    path, info = planar_rve
    assert np.abs(np.array(info["stress"][:2]) / -1e5 - 1).max() < 1e-3 and info["stress"][2] == 0
    S = Scene()
    S.load(str(path))
    z = S.positions()[:, 2]
    assert np.ptp(z) == 0 and S.cell.hSize[2, 2] > 2 * S.radii().max()     # one layer, no contact through z
    rves = MultiscaleRVEs(str(path), numPoints=2, nSteps=20)
    g = np.array([[1e-3, 2e-4], [0, -2e-3]])
    rves.run(np.array([g, g]))
    stress, _ = rves.getStressAndTangent()
    S, ref = replay(path, [g], 20)
    assert rel(stress[0], ref[0][:2, :2]) < 1e-10
    assert np.ptp(S.positions()[:, 2]) == 0                                  # still in the plane


def test_a_heterogeneous_sample_keeps_each_points_packing(rve_file, planar_rve):
    # One RVE file per Gauss point (here a 3D packing and a planar one): each point follows its own
    # packing, as a direct DEM run of that file under the same gradient.
    from talus.fem import MultiscaleRVEs
    from talus.fem.direct import replay
    files = [rve_file[0], planar_rve[0]]
    g = np.array([[1e-3, 2e-4], [0, -2e-3]])
    mixed = MultiscaleRVEs([str(f) for f in files], nSteps=20)
    mixed.run(np.array([g, g]))
    stress, _ = mixed.getStressAndTangent()
    voids = mixed.getVoidRatio()
    for k, path in enumerate(files):
        S, ref = replay(path, [g], 20)
        assert rel(stress[k], ref[0][:2, :2]) < 1e-10
        np.testing.assert_allclose(voids[k], porosity(scene=S) / (1 - porosity(scene=S)), rtol=1e-12)
    assert abs(voids[1] / voids[0] - 1) > 0.1                              # two different packings
