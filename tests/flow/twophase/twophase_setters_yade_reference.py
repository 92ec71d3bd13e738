# Yade side of tests/flow/twophase/test_twophase_setters.py: run with
#   PYTHONPATH=build/python python3 tests/flow/twophase/twophase_setters_yade_reference.py
# Runs the scenario cases/yade/twophase/twophase_setters.py (a drainage from pore body and throat radii and
# non-wetting pores set one by one: setPoreBodyRadius, setPoreThroatRadius, setCellSaturation,
# setCellIsNWRes, setCellIsWRes, updatePressure) in Yade 2023.02a (yade -n -j1 -x, through
# talus.twin) on the 400-sphere cloud of data/pore_packing.txt with the parameters below and writes
# its result, with the parameters, to data/twophase_setters_yade_reference.json.
import json
from pathlib import Path

from talus import twin

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_setters.py"
GAMMA = 0.0728
PARAMS = {"pcs": [GAMMA / 0.1 * (0.2 + 0.1 * i) for i in range(40)], "every": [7, 11, 13]}

result = twin.run(SCENARIO, {**PARAMS, "packing": str(HERE.parent / "data" / "pore_packing.txt")}, "yade")
(HERE.parent / "data" / "twophase_setters_yade_reference.json").write_text(json.dumps({"params": PARAMS, **result}))
print("written: saturations", [round(s, 4) for s in result["saturations"][::5]])
