# Yade side of tests/flow/twophase/test_twophase_injection.py: run with
#   PYTHONPATH=build/python python3 tests/flow/twophase/twophase_injection_yade_reference.py
# Runs the injection scenario cases/yade/twophase/twophase_injection.py in Yade 2023.02a (yade -n -j1 -x,
# through talus.twin) on the 400-sphere cloud of data/pore_packing.txt with the parameters
# below and writes its result, with the parameters, to data/twophase_injection_yade_reference.json.
import json
from pathlib import Path

from talus import twin

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_injection.py"
PARAMS = {"steps": 1000, "dt": 3e-5, "every": 50, "pressure": 1000.0, "viscosity": 0.1}

result = twin.run(SCENARIO, {**PARAMS, "packing": str(HERE.parent / "data" / "pore_packing.txt")}, "yade")
(HERE.parent / "data" / "twophase_injection_yade_reference.json").write_text(json.dumps({"params": PARAMS, **result}, indent=1))
print("written: wet pores", [r["wet"] for r in result["records"]])
