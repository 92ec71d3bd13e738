"""Heat-flux boundaries of ThermalEngine (Talus's addition: a side with bndCondIsTemperature
False and a non-zero thermalBndCondValue receives that value as W/m² into the packing, where
Yade leaves it insulated): the energy balance of a closed packing, with and without pore fluid."""
import numpy as np
import pytest

from talus.dem import O
from test_thermal_expansion import PACKING, packing

pytestmark = pytest.mark.skipif(not PACKING.exists(), reason="Yade's examples (the packing of its ThermalEngine "
                                "scripts) are not installed")
Q, SIDE, STEPS, CP = 5e4, 3, 50, 750.0   # W/m² into the packing through ymax


def heated_packing(advection):
    flow, thermal = packing(alpha=0)
    for name in ("thermoMech", "solidThermoMech", "fluidThermoMech"):
        setattr(thermal, name, False)
    thermal.advection = thermal.fluidConduction = advection
    thermal.particleCp = CP
    thermal.thermalBndCondValue = [Q if k == SIDE else 0 for k in range(6)]
    return flow, thermal


def side_area(flow):
    """Area of ymax: the FlowEngine's box face, between its x and z boundaries (where it put them:
    on the spheres' extents, inside the walls at 0 and 0.05 m)."""
    x0, x1, _, _, z0, z1 = flow.boundaryPositions()
    assert 0.04 < x1 - x0 < 0.05 and 0.04 < z1 - z0 < 0.05
    return (x1 - x0) * (z1 - z0)


def temperatures(flow, thermal):
    spheres = np.array([b.state.temp for b in O.bodies if type(b.shape).__name__ == "Sphere"])
    return spheres, (np.asarray(flow._poreHeat.temperatures()) if thermal.advection else np.zeros(0))


def heat_gained(flow, thermal, before):
    """Sum of m Cp dT over the spheres and rho Cp V_void dT over the pores since `before` (J)."""
    spheres, pores = temperatures(flow, thermal)
    mass = np.array([b.state.mass for b in O.bodies if type(b.shape).__name__ == "Sphere"])
    total = float(np.sum(mass * CP * (spheres - before[0])))
    if thermal.advection:   # boundary pores keep their temperature: dT = 0 there
        total += float(np.sum(flow.fluidRho * flow.fluidCp * np.asarray(flow.cellVoidVolumes) * (pores - before[1])))
    return total


@pytest.mark.parametrize("advection", [False, True])
def test_flux_side_gives_q_area_time(advection):
    """A closed packing, every other side insulated: after STEPS steps it holds Q x A x t more
    heat (spheres and fluid) to 1e-10, thermalBndFlux reports Q x A W on that side only and
    thermalBndHeat its time integral; the heat enters the spheres touching ymax (the others are
    untouched at the first step). A warning says the value is applied as a flux."""
    flow, thermal = heated_packing(advection)
    type(thermal)._warned_flux = False
    with pytest.warns(RuntimeWarning, match=r"thermalBndCondValue .* applied as a heat flux"):
        O.run(1, True)
    before = temperatures(flow, thermal)
    O.run(STEPS, True)
    rate = Q * side_area(flow)
    expected = rate * STEPS * O.dt
    gained = heat_gained(flow, thermal, before)
    if advection:   # the fluid took part of it
        assert np.ptp(flow._poreHeat.temperatures()) > 0
    assert gained == pytest.approx(expected, rel=1e-10)
    assert thermal.thermalBndFlux == pytest.approx([rate if k == SIDE else 0 for k in range(6)], rel=1e-12)
    assert thermal.thermalBndHeat[SIDE] == pytest.approx(expected * (STEPS + 1) / STEPS, rel=1e-10)
    ids = set(flow._flow.boundarySphereIds(SIDE))
    assert ids and all(q > 0 for _, q in thermal._conduction.heatFlux(SIDE))
    assert {i for i, _ in thermal._conduction.heatFlux(SIDE)} == ids


def test_zero_value_stays_insulated():
    """thermalBndCondValue 0 on a non-temperature side: no heat enters (as Yade)."""
    flow, thermal = heated_packing(advection=False)
    thermal.thermalBndCondValue = [0] * 6
    O.run(1, True)
    before = temperatures(flow, thermal)
    O.run(STEPS, True)
    assert np.array_equal(temperatures(flow, thermal)[0], before[0])
    assert thermal.thermalBndFlux == [0.0] * 6 and all(not thermal._conduction.heatFlux(k) for k in range(6))


@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_non_finite_flux_refused_naming_it(value):
    _, thermal = heated_packing(advection=False)
    with pytest.raises(ValueError, match=r"ThermalEngine.thermalBndCondValue\[2\] must be finite"):
        thermal.thermalBndCondValue = [0, 0, value, 0, 0, 0]


def test_temperature_side_below_absolute_zero_refused_whichever_is_set_first():
    """-274 is a valid flux but not a temperature: refused once the side holds a temperature."""
    _, thermal = heated_packing(advection=False)
    thermal.thermalBndCondValue = [0, -274, 0, 0, 0, 0]
    with pytest.raises(ValueError, match=r"ThermalEngine.thermalBndCondValue\[1\] = -274.0 is below absolute zero"):
        thermal.bndCondIsTemperature = [0, 1, 0, 0, 0, 0]
    thermal.thermalBndCondValue = [0] * 6
    thermal.bndCondIsTemperature = [0, 1, 0, 0, 0, 0]
    with pytest.raises(ValueError, match=r"ThermalEngine.thermalBndCondValue\[1\] = -274.0 is below absolute zero"):
        thermal.thermalBndCondValue = [0, -274, 0, 0, 0, 0]


def test_checkpoint_keeps_the_flux(tmp_path):
    """Saved half-way, the reloaded run goes on bit for bit (the flux's spheres and rates are in
    the checkpoint), and the boundary heat keeps counting."""
    flow, thermal = heated_packing(advection=False)
    O.run(10, True)
    path = tmp_path / "flux.h5"
    O.save(str(path))
    O.run(10, True)
    spheres = [b.state.temp for b in O.bodies if type(b.shape).__name__ == "Sphere"]
    heat = thermal.thermalBndHeat
    O.load(str(path))
    O.run(10, True)
    assert [b.state.temp for b in O.bodies if type(b.shape).__name__ == "Sphere"] == spheres
    loaded = next(e for e in O.engines if hasattr(e, "thermalBndHeat"))
    assert loaded.thermalBndHeat == heat and heat[SIDE] > 0
