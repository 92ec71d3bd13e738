"""ThermalEngine's bad input: each refused when set (or at the first step for what only the scene
decides), with a message naming the parameter: temperatures below absolute zero, negative
conductivity or density, a non-positive heat capacity, boundary lists of the wrong length or
type, a safety factor above 1, the planned physics switched on, a thermal step above the stable
one without sub-stepping, temperature boundaries without a FlowEngine."""
import math

import pytest

from talus.dem import (O, FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, Bo1_Sphere_Aabb,
                       Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, sphere)
from talus.flow import FlowEngine, ThermalEngine

PLANNED_OFF = dict(advection=False, fluidConduction=False, thermoMech=False, solidThermoMech=False,
                   fluidThermoMech=False)


@pytest.mark.parametrize("name, value, message", [
    ("particleT0", -300, r"ThermalEngine.particleT0 = -300.0 is below absolute zero"),
    ("particleK", -1, r"ThermalEngine.particleK must be >= 0"),
    ("particleCp", 0, r"ThermalEngine.particleCp must be > 0"),
    ("particleDensity", -2600, r"ThermalEngine.particleDensity must be >= 0"),
    ("particleK", math.nan, r"ThermalEngine.particleK must be finite"),
    ("tsSafetyFactor", 1.5, r"ThermalEngine.tsSafetyFactor = 1.5: above 1"),
    ("thermalBndCondValue", [0, 0, 0], r"ThermalEngine.thermalBndCondValue needs 6 values"),
    ("thermalBndCondValue", [0, math.inf, 0, 0, 0, 0], r"ThermalEngine.thermalBndCondValue\[1\] must be finite"),
    ("bndCondIsTemperature", [1, 1, 0, 0, 0], r"ThermalEngine.bndCondIsTemperature needs 6 values"),
    ("bndCondIsTemperature", "abcdef", r"ThermalEngine.bndCondIsTemperature needs 6 values"),
    ("bndCondIsTemperature", [1, 2, 0, 0, 0, 0], r"ThermalEngine.bndCondIsTemperature must be 6 booleans"),
    ("fluidK", -0.6, r"ThermalEngine.fluidK must be >= 0"),
    ("particleCp", "710", r"ThermalEngine.particleCp must be a number"),
    ("particleAlpha", -1e-5, r"ThermalEngine.particleAlpha must be >= 0"),
    ("fluidBeta", -2e-4, r"ThermalEngine.fluidBeta must be >= 0"),
    ("porosityFactor", -0.1, r"ThermalEngine.porosityFactor must be >= 0"),
])
def test_parameter_refused_naming_it(name, value, message):
    with pytest.raises((ValueError, TypeError), match=message):
        ThermalEngine(**{name: value})
    engine = ThermalEngine()
    with pytest.raises((ValueError, TypeError), match=message):
        setattr(engine, name, value)


@pytest.mark.parametrize("name", ["useHertzMethod", "letThermalRunFlowForceUpdates", "tempDependentFluidBeta"])
def test_planned_switch_refused_naming_it(name):
    with pytest.raises(NotImplementedError, match=rf"ThermalEngine.{name}: .* not implemented yet in Talus \(planned"):
        ThermalEngine(**{name: True})
    assert getattr(ThermalEngine(**{name: False}), name) is False


@pytest.mark.parametrize("name, value, error, message", [
    ("tZero", -300, ValueError, r"FlowEngine.tZero = -300.0: below absolute zero"),
    ("fluidRho", 0, ValueError, r"FlowEngine.fluidRho must be > 0"),
    ("fluidCp", -4181, ValueError, r"FlowEngine.fluidCp must be > 0"),
    ("thermalPorosity", 1.5, ValueError, r"FlowEngine.thermalPorosity must be in \[0, 1\]"),
    ("thermalBndCondValue", [0, 0, -280, 0, 0, 0], ValueError, r"FlowEngine.thermalBndCondValue = .*below absolute zero"),
    ("bndCondIsTemperature", [1, 0], ValueError, r"FlowEngine.bndCondIsPressure needs a list of 6 values"),
    ("tempDependentViscosity", True, NotImplementedError, r"FlowEngine.tempDependentViscosity: .* not implemented"),
])
def test_flow_thermal_attribute_refused_naming_it(name, value, error, message):
    with pytest.raises(error, match=message):
        setattr(FlowEngine(), name, value)


def test_unknown_attribute():
    with pytest.raises(AttributeError, match="ThermalEngine has no attribute 'particleKK'"):
        ThermalEngine(particleKK=2)
    flow = FlowEngine(thermalEngine=True, tZero=20, fluidRho=997)
    assert (flow.thermalEngine, flow.tZero, flow.fluidRho, flow.fluidCp) == (True, 20.0, 997.0, 4181.3)
    with pytest.raises(RuntimeError, match="no pore temperatures yet"):
        flow.getPoreTemperature((0, 0, 0))


def chain(thermal, n=5, radius=0.01, flow=None):
    """n touching spheres along x (overlap 1e-4 r), no motion."""
    O.reset()
    mat = O.materials.append(FrictMat(young=1e7, density=2600))
    for i in range(n):
        O.bodies.append(sphere((i * 2 * radius * (1 - 5e-5), 0, 0), radius, fixed=True, material=mat))
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 *([flow] if flow else []), thermal, NewtonIntegrator()]
    return thermal


def test_yade_defaults_without_a_flow_engine_stop_at_the_first_step_naming_advection():
    chain(ThermalEngine())
    O.dt = 1e-3
    with pytest.raises(ValueError, match=r"ThermalEngine.advection: .* O.engines has no FlowEngine"):
        O.step()


def test_per_body_alpha_refused_naming_it():
    thermal = chain(ThermalEngine(**PLANNED_OFF))
    with pytest.raises(ValueError, match=r"state.alpha must be >= 0"):
        O.bodies[1].state.alpha = -1e-5
    O.bodies[1].state.alpha = 2e-5
    assert O.bodies[1].state.alpha == 2e-5 and thermal.particleAlpha == 1.16e-5


@pytest.mark.parametrize("settings, error, message", [
    (dict(advection=False), ValueError, r"ThermalEngine.fluidConduction needs advection=True"),
    (dict(uniformReynolds=10, fluidK=0), ValueError, r"ThermalEngine.fluidK = 0.0: .* must be > 0 with advection"),
    (dict(uniformReynolds=10), ValueError, r"ThermalEngine.advection: .* O.engines has no FlowEngine"),
])
def test_fluid_settings_refused_at_the_first_step(settings, error, message):
    """Yade's advection and fluidConduction (on by default) need a FlowEngine and a Reynolds
    number; fluid conduction without advection would do nothing, as in Yade."""
    chain(ThermalEngine(thermoMech=False, solidThermoMech=False, fluidThermoMech=False, **settings))
    O.dt = 1e-3
    with pytest.raises(error, match=message):
        O.step()


def test_step_above_the_stable_one_stops_naming_it():
    """tsSafetyFactor <= 0: the thermal step is O.dt; the chain's stable step is C / 2G =
    rho 4/3 pi r^3 Cp / (2 x 2 k r) = 1.29 s for k = 150 (G = 2 (k + k) r r / 2r)."""
    thermal = chain(ThermalEngine(tsSafetyFactor=0, particleK=150, particleCp=710, particleT0=300, **PLANNED_OFF))
    O.bodies[0].state.temp = 400
    O.dt = 1.0
    O.run(3, True)
    assert 300 < O.bodies[1].state.temp < 400 and thermal.getMaxTimeStep() == pytest.approx(1.29, rel=0.01)
    O.dt = 2.0
    with pytest.raises(ValueError, match=r"ThermalEngine: the thermal step O.dt = 2 s exceeds the stable conduction "
                                         r"step 1.2\d* s \(sphere [1-3]: .*tsSafetyFactor"):
        O.step()
    before = O.bodies[1].state.temp
    O.step()    # finishes the failed step without its conduction (the temperatures are untouched)
    assert O.bodies[1].state.temp == before and O.iter == 4
    thermal.tsSafetyFactor = 0.5    # sub-steps of at most 0.5 x 1.29 s
    O.step()
    assert thermal.getThermalDT() == 2.0 and O.bodies[1].state.temp != before


def test_temperature_boundaries_need_a_flow_engine():
    chain(ThermalEngine(bndCondIsTemperature=[1, 0, 0, 0, 0, 0], **PLANNED_OFF))
    O.dt = 1e-3
    with pytest.raises(ValueError, match=r"ThermalEngine.bndCondIsTemperature: .* O.engines has no FlowEngine"):
        O.step()


def test_per_body_fields_refused_naming_them():
    chain(ThermalEngine(**PLANNED_OFF))
    state = O.bodies[2].state
    with pytest.raises(ValueError, match=r"state.temp = -300.0 is below absolute zero"):
        state.temp = -300
    with pytest.raises(ValueError, match=r"state.k must be >= 0"):
        state.k = -1
    with pytest.raises(ValueError, match=r"state.Cp must be > 0"):
        state.Cp = 0
    with pytest.raises(AttributeError, match=r"state.Tcondition is set by ThermalEngine.bndCondIsTemperature"):
        state.Tcondition = True
    state.temp, state.k, state.Cp = 350, 4, 800
    O.dt = 1e-3
    O.step()     # the values set by hand before the first step stay (Yade's particleT0 would overwrite them)
    assert (state.k, state.Cp) == (4, 800) and 300 < state.temp <= 350
    with pytest.raises(AttributeError, match="no attribute 'tmp'"):
        state.tmp
