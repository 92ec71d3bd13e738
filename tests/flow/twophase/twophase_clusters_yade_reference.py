# Yade side of tests/flow/twophase/test_twophase_clusters.py: run with
#   PYTHONPATH=build/python python3 tests/flow/twophase/twophase_clusters_yade_reference.py
# Runs the scenario cases/yade/twophase/twophase_cluster_invasion.py in Yade 2023.02a (yade -n -j1 -x,
# through talus.twin) on the 400-sphere cloud of data/pore_packing.txt, with each parameter set
# below: an invasion() leaving trapped clusters then pores drained one at a time by
# clusterInvadePore ("invade") or clusterInvadePoreFast ("fast"); a drainage by invasion() with
# useFastInvasion ("fastInvasion"). Writes the results, with the parameters, to
# data/twophase_clusters_yade_reference.json.
import json
from pathlib import Path

from talus import twin

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_cluster_invasion.py"
GAMMA = 0.0728
# "fast" stops at the first step where Yade keeps whole a cluster the drained pore cut (the 85th on
# this packing), so that its end state holds that cluster
RUNS = {"invade": {"pc": 2.0, "invasions": 200},
        "fast": {"pc": 2.0, "invasions": 85, "fast": True},
        "fastInvasion": {"pcs": [GAMMA / 0.1 * (0.2 + 0.1 * i) for i in range(40)]}}

packing = str(HERE.parent / "data" / "pore_packing.txt")
result = {name: {"params": params, **twin.run(SCENARIO, {**params, "packing": packing}, "yade")}
          for name, params in RUNS.items()}
(HERE.parent / "data" / "twophase_clusters_yade_reference.json").write_text(json.dumps(result))
print("written:", {name: (len(r["steps"]), len(r["clusters"])) for name, r in result.items()})
