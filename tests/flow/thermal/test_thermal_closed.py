"""A FlowEngine that imposes no pressure anywhere, with an incompressible fluid (Yade's
noFlowScenario.py): the pressure is known up to a constant, fixed by pZero (the mean pressure),
and exists only if the pores' volume changes sum to zero. The example runs unchanged and gives the
temperatures of its well-posed twin (thermal_noflow.py, one boundary at pressure 0) as run by Yade;
a closed packing whose fluid expands stops with an error naming what to set."""
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from talus.dem import O
from test_thermal_expansion import packing

HERE = Path(__file__).resolve().parent
EXAMPLE = Path("/usr/share/doc/yade/examples/ThermalEngine")
needs_example = pytest.mark.skipif(not (EXAMPLE / "noFlowScenario.py").exists(),
                                   reason="Yade's ThermalEngine examples are not installed")


@needs_example
def test_noflow_example_runs_unchanged_with_the_twins_temperatures(talus_cmd, tmp_path):
    """2000 steps of the unchanged script: the fluid stays at rest at pZero = 0 in every pore,
    and the temperatures are those Yade computes on thermal_noflow.py (the same physics with
    boundary xmin at pressure 0) to the tolerances of test_thermal_fluid.py."""
    for name in ("noFlowScenario.py", "5cmEdge_1mm.spheres"):
        shutil.copy(EXAMPLE / name, tmp_path)
    out = tmp_path / "example.json"
    talus_cmd("run", "-j", "1", HERE / "noflow_example_driver.py", out, cwd=tmp_path, timeout=300)
    ours = json.loads(out.read_text())
    yade = json.loads((HERE.parent / "data" / "thermal_noflow_yade.json").read_text())
    assert ours["steps"] == 2000 and ours["ids"] == yade["ids"] and ours["contacts"] == yade["contacts"]
    assert np.all(np.array(ours["pressures"]) == 0)
    spheres = np.array(ours["temp"])
    assert np.all(np.isfinite(spheres)) and 0.03 < (spheres - 333.15).max() < 0.04
    np.testing.assert_allclose(spheres, yade["temp"], rtol=0, atol=1e-11)
    np.testing.assert_allclose(ours["poreTempBefore"], yade["poreTemp"], rtol=0, atol=1e-8)


def closed_packing(fluidThermoMech=False, pZero=0.0):
    """The example's packing, fixed, in a closed box of incompressible water."""
    flow, thermal = packing(alpha=0)
    flow.fluidBulkModulus, flow.pZero = 0, pZero
    for name in ("thermoMech", "solidThermoMech", "fluidThermoMech"):
        setattr(thermal, name, fluidThermoMech)
    return flow


@needs_example
def test_closed_packing_whose_fluid_expands_names_what_to_set():
    """Heating the water of a closed box: its volume grows with nowhere to go."""
    flow = closed_packing(fluidThermoMech=True)
    O.run(2, True)
    assert np.all(np.asarray(flow.pressures) == 0)
    heat = flow._poreHeat
    for i, t in enumerate(heat.temperatures()):
        heat.setTemperature(i, t + 1.0)
    with pytest.raises(ValueError, match=r"nowhere to go.*bndCondIsPressure.*fluidBulkModulus > 0"):
        O.run(2, True)


@needs_example
def test_closed_network_with_balanced_point_fluxes_has_mean_pressure_pZero():
    """Fluid injected at one point and drawn at another, the same rate: a solution exists. Each
    pore's net outflux is its imposed flux, the volume-weighted mean pressure is pZero (pZero = 7
    shifts the field by 7), and a solve with the sink's pressure imposed instead (well-posed) gives
    the same field."""
    source, sink, q = (0.0131, 0.0247, 0.0253), (0.0372, 0.0254, 0.0246), 1e-9

    def closed(pZero):
        flow = closed_packing(pZero=pZero)
        flow.imposeFlux(source, -q)     # Yade's sign: influx negative
        flow.imposeFlux(sink, q)
        O.run(1, True)
        return flow

    flow = closed(0.0)
    p = np.asarray(flow.pressures)
    volume = np.abs(np.asarray(flow.cellVolumes))
    spread = p.max() - p.min()
    assert spread > 0 and abs(np.sum(p * volume) / np.sum(volume)) < 1e-12 * spread
    pores, k = np.asarray(flow.throatPores), np.asarray(flow.throatConductances)
    outflux = np.zeros(len(p))
    np.add.at(outflux, pores[:, 0], k * (p[pores[:, 0]] - p[pores[:, 1]]))
    np.add.at(outflux, pores[:, 1], k * (p[pores[:, 1]] - p[pores[:, 0]]))
    expected = np.zeros(len(p))
    expected[flow.getCell(source)], expected[flow.getCell(sink)] = q, -q
    np.testing.assert_allclose(outflux, expected, rtol=0, atol=1e-9 * q)
    assert flow.getPorePressure(source) > 0 > flow.getPorePressure(sink)
    np.testing.assert_allclose(closed(7.0).pressures, p + 7.0, rtol=0, atol=1e-9 * spread)

    drained = closed_packing()
    drained.imposeFlux(source, -q)
    drained.imposePressure(sink, float(p[flow.getCell(sink)]))
    O.run(1, True)
    np.testing.assert_allclose(drained.pressures, p, rtol=0, atol=1e-6 * spread)
