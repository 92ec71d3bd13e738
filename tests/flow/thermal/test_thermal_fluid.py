"""ThermalEngine with the pore fluid (advection, sphere-fluid exchange, conduction through the
fluid): the set-up of Yade's noFlowScenario.py (thermal_noflow.py, the same script under Yade and
Talus) against Yade 2023.02a's numbers; bad input of the fluid parameters."""
import json
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
PACKING = Path("/usr/share/doc/yade/examples/ThermalEngine/5cmEdge_1mm.spheres")
YADE = json.loads((HERE.parent / "data" / "thermal_noflow_yade.json").read_text())
T_SPHERES, T_FLUID = 333.15, 343.15


@pytest.mark.skipif(not PACKING.exists(), reason="Yade's examples (the packing of noFlowScenario.py) are not installed")
def test_noflow_scenario_matches_yade(talus_cmd, tmp_path):
    """2000 steps of 1e-5 s: the spheres warm by up to 0.034 K and the water cools by 0.054 K.
    Sphere temperatures equal Yade's to round-off (measured 3.4e-13 K). Yade's pores lag one step:
    its pore temperatures after 2000 steps are Talus's after 1999 (measured 1.6e-10 K), 2.7e-5 K
    (0.05 % of the change) from Talus's after 2000; a heat capacity or an exchange area 1 % off
    moves the pores by 5e-4 K."""
    out = tmp_path / "noflow.json"
    talus_cmd("run", "-j", "1", HERE / "thermal_noflow.py", out, cwd=tmp_path)
    talus = json.loads(out.read_text())
    assert talus["ids"] == YADE["ids"] and talus["contacts"] == YADE["contacts"]
    spheres, yade = np.array(talus["temp"]), np.array(YADE["temp"])
    assert 0.03 < (yade - T_SPHERES).max() < 0.04
    np.testing.assert_allclose(spheres, yade, rtol=0, atol=1e-11)
    fluid = np.array(YADE["poreTemp"])
    assert np.all((T_FLUID - fluid > 0.03) & (T_FLUID - fluid < 0.06))
    np.testing.assert_allclose(talus["poreTempBefore"], fluid, rtol=0, atol=1e-8)
    np.testing.assert_allclose(talus["poreTemp"], fluid, rtol=0, atol=1e-3 * (T_FLUID - fluid).max())
