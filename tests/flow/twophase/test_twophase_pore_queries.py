"""TwoPhaseFlowEngine's per-pore queries (getCellVolume by pore id, getCellVoidVolume,
getCellPorosity, getCellIsFictious, isCellNeighbor, getCellFluxFromId) and
getPotentialPendularSpheresPair: the
scenario cases/yade/twophase/twophase_pore_queries.py on the 400-sphere cloud of data/pore_packing.txt
against Yade 2023.02a's run of it (data/twophase_pore_queries_yade_reference.json, written by
twophase_pore_queries_yade_reference.py)."""
import json
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.flow import TwoPhaseFlowEngine

HERE = Path(__file__).resolve().parent
PACKING = HERE.parent / "data" / "pore_packing.txt"
REF = json.loads((HERE.parent / "data" / "twophase_pore_queries_yade_reference.json").read_text())
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_pore_queries.py"


@pytest.fixture(scope="module")
def ours():
    return twin.run(SCENARIO, {**REF["params"], "packing": str(PACKING)}, "talus")


def test_pore_queries_as_yade(ours):
    """The volumes of every pore to 1e-7 (those on the walls, with their far fictitious spheres,
    differ from Yade's by 2e-8), the wall flags and the neighbours exactly."""
    for key in ("volume", "voidVolume", "porosity"):
        assert ours[key].keys() == REF[key].keys()
        got = np.array([ours[key][k] for k in REF[key]])
        np.testing.assert_allclose(got, list(REF[key].values()), rtol=1e-7, err_msg=key)
    assert ours["fictious"] == REF["fictious"] and 0 < sum(REF["fictious"].values()) < len(REF["fictious"])
    assert ours["neighbours"] is REF["neighbours"] is True
    assert ours["notNeighbours"] is REF["notNeighbours"] is False


def test_pendular_pairs_as_yade(ours):
    """The same vertex pairs with only non-wetting pores around them, before (the ymax wall's
    edges) and after a drainage."""
    assert ours["pendular0"] == REF["pendular0"]
    assert ours["pendular"] == REF["pendular"] and len(REF["pendular"]) > 10 * len(REF["pendular0"])


def test_pore_fluxes_as_yade(ours):
    """getCellFluxFromId on the pressures of the wetting reservoir grown by 40 pores: every
    pore's flux as Yade's (the dry pores along the cluster receive, negative)."""
    assert ours["flux"].keys() == REF["flux"].keys()
    got, theirs = np.array([ours["flux"][k] for k in REF["flux"]]), np.array(list(REF["flux"].values()))
    np.testing.assert_allclose(got, theirs, rtol=1e-9, atol=1e-9 * np.abs(theirs).max())
    assert (theirs < -1).sum() > 10


def test_cell_volume_by_position_still_locates():
    """Given a position, getCellVolume is FlowEngine's (the pore containing it)."""
    spheres = np.loadtxt(PACKING)
    tp = TwoPhaseFlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0])
    tp.triangulate(spheres[:, :3], spheres[:, 3], ids=np.arange(6, 6 + len(spheres)))
    tp.initialization()
    assert tp.getCellVolume(np.asarray(tp.cellCenters[10])) == tp.getCellVolume(tp.getCell(tp.cellCenters[10]))
    assert tp.getCellVolume(0) > tp.getCellVoidVolume(0) > 0
    with pytest.raises(IndexError, match="cell id"):
        tp.getCellVoidVolume(tp.nCells())
