"""TwoPhaseFlowEngine's per-pore setters (setPoreBodyRadius, setPoreThroatRadius,
setCellSaturation, setCellIsWRes, setCellIsNWRes) and updatePressure: the drainage of
cases/yade/twophase/twophase_setters.py from a state set pore by pore, on the 400-sphere cloud of
data/pore_packing.txt, against Yade 2023.02a's run of it (data/twophase_setters_yade_reference.json,
written by twophase_setters_yade_reference.py), and bad input."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.flow import TwoPhaseFlowEngine

HERE = Path(__file__).resolve().parent
PACKING = HERE.parent / "data" / "pore_packing.txt"
REF = json.loads((HERE.parent / "data" / "twophase_setters_yade_reference.json").read_text())
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_setters.py"
SPHERES = np.loadtxt(PACKING)


def run(every):
    return twin.run(SCENARIO, {"pcs": REF["params"]["pcs"], "every": every, "packing": str(PACKING)}, "talus")


def test_set_state_drains_as_yade():
    """The saturation after each step, every pore's phase at the end and the pressures
    updatePressure() gives as Yade's; the set-up changes the drainage (against none)."""
    ours = run(REF["params"]["every"])
    np.testing.assert_allclose(ours["saturations"], REF["saturations"], rtol=0, atol=1e-12)
    assert ours["cells"] == REF["cells"]
    assert ours["pressures"] == pytest.approx(REF["pressures"], abs=1e-12)
    assert {0.0, -REF["params"]["pcs"][0]} == set(REF["pressures"].values())   # both phases sampled
    plain = run([0, 0, 0])
    assert REF["saturations"][0] < plain["saturations"][0] - 0.05  # the non-wetting pores set
    assert max(abs(a - b) for a, b in zip(REF["saturations"], plain["saturations"])) > 0.05


def engine():
    tp = TwoPhaseFlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0])
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3], ids=np.arange(6, 6 + len(SPHERES)))
    tp.initialization()
    return tp


def test_setters_and_update_pressure():
    tp = engine()
    a, b = next((i, n) for i in range(tp.nCells()) for n in tp.getNeighbors(i) if n >= 0)
    tp.setPoreThroatRadius(a, b, 0.25)
    assert tp.getPoreThroatRadius(b, a) == 0.25
    tp.setPoreBodyRadius(a, 0.125)
    assert tp.getCellInSphereRadius(a) == 0.125
    tp.setCellSaturation(a, 0.0)
    tp.setCellIsNWRes(a, True)
    tp.setCellIsWRes(a, False)
    assert (tp.getCellSaturation(a), tp.getCellIsNWRes(a), tp.getCellIsWRes(a)) == (0.0, True, False)
    tp.bndCondValue = [0, 0, -3.0, 2.0, 0, 0]
    tp.updatePressure()
    assert tp.getCellPressure(a) == 2.0 and tp.getCellPressure(b) == -3.0


def test_bad_input():
    with pytest.raises(RuntimeError, match=r"call initialization\(\) first"):
        TwoPhaseFlowEngine().setCellSaturation(0, 1.0)
    tp = engine()
    with pytest.raises(ValueError, match=r"setCellSaturation.*\[0, 1\]"):
        tp.setCellSaturation(0, 1.5)
    with pytest.raises(ValueError, match=r"setCellSaturation"):
        tp.setCellSaturation(0, math.nan)
    with pytest.raises(ValueError, match=r"setPoreBodyRadius.*> 0"):
        tp.setPoreBodyRadius(0, -1.0)
    with pytest.raises(ValueError, match=r"setPoreThroatRadius.*finite"):
        tp.setPoreThroatRadius(0, next(n for n in tp.getNeighbors(0) if n >= 0), math.inf)
    with pytest.raises(ValueError, match=r"setPoreThroatRadius: pores 0 and 0 are not neighbours"):
        tp.setPoreThroatRadius(0, 0, 0.1)
    with pytest.raises(IndexError, match="cell id must be an integer"):
        tp.setCellIsWRes(tp.nCells(), True)


def test_yade_check_gate(talus_cmd, tmp_path):
    """Yade's check_TwoPhaseFlowEngine_PressureInjection.py runs only when its script globals
    have 'PFVFLOW' and 'TWOPHASEFLOW' in `features` (as under yade -x)."""
    script = tmp_path / "gate.py"
    script.write_text("print('GATE', ('PFVFLOW' in features) and ('TWOPHASEFLOW' in features))\n")
    assert "GATE True" in talus_cmd("run", script).stdout
