"""TwoPhaseFlowEngine's clusters as a drainage changes them: clusterInvadePore (a wetting pore
drains and its cluster is labelled again, split if need be), clusterInvadePoreFast and
useFastInvasion (the cluster kept in place, split only when the pore's neighbours no longer meet
around it). The scenario cases/yade/twophase/twophase_cluster_invasion.py on the 400-sphere cloud of
data/pore_packing.txt against Yade 2023.02a's runs of it (data/twophase_clusters_yade_reference.json,
written by twophase_clusters_yade_reference.py), the bookkeeping of one split, and bad input."""
import json
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.flow import TwoPhaseFlowEngine

HERE = Path(__file__).resolve().parent
PACKING = HERE.parent / "data" / "pore_packing.txt"
REF = json.loads((HERE.parent / "data" / "twophase_clusters_yade_reference.json").read_text())
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_cluster_invasion.py"
SPHERES = np.loadtxt(PACKING)


def run(name):
    return twin.run(SCENARIO, {**REF[name]["params"], "packing": str(PACKING)}, "talus")


def assert_clusters_as_yade(ours, theirs):
    """Every pore's label and interface flag, every cluster's pores and interfaces in Yade's
    order, their volumes to the pore volumes' round-off."""
    assert ours["labels"] == theirs["labels"]
    assert ours["hasInterface"] == theirs["hasInterface"]
    assert len(ours["clusters"]) == len(theirs["clusters"])
    for mine, yade in zip(ours["clusters"], theirs["clusters"]):
        for key in ("label", "pores", "interfaces", "entryPore"):
            assert mine[key] == yade[key], (yade["label"], key)
        assert mine["volume"] == pytest.approx(yade["volume"], rel=1e-7, abs=1e-15)
        # the reservoir's entry throat is on the ymin wall, where the entry radii differ by 4e-5
        assert mine["entryRadius"] == pytest.approx(yade["entryRadius"], rel=1e-4)


def test_invade_pore_as_yade():
    """200 pores drained by clusterInvadePore: the same pores, the same labels returned (the
    splits), and the same clusters at the end."""
    ours, theirs = run("invade"), REF["invade"]
    assert ours["nCells"] == theirs["nCells"] and ours["steps"] == theirs["steps"]
    splits = [s for s in theirs["steps"] if len(s["returned"]) > 1]
    emptied = [s for s in theirs["steps"] if not s["returned"]]
    assert len(splits) >= 10 and len(emptied) >= 10  # the scenario exercises both
    assert_clusters_as_yade(ours, theirs)


def test_fast_invasion_as_yade():
    """A drainage by invasion() with useFastInvasion (no labelling after each step: the clusters
    follow the drained pores): the saturation after each step and the clusters at the end."""
    ours, theirs = run("fastInvasion"), REF["fastInvasion"]
    assert [s["clusters"] for s in ours["steps"]] == [s["clusters"] for s in theirs["steps"]]
    assert theirs["steps"][-1]["clusters"] > 50  # trapped clusters were split off on the way
    np.testing.assert_allclose([s["saturation"] for s in ours["steps"]],
                               [s["saturation"] for s in theirs["steps"]], rtol=0, atol=1e-12)
    assert_clusters_as_yade(ours, theirs)


def adjacency():
    """Neighbouring pores by name (sorted vertex ids, as the scenario names them)."""
    tp = engine(pc=0.0)
    name = [" ".join(map(str, sorted(v))) for v in tp.cellVertexIds]
    return {name[i]: {name[n] for n in tp.getNeighbors(i) if n >= 0} for i in range(tp.nCells())}


def connected(pores, neighbours):
    if not pores:
        return True
    left, todo = set(pores), [pores[0]]
    left.discard(pores[0])
    while todo:
        for n in neighbours[todo.pop()] & left:
            left.discard(n)
            todo.append(n)
    return not left


def test_invade_pore_fast_as_yade_but_its_missed_splits():
    """200 pores drained by clusterInvadePoreFast: the same steps as Yade until Yade keeps whole a
    cluster the drained pore has cut (its test of the neighbours meeting around the pore's edges
    takes, for the facet pairs (3, 0) and (3, 1), an edge that is not the one the facets share);
    Talus splits it there, and its clusters stay connected where one of Yade's is not."""
    ours, theirs = run("fast"), REF["fast"]
    first = next(k for k, (a, b) in enumerate(zip(ours["steps"], theirs["steps"])) if a != b)
    assert first >= 50 and sum(len(s["returned"]) > 1 for s in theirs["steps"][:first]) >= 10
    assert ours["steps"][first]["pore"] == theirs["steps"][first]["pore"]
    assert len(ours["steps"][first]["returned"]) > len(theirs["steps"][first]["returned"])
    neighbours = adjacency()
    assert all(connected(c["pores"], neighbours) for c in ours["clusters"])
    assert not all(connected(c["pores"], neighbours) for c in theirs["clusters"])


def engine(pc=2.0):
    tp = TwoPhaseFlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], isCellLabelActivated=True)
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3], ids=np.arange(6, 6 + len(SPHERES)))
    tp.initialization()
    tp.bndCondValue = [0, 0, -pc, 0, 0, 0]
    tp.invasion()
    return tp


def neighbours_in(tp, pore, label):
    return [n for n in tp.getNeighbors(pore) if n >= 0 and tp.getCellLabel(n) == label]


def test_split_bookkeeping():
    """A pore joining two parts of its cluster drains: it becomes non-wetting (label 0, in
    cluster 0), each part is a cluster of connected pores, their interfaces go to non-wetting
    pores (the drained one among them) with volume 0, the volumes add up."""
    tp = engine()
    for cluster in tp.getClusters()[1:]:
        for pore in cluster.getPores():
            if len(neighbours_in(tp, pore, cluster.label)) < 2:
                continue
            volume, n = cluster.volume, len(cluster.getPores())
            cluster.setCapVol(0, 1e-3)
            returned = tp.clusterInvadePore(pore)
            if len(returned) > 1:
                break
        else:
            continue
        break
    else:
        pytest.fail("no pore splits its cluster")
    assert returned[0] == cluster.label and tp.getCellLabel(pore) == 0
    assert tp.getCellSaturation(pore) == 0 and pore in tp.getClusters()[0].getPores()
    parts = [tp.getClusters()[k] for k in returned]
    assert sum(len(p.getPores()) for p in parts) == n - 1
    assert sum(p.volume for p in parts) == pytest.approx(volume - 1 / tp.getCellInvVoidVolume(pore), rel=1e-12)
    for part in parts:
        pores = set(part.getPores())
        assert all(tp.getCellLabel(p) == part.label for p in pores)
        reached, todo = set(), [part.getPores()[0]]   # connected through its own pores
        while todo:
            p = todo.pop()
            if p not in reached:
                reached.add(p)
                todo += neighbours_in(tp, p, part.label)
        assert reached == pores
        assert any(i[1] == pore for i in part.getInterfaces())
        assert all(tp.getCellLabel(i[1]) == 0 and part.getCapVol(i[3]) == 0 for i in part.getInterfaces())


def test_last_pore_empties_the_cluster():
    tp = engine()
    single = next(c for c in tp.getClusters()[2:] if len(c.getPores()) == 1)
    pore = single.getPores()[0]
    assert tp.clusterInvadePore(pore) == []
    assert single.getPores() == [] and single.getInterfaces() == [] and single.volume == 0
    assert tp.getCellLabel(pore) == 0


def test_bad_input():
    tp = engine()
    dry = tp.getClusters()[0].getPores()[0]
    with pytest.raises(ValueError, match=f"cellId {dry} is not in a wetting cluster"):
        tp.clusterInvadePore(dry)   # Yade warns and does nothing
    with pytest.raises(IndexError, match="cellId 99999 out of range"):
        tp.clusterInvadePore(99999)
    with pytest.raises(TypeError, match="clusterInvadePore: cellId must be a pore index"):
        tp.clusterInvadePore(1.0)
    with pytest.raises(ValueError, match=f"clusterInvadePoreFast: cellId {dry} is not in a wetting cluster"):
        tp.clusterInvadePoreFast(dry)
    tp.useFastInvasion = True
    tp.isImbibitionActivated = True
    with pytest.raises(ValueError, match="useFastInvasion.*drainage only"):
        tp.invasion()


@pytest.mark.parametrize("name", ["primaryTPF", "actionTPF", "reTriangulateSpheres"])
def test_dynamic_model_names_are_refused(name):
    """Yade's dynamic two-phase model is not in Talus: its names say so, read or set."""
    tp = TwoPhaseFlowEngine()
    with pytest.raises(AttributeError, match=f"TwoPhaseFlowEngine.{name} belongs to Yade's dynamic two-phase flow"):
        getattr(tp, name)
    with pytest.raises(AttributeError, match=f"{name} belongs to Yade's dynamic"):
        setattr(tp, name, False)
