# Yade side of tests/flow/twophase/test_twophase_subdomains.py: run with
#   PYTHONPATH=build/python python3 tests/flow/twophase/twophase_subdomains_yade_reference.py
# Runs the scenario cases/yade/twophase/twophase_subdomains.py (UnsaturatedEngine's measures of parts of
# the packing along a drainage) in Yade 2023.02a (yade -n -j1 -x, through talus.twin) on the
# 400-sphere cloud of data/pore_packing.txt with the parameters below and writes its result, with
# the parameters, to data/twophase_subdomains_yade_reference.json.
import json
from pathlib import Path

from talus import twin

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_subdomains.py"
GAMMA = 0.0728
PARAMS = {"pcs": [GAMMA / 0.1 * (0.2 + 0.2 * i) for i in range(20)]}

result = twin.run(SCENARIO, {**PARAMS, "packing": str(HERE.parent / "data" / "pore_packing.txt")}, "yade")
(HERE.parent / "data" / "twophase_subdomains_yade_reference.json").write_text(json.dumps({"params": PARAMS, **result}, indent=1))
print("written:", {k: [round(x, 4) for x in v[::5]] for k, v in result.items()})
