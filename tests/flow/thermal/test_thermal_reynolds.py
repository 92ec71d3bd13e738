"""ThermalEngine.uniformReynolds = -1 (Yade's default): each pore's Nusselt number from its own
Reynolds number, against Yade 2023.02a on the flow scenario of its examples (twin script
cases/yade/thermal_scenario.py, the examples' lattice with centres moved by up to 2 um)."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

ROOT = Path(__file__).resolve().parents[3]
PACKING = Path("/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres")
T0 = 333.15


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    rows = np.loadtxt(PACKING)
    rows[:, :3] += np.random.default_rng(1).uniform(-2e-6, 2e-6, (len(rows), 3))
    packing = tmp_path_factory.mktemp("reynolds") / "jittered.spheres"
    np.savetxt(packing, rows, fmt="%.9e")
    base = {"mode": "flow", "steps": 1000, "packing": str(packing), "yadeInsertionOrder": True}
    out = {(who, re): twin.run(ROOT / "cases/yade/thermal_scenario.py", {**base, "uniformReynolds": re}, who)
           for who in ("talus", "yade") for re in (-1, 10)}
    return {k: (np.array(v["temp"]) - T0, np.array(v["poreTemp"]) - T0) for k, v in out.items()}


@pytest.mark.skipif(not (twin.yade_available() and PACKING.exists()), reason="yade or its examples are not installed")
def test_pore_reynolds_numbers_as_yade(runs):
    spheres, pores = runs[("talus", -1)]
    y_spheres, y_pores = runs[("yade", -1)]
    # the pores' own Reynolds numbers (about 10-100 here) give other temperatures than a uniform 10
    assert np.abs(y_spheres - runs[("yade", 10)][0]).max() > 0.5 * np.abs(y_spheres).max()
    assert np.abs(spheres - y_spheres).max() < 1e-2 * np.abs(y_spheres).max()
    assert np.abs(pores - y_pores).max() < 1e-3 * np.abs(y_pores).max()
    # Yade's own runs of this scenario differ from each other by up to 1.6e-3 in this sum
    # (three runs of the same input gave 1.21608, 1.21808, 1.21808)
    assert spheres.sum() == pytest.approx(y_spheres.sum(), rel=5e-3)


def test_a_negative_uniformReynolds_other_than_minus_one_is_refused():
    from talus.flow import ThermalEngine
    with pytest.raises(ValueError, match="uniformReynolds must be >= 0, or -1"):
        ThermalEngine(uniformReynolds=-2)
