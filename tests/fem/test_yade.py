"""Against Yade: on the same exported RVE packing (one step of deterministic particle velocities, as
tests/dem/measure/test_tangent.py; the scenario cases/yade/fem_rve_tangent.py, also run by
cases/fem/fem_vs_yade.py), the Gauss-point stress and tangent (form="yade") equal Yade's
getStressAndTangent within 1e-6."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

SCENARIO = Path(__file__).resolve().parents[2] / "cases" / "yade" / "fem_rve_tangent.py"


@pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")
def test_rve_stress_and_tangent_equal_yades(rve_file, tmp_path):
    from talus.fem import exportRVE, rve_scene
    exportRVE(rve_file[0], tmp_path / "rve_packing.json")
    params = {"packing": str(tmp_path / "rve_packing.json"), "rveSceneDir": rve_scene.FOLDER}
    ours, yade = (twin.run(SCENARIO, params, program, timeout=300) for program in ("talus", "yade"))
    assert ours["shearing"] > 50                       # contacts with a shear force: Yade's shear term is used
    s, sy = np.array(ours["stress"]), np.array(yade["stress"])
    c, cy = np.array(ours["tangent"]), np.array(yade["tangent"])
    assert np.abs(sy).max() > 1e3                     # the packing is loaded
    assert np.abs(s - sy).max() < 1e-6 * np.abs(sy).max()
    assert np.abs(c - cy).max() < 1e-6 * np.abs(cy).max()
    print(f"stress {np.abs(s - sy).max() / np.abs(sy).max():.2e} tangent {np.abs(c - cy).max() / np.abs(cy).max():.2e}")
