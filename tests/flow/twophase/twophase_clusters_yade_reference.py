# Yade side of tests/flow/twophase/test_twophase_clusters.py: run with
#   PYTHONPATH=build/python python3 tests/flow/twophase/twophase_clusters_yade_reference.py
# Runs the scenario cases/yade/twophase_cluster_invasion.py (an invasion() leaving trapped
# clusters, then pores drained one at a time by clusterInvadePore) in Yade 2023.02a (yade -n -j1
# -x, through talus.twin) on the 400-sphere cloud of data/pore_packing.txt with the parameters
# below and writes its result, with the parameters, to data/twophase_clusters_yade_reference.json.
import json
from pathlib import Path

from talus import twin

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase_cluster_invasion.py"
PARAMS = {"pc": 2.0, "invasions": 200}

result = twin.run(SCENARIO, {**PARAMS, "packing": str(HERE.parent / "data" / "pore_packing.txt")}, "yade")
(HERE.parent / "data" / "twophase_clusters_yade_reference.json").write_text(json.dumps({"params": PARAMS, **result}))
print("written:", len(result["steps"]), "invasions,", len(result["clusters"]), "clusters")
