"""TwoPhaseFlowEngine's clusters (isCellLabelActivated, PhaseCluster, clusterOutvadePore): the
dynamic injection of Yade's TwoPhaseFlowInjection.py (cases/yade/twophase/twophase_injection.py) on the
400-sphere cloud of data/pore_packing.txt against Yade 2023.02a's run of the same scenario
(data/twophase_injection_yade_reference.json, written by twophase_injection_yade_reference.py),
the clusters' bookkeeping, and bad input."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from talus import twin
from talus.flow import TwoPhaseFlowEngine

HERE = Path(__file__).resolve().parent
REF = json.loads((HERE.parent / "data" / "twophase_injection_yade_reference.json").read_text())
SCENARIO = HERE.parents[2] / "cases" / "yade" / "twophase" / "twophase_injection.py"
SPHERES = np.loadtxt(HERE.parent / "data" / "pore_packing.txt")


@pytest.fixture(scope="module")
def injection():
    return twin.run(SCENARIO, {**REF["params"], "packing": str(HERE.parent / "data" / "pore_packing.txt")}, "talus")


def test_injection_as_yade(injection):
    """Same pores wet at each record, the injected volume (getBoundaryFlux integrated) and the
    stored one (imbibed pores + menisci) as Yade's to round-off, the pore-body volumes' 1e-9."""
    ours, theirs = injection["records"], REF["records"]
    assert [r["wet"] for r in ours] == [r["wet"] for r in theirs]
    assert theirs[0]["wet"] < theirs[-1]["wet"] == REF["dry0"]  # the injection fills the dry pores
    assert (injection["nCells"], injection["dry0"], injection["interfaces0"]) == (REF["nCells"], REF["dry0"],
                                                                                  REF["interfaces0"])
    for key, rtol in (("injected", 1e-12), ("stored", 1e-8), ("lost", 1e-5)):
        np.testing.assert_allclose([r[key] for r in ours], [r[key] for r in theirs], rtol=rtol, atol=1e-12)
    np.testing.assert_allclose(injection["wallForce"], REF["wallForce"], rtol=1e-12, atol=1e-9)


def test_injected_volume_is_stored_or_lost(injection):
    """Mass balance: what entered through the wetting boundary is in the imbibed pores, in the
    menisci or counted as trapped."""
    for r in injection["records"]:
        assert r["injected"] == pytest.approx(r["stored"] + r["lost"], rel=1e-12)


def engine(isCellLabelActivated=True, pressure=(0, 0, 1, 0, 0, 0)):
    tp = TwoPhaseFlowEngine(bndCondIsPressure=list(pressure), bndCondValue=[0, 0, 1000, 0, 0, 0],
                            drainageFirst=False, isDrainageActivated=False, isImbibitionActivated=True,
                            isCellLabelActivated=isCellLabelActivated, viscosity=0.1)
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3], ids=np.arange(6, 6 + len(SPHERES)))
    tp.initialization()
    return tp


def test_labels_and_outvade():
    """After initialization the wetting reservoir (label 1) is the pores of ymin, every other
    pore non-wetting (0); a pore joining it takes label 1, its throats to dry pores become
    interfaces (volume 0) and the interfaces onto it go."""
    tp = engine()
    clusters = tp.getClusters()
    assert [c.label for c in clusters] == [0, 1]
    reservoir = clusters[1]
    labels = [tp.getCellLabel(i) for i in range(tp.nCells())]
    assert sorted(reservoir.getPores()) == [i for i, l in enumerate(labels) if l == 1]
    assert len(clusters[0].getPores()) + len(reservoir.getPores()) == tp.nCells()
    inner, outer, area, rank = reservoir.getInterfaces()[0]
    assert labels[inner] == 1 and labels[outer] == 0 and area > 0 and rank == 0
    reservoir.setCapVol(0, 1e-6)
    assert reservoir.getCapVol(0) == 1e-6
    merged = tp.clusterOutvadePore(inner, outer)
    assert merged == [1] and tp.getCellLabel(outer) == 1 and outer in reservoir.getPores()
    assert all(i[1] != outer for i in reservoir.getInterfaces())
    new = reservoir.getInterfaces(cellId=outer)
    assert new == reservoir.getInterfaces(CellId=outer)  # Yade's binding spells it CellId
    assert new and all(tp.getCellLabel(i[1]) == 0 and reservoir.getCapVol(i[3]) == 0 for i in new)


def test_cluster_pressure_and_fluxes():
    """The reservoir cluster grown by one layer: its pressures lie between the imposed 1000 and
    the dry pores' 0; what enters through ymin leaves through the interfaces."""
    tp = engine()
    reservoir = tp.getClusters()[1]
    for inner, outer, area, rank in reservoir.getInterfaces():
        if tp.getCellLabel(outer) == 0:
            tp.clusterOutvadePore(inner, outer)
    reservoir.solvePressure()
    p = tp.phasePressures
    inside = [i for i in reservoir.getPores() if not tp.cellSaturations[i] == 0]
    assert all(-1e-9 <= p[i] <= 1000 + 1e-9 for i in inside)
    out = sum(reservoir.getFlux(i[3]) for i in reservoir.getInterfaces())
    assert out > 0 and -tp.getBoundaryFlux(2) == pytest.approx(out, rel=1e-9)
    k = reservoir.getConductivity(0)
    inner, outer = reservoir.getInterfaces()[0][:2]
    assert reservoir.getFlux(0) == pytest.approx(k * (p[inner] - p[outer]), rel=1e-12)
    reservoir.setCapPressure(0, -50.0)
    assert reservoir.getFlux(0) == pytest.approx(k * (p[inner] - 50 - p[outer]), rel=1e-12)
    volume = reservoir.updateCapVol(0, 1e-3)
    assert volume == pytest.approx(1e-3 * reservoir.getFlux(0))


def test_bad_input():
    tp = engine()
    reservoir = tp.getClusters()[1]
    n = len(reservoir.getInterfaces())
    with pytest.raises(IndexError, match=f"interface index {n} out of range"):
        reservoir.getCapVol(n)
    with pytest.raises(IndexError, match="interface index -1"):
        reservoir.setCapVol(-1, 0.0)
    with pytest.raises(TypeError, match="numf"):
        reservoir.getConductivity(1.5)
    with pytest.raises(ValueError, match="vCap must be finite"):
        reservoir.setCapVol(0, math.nan)
    with pytest.raises(IndexError, match="startingId 99999 out of range"):
        tp.clusterOutvadePore(99999, 0)
    dry = reservoir.getInterfaces()[0][1]
    with pytest.raises(IndexError, match="imbibedId -3 out of range"):
        tp.clusterOutvadePore(reservoir.getPores()[0], -3)
    with pytest.raises(ValueError, match=f"startingId {dry} is not in a wetting cluster"):
        tp.clusterOutvadePore(dry, dry)
    with pytest.raises(ValueError, match="imbibedId .* is not a non-wetting pore"):
        tp.clusterOutvadePore(reservoir.getPores()[0], reservoir.getPores()[1])
    with pytest.raises(IndexError, match="cell id must be an integer"):
        tp.getCellLabel(tp.nCells())
    with pytest.raises(ValueError, match="invasion\\(\\) needs the pressure imposed on boundaries 2 and 3"):
        tp.invasion()
    with pytest.raises(ValueError, match="optional with isCellLabelActivated"):
        engine(isCellLabelActivated=False)
    with pytest.raises(RuntimeError, match=r"call initialization\(\) first"):
        TwoPhaseFlowEngine().getCellLabel(0)
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3])
    with pytest.raises(RuntimeError, match="rebuilt since initialization"):
        reservoir.getCapVol(0)
    with pytest.raises(RuntimeError, match="set isCellLabelActivated = True"):
        engine(isCellLabelActivated=False, pressure=(0, 0, 1, 1, 0, 0)).getClusters()
