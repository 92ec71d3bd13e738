# Yade side of tests/flow/twophase/test_twophase_pore_queries.py: run with
#   PYTHONPATH=build/python python3 tests/flow/twophase/twophase_pore_queries_yade_reference.py
# Runs the scenario cases/yade/twophase/twophase_pore_queries.py (per-pore volumes, porosity, wall flags,
# neighbours, the pendular pairs before and after a drainage) in Yade 2023.02a (yade -n -j1 -x,
# through talus.twin) on the 400-sphere cloud of data/pore_packing.txt with the parameters below
# and writes its result, with the parameters, to data/twophase_pore_queries_yade_reference.json.
import json
from pathlib import Path

from talus import twin

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_pore_queries.py"
PARAMS = {"pc": 2.0}

result = twin.run(SCENARIO, {**PARAMS, "packing": str(HERE.parent / "data" / "pore_packing.txt")}, "yade")
(HERE.parent / "data" / "twophase_pore_queries_yade_reference.json").write_text(json.dumps({"params": PARAMS, **result}))
print("written:", len(result["volume"]), "pores,", len(result["pendular0"]), "and", len(result["pendular"]), "pendular pairs")
