"""Yade's FEMxDEM interface on Talus RVEs (talus.fem.msfem, the drop-in modules yade_femxdem/):
a one-element biaxial test written as Yade's examples are, run by run-escript, gives at every
Gauss point the stress of a direct talus.fem.MultiscaleRVEs call on the same RVE file with the
same gradients and Yade's step counts; planar RVEs answer in 2D shapes before the first run."""
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import talus

HERE = Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def planar_rve(tmp_path_factory):
    if not talus.build_info()["components"].get("fem", (False,))[0]:
        pytest.skip("this build has no fem component (see `talus info`)")
    from talus.fem import prepareRVE
    folder = tmp_path_factory.mktemp("msfem")
    info = prepareRVE(folder / "0.yade.gz", size=0.4, rMean=0.03, sigma=-1e5, young=1e8, planar=True, damping=0.1)
    return folder, info


def test_planar_rve_answers_in_2d_before_the_first_run(planar_rve):
    from talus.fem import MultiscaleRVEs, isPlanarRVE
    path = planar_rve[0] / "0.yade.gz"
    assert isPlanarRVE(str(path))
    s, t = MultiscaleRVEs(str(path), numPoints=2).getStressAndTangent()
    assert s.shape == (2, 2, 2) and t.shape == (2, 3, 3)
    s3, t3 = MultiscaleRVEs(str(path), numPoints=2, dim=3).getStressAndTangent()
    assert s3.shape == (2, 3, 3) and t3.shape == (2, 6, 6)
    np.testing.assert_allclose(s3[:, :2, :2], s, rtol=0, atol=1e-9 * np.abs(s).max())


def test_prepare_reports_the_residual_shear(planar_rve):
    info = planar_rve[1]
    assert 0 <= info["shear"] < 0.5 and "shearBefore" in info


@pytest.mark.skipif(shutil.which("run-escript") is None, reason="escript is not installed")
def test_dropin_equals_direct_calls(planar_rve):
    from talus.fem import MultiscaleRVEs
    from talus.fem.msfem import rveSettings, yadeSteps
    folder, _ = planar_rve
    python = Path(talus.__file__).resolve().parent.parent
    dropins = python / "yade_femxdem"
    assert (dropins / "msFEM2D.py").exists(), "the build has not copied fem/python/yade_femxdem"
    env = {**os.environ, "PYTHONPATH": f"{dropins}:{python}", "OMP_NUM_THREADS": "1",
           "TALUS_MSFEM": json.dumps({"damping": 0.1})}     # the Talus-only keywords of unchanged scripts
    steps, vel = 2, -2e-3
    done = subprocess.run(["run-escript", HERE / "msfem_biaxial.py", str(steps), str(vel), "-1e5"], cwd=folder,
                          capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    out = json.loads((folder / "out.json").read_text())
    assert out["initialShape"] == [2, 2] and out["initialTangentShape"] == [2, 2, 2, 2]
    assert "Convergence reached" in done.stdout
    n = out["numg"]
    assert rveSettings(folder / "0.yade.gz")["planar"]
    rves = MultiscaleRVEs(str(folder / "0.yade.gz"), numPoints=n, form="yade", damping=0.1)
    for k in range(steps):
        g = np.array(out["increments"][k])
        assert np.abs(g[:, 1, 1]).max() > 1e-4          # the load step strained the points
        rves.run(g, nSteps=yadeSteps(g))
        s, _ = rves.getStressAndTangent()
        rves.commit()
        s = 0.5 * (s + np.swapaxes(s, 1, 2))
        theirs = np.array(out["stress"][k])
        print(f"step {k + 1}: drop-in vs direct {np.abs(theirs - s).max() / np.abs(s).max():.1e}")
        np.testing.assert_allclose(theirs, s, rtol=0, atol=1e-10 * np.abs(s).max())
    # saveGauss2D writes Yade's format: "<name> <count>" then the rows of each point's tensor
    lines = (folder / f"gauss_{steps}.dat").read_text().splitlines()
    assert lines[0] == f"strain {n}" and len(lines[1].split()) == 4
    stress = lines.index(f"stress {n}")
    np.testing.assert_allclose(np.array(lines[stress + 1].split(), float).reshape(2, 2), out["stress"][-1][0])
    assert np.all(np.array(out["voidRatio"]) > 0)
