"""TwoPhaseFlowEngine (quasi-static two-phase flow on the pore network) against Yade 2023.02a's on
the 400-sphere cloud of data/pore_packing.txt (data/twophase_yade_reference.json, written by
twophase_yade_reference.py), the entry radii of sphere triplets, and bad input."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from talus.flow import TwoPhaseFlowEngine, UnsaturatedEngine

DATA = Path(__file__).resolve().parents[1] / "data"
REF = json.loads((DATA / "twophase_yade_reference.json").read_text())
SPHERES = np.loadtxt(DATA / "pore_packing.txt")


def engine(method=1, trapped=True, **attrs):
    tp = TwoPhaseFlowEngine(bndCondIsPressure=[0, 0, 1, 1, 0, 0], surfaceTension=REF["surfaceTension"],
                            entryPressureMethod=method, isPhaseTrapped=trapped, **attrs)
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3], ids=np.arange(6, 6 + len(SPHERES)))
    tp.initialization()
    return tp


def drain(tp, pcs):
    out = []
    for pc in pcs:
        tp.bndCondValue = [0, 0, -pc, 0, 0, 0]
        tp.invasion()
        out.append(tp.getSaturation(False))
    return np.array(out)


@pytest.mark.parametrize("method", [1, 2, 3])
@pytest.mark.parametrize("trapped", [True, False])
def test_drainage_as_yade(method, trapped):
    """Saturation after each capillary-pressure step as Yade's (the same pores invade: equal to
    round-off), for each entry-pressure method, with and without trapping."""
    ref = REF["runs"][f"{method}-{int(trapped)}"]
    tp = engine(method, trapped)
    assert tp.nCells() == ref["nCells"]
    sw = drain(tp, REF["pcs"])
    assert sw[0] > sw[-1]  # the curve is not flat: the comparison tests invasion
    np.testing.assert_allclose(sw, ref["drainage"], rtol=0, atol=1e-9)
    assert tp.getSaturation(True) == pytest.approx(ref["sideIncluded"], abs=1e-9)


def test_pore_body_radii_as_yade():
    """The sphere inscribed in each pore (Yade's stepped search, walls as fictitious spheres),
    matched pore by pore through the pores' vertex ids."""
    tp = engine()
    radii = tp.cellInSphereRadii
    ours = {" ".join(map(str, sorted(int(v) for v in verts))): radii[i] for i, verts in enumerate(tp.cellVertexIds)}
    assert ours.keys() == REF["bodyRadii"].keys()
    got = np.array([ours[k] for k in REF["bodyRadii"]])
    np.testing.assert_allclose(got, list(REF["bodyRadii"].values()), rtol=1e-9)


def test_imbibition_after_drainage_as_yade():
    """Main imbibition from the drained state (drainage off, imbibition on), trapped phases."""
    ref = REF["runs"]["1-1"]
    tp = engine()
    drain(tp, REF["pcs"])
    tp.isDrainageActivated = False
    tp.isImbibitionActivated = True
    sw = drain(tp, REF["pcs"][::-1])
    assert sw[-1] > sw[0] + 0.3
    np.testing.assert_allclose(sw, ref["imbibition"], rtol=0, atol=1e-9)


def test_trapping_keeps_wetting_phase():
    """Trapped wetting clusters stay: the saturation with trapping is never below the one
    without, and both only decrease during drainage."""
    pcs = REF["pcs"]
    with_trap, without = drain(engine(1, True), pcs), drain(engine(1, False), pcs)
    assert np.all(np.diff(with_trap) <= 0) and np.all(np.diff(without) <= 0)
    assert np.all(with_trap >= without - 1e-12)
    assert with_trap[-1] > without[-1] + 0.05


def test_next_entry_pressures():
    """getMinDrainagePc is the capillary pressure of the next drainage: just below it nothing
    moves, just above it the saturation falls."""
    tp = engine()
    drain(tp, REF["pcs"][:5])
    pc = tp.getMinDrainagePc()
    assert pc > REF["pcs"][4]
    before = tp.getSaturation()
    drain(tp, [pc * (1 - 1e-9)])
    assert tp.getSaturation() == before
    drain(tp, [pc * (1 + 1e-9)])
    assert tp.getSaturation() < before


def test_capillary_forces_as_yade():
    """computeCapillaryForce: the force of the phase pressures on the spheres, as Yade's."""
    tp = engine()
    drain(tp, REF["pcs"][:REF["forceStep"]])
    tp.computeCapillaryForce()
    for body, force in REF["forces"].items():
        np.testing.assert_allclose(tp.fluidForce(int(body)), force, rtol=1e-7, atol=1e-12)


def test_entry_radii_of_triplets():
    """MS-P and inscribed radii of sphere triplets as Yade's getMSPRcByPosRadius and
    getEffRcByPosRadius; the inscribed circle of three touching equal spheres is R (2/sqrt(3) - 1)."""
    tp = TwoPhaseFlowEngine()
    for t in REF["triplets"]:
        assert tp.getMSPRcByPosRadius(*t["spheres"]) == pytest.approx(t["msp"], rel=1e-9)
        assert tp.getEffRcByPosRadius(*t["spheres"]) == pytest.approx(t["inscribed"], rel=1e-9)
    touching = REF["triplets"][0]["spheres"]
    assert tp.getEffRcByPosRadius(*touching) == pytest.approx(2 / math.sqrt(3) - 1, rel=1e-12)
    assert 0 < tp.getMSPRcByPosRadius(*touching) <= tp.getEffRcByPosRadius(*touching)


def test_phase_vtk(tmp_path):
    tp = engine()
    drain(tp, REF["pcs"][:15])
    path = Path(tp.savePhaseVtk(str(tmp_path), withBoundaries=False))
    text = path.read_text()
    assert path.name == "out_0.vtk" and "SCALARS saturation" in text
    sat = [float(v) for v in text.split("SCALARS saturation double 1\nLOOKUP_TABLE default\n")[1].split("SCALARS")[0].split()]
    assert 0 < sum(sat) < len(sat)  # both phases present


def test_unsaturated_engine_is_the_same_model():
    assert issubclass(UnsaturatedEngine, TwoPhaseFlowEngine)


# --- bad input: a clear error naming the parameter ----------------------------------------------
@pytest.mark.parametrize("value", [0, 4, 1.0, "MSP", True])
def test_unknown_entry_pressure_method(value):
    with pytest.raises(ValueError, match="entryPressureMethod"):
        TwoPhaseFlowEngine(entryPressureMethod=value)


@pytest.mark.parametrize("value", [-0.07, math.nan, math.inf, "water"])
def test_bad_surface_tension(value):
    with pytest.raises(ValueError, match="surfaceTension"):
        TwoPhaseFlowEngine(surfaceTension=value)


@pytest.mark.parametrize("name", ["bndCondValue", "bndCondIsPressure", "bndCondIsWaterReservoir"])
def test_boundary_list_length(name):
    with pytest.raises(ValueError, match=f"TwoPhaseFlowEngine.{name}.*6"):
        TwoPhaseFlowEngine(**{name: [0, 0, 1, 1, 0]})


def test_reservoirs_must_be_pressure_boundaries():
    tp = TwoPhaseFlowEngine(bndCondIsPressure=[1, 1, 0, 0, 0, 0])
    tp.triangulate(SPHERES[:, :3], SPHERES[:, 3])
    with pytest.raises(ValueError, match=r"bndCondIsPressure.*boundaries 2.*3"):
        tp.initialization()


def test_invasion_before_initialization():
    with pytest.raises(RuntimeError, match="initialization"):
        TwoPhaseFlowEngine().invasion()


def test_yade_namespace_and_script_options():
    """The Yade names in the drop-in namespace, and the options Yade's example scripts set:
    meshUpdateInterval -1 (never remesh), the cluster labels; invading a pore out of a cluster
    (clusterInvadePore) is named as out of scope."""
    import yade
    from yade._scope import out_of_scope
    namespace = {}
    exec("from yade import *", namespace)
    assert namespace["TwoPhaseFlowEngine"] is TwoPhaseFlowEngine and namespace["UnsaturatedEngine"] is UnsaturatedEngine
    assert yade is not None and out_of_scope("TwoPhaseFlowEngine") is None
    assert out_of_scope("c0 = flow.getClusters(); flow.clusterOutvadePore(1, 2)") is None
    assert "clusterInvadePore" in out_of_scope("flow.clusterInvadePore(3)")
    tp = TwoPhaseFlowEngine(meshUpdateInterval=-1, isCellLabelActivated=False, iniVoidVolumes=True)
    assert tp.meshUpdateInterval > 10 ** 9
    tp.isCellLabelActivated = True
    assert tp.isCellLabelActivated is True


def test_capillary_force_on_walls():
    """fluidForce of a wall body (wallIds, Yade's 0..5) is its boundary's capillary force: the
    non-wetting reservoir's wall is pushed outwards (+y) by the positive gas pressure."""
    tp = engine()
    pcs = REF["pcs"]
    tp.bndCondValue = [0, 0, 0, pcs[10], 0, 0]  # the same capillary pressure, gas pressure positive
    tp.invasion()
    tp.computeCapillaryForce()
    assert tp.fluidForce(3)[1] > 0 and tp.fluidForce(2)[1] == pytest.approx(0, abs=1e-12)


@pytest.mark.parametrize("name", sorted(REF["variants"]))
def test_option_variants_as_yade(name):
    """isInvadeBoundary off (throats between boundary pores closed), recursiveInvasion off (one
    pore deep per invasion), and a non-wetting start imbibed by decreasing capillary pressure."""
    variant = REF["variants"][name]
    tp = engine(**variant["attrs"])
    sw = drain(tp, variant["pcs"])
    assert abs(sw[-1] - sw[0]) > 0.1
    np.testing.assert_allclose(sw, variant["saturations"], rtol=0, atol=1e-9)


def test_initialization_options_set_later_warn():
    tp = engine()
    with pytest.warns(RuntimeWarning, match="entryPressureMethod acts at the next initialization"):
        tp.entryPressureMethod = 2
