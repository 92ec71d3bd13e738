"""The particles' heat is the DEM core's (Yade's ThermalState fields temp, Cp, k, alpha, one value
per body): another component sees and changes, through the scene's arrays (the particle exchange
interface), the temperatures ThermalEngine conducts; checkpoints keep them; a scene without heat
has none (NaN, nothing written)."""
import math

import h5py
import numpy as np
import pytest

from talus.dem import O, PyRunner, VTKRecorder
from talus.flow import ThermalEngine
from test_bad_input_thermal import PLANNED_OFF, chain

K, CP, RHO, R = 2.0, 710.0, 2600.0, 0.01


def rod(**settings):
    """Five touching spheres at 300 K, DEM-only conduction with O.dt = 1 s (stable: 1.29 s x 2.5)."""
    thermal = chain(ThermalEngine(tsSafetyFactor=0, particleK=K, particleCp=CP, particleT0=300, **PLANNED_OFF,
                                  **settings))
    O.dt = 1.0
    return thermal


def conductance(i, j):
    """Yade's default conductance of contact (i, j): 2 (k_i + k_j) r_i r_j / d."""
    d = np.linalg.norm(np.asarray(O.bodies[j].state.pos) - np.asarray(O.bodies[i].state.pos))
    return 2 * (K + K) * R * R / d


def test_another_component_sees_and_changes_the_temperatures_conducted():
    """A hook before the ThermalEngine (a stand-in for another coupling) reads the temperatures
    through O.temperatures() and heats sphere 0 by a fixed power; ThermalEngine conducts what it
    wrote: after each step the rod holds exactly the heat given (sum m Cp dT), and sphere 1's
    first change is G (T0' - T1) dt / C with T0' the hooked value."""
    rod()
    O.step()                                  # the engine gives its defaults
    seen = O.temperatures()
    assert np.array_equal(seen[:5], [300.0] * 5)
    assert [b.state.temp for b in O.bodies] == list(seen[:5])
    mass = np.array([b.state.mass for b in O.bodies])
    power = 3.0                               # W into sphere 0
    log = []

    def heater():
        t = O.temperatures()
        log.append(t[:5].copy())
        t[0] += power * O.dt / (mass[0] * CP)
    O.engines = O.engines[:3] + [PyRunner(command=heater, iterPeriod=1)] + O.engines[3:]
    before = O.temperatures()[:5].copy()
    O.step()
    after = O.temperatures()[:5].copy()
    heated = before[0] + power * O.dt / (mass[0] * CP)
    expected = conductance(0, 1) * (heated - before[1]) * O.dt / (mass[1] * CP)
    assert after[1] - before[1] == pytest.approx(expected, rel=1e-12)
    assert after[1] > before[1]
    O.run(20, True)
    gained = float(np.sum(mass * CP * (O.temperatures()[:5] - before)))
    assert gained == pytest.approx(power * 21 * O.dt, rel=1e-10)
    assert len(log) == 21 and np.array_equal(log[1], after)   # the hook read what the engine wrote
    # and the values the engine writes are what b.state.temp and the component read
    assert [b.state.temp for b in O.bodies] == list(O.temperatures()[:5])


def test_values_given_by_another_component_before_the_first_step_are_kept():
    """The engine gives particleT0, particleK, particleCp, particleAlpha only to the fields not
    given (NaN): what a component wrote into the arrays before stays."""
    thermal = rod(particleAlpha=1e-5)
    O.temperatures()[2] = 350.0
    O.conductivities()[3] = 4.0
    O.heat_capacities()[4] = 900.0
    O.thermal_expansions()[1] = 2e-5
    assert math.isnan(O.temperatures()[0]) and O.bodies[0].state.temp == 300.0   # the engine's default, read
    O.step()
    assert O.temperatures()[0] == 300.0 and O.temperatures()[2] < 350.0
    assert list(O.conductivities()[:5]) == [K, K, K, 4.0, K]
    assert list(O.heat_capacities()[:5]) == [CP, CP, CP, CP, 900.0]
    assert list(O.thermal_expansions()[:5]) == [1e-5, 2e-5, 1e-5, 1e-5, 1e-5]
    assert thermal.lenBodies == 5


def test_scene_without_heat_has_none_and_a_component_can_give_it(tmp_path):
    """No ThermalEngine: every field is NaN, b.state.temp is an AttributeError (Yade's plain State
    has none) and the checkpoint holds no heat; temperatures given through the arrays are read by
    b.state.temp, written by VTKRecorder's thermal recorder and kept by O.save."""
    chain(PyRunner(command="pass", iterPeriod=1))
    assert np.isnan(O.temperatures()).all() and np.isnan(O.heat_capacities()).all()
    with pytest.raises(AttributeError, match=r"body 1 has no state.temp"):
        O.bodies[1].state.temp
    assert not hasattr(O.bodies[1].state, "k")
    O.save(str(tmp_path / "plain.h5"))
    with h5py.File(tmp_path / "plain.h5") as f:
        assert not any(name in f["bodies"] for name in ("temperature", "heatCapacity", "conductivity",
                                                         "thermalExpansion"))
    O.temperatures()[:] = [280.0, 290.0, 300.0, 310.0, 320.0]
    O.bodies[0].state.k = 1.5
    assert O.bodies[3].state.temp == 310.0 and O.conductivities()[0] == 1.5
    recorder = VTKRecorder(fileName=str(tmp_path / "vtk-"), recorders=["spheres", "thermal"], iterPeriod=1)
    O.engines = O.engines + [recorder]
    with pytest.warns(Warning, match=r"4 spheres with non-finite values"):   # k of spheres 1-4: NaN, flagged
        O.run(2, True)
    text = next(tmp_path.glob("vtk-spheres*.vtu")).read_text(errors="replace")
    assert 'Name="temp"' in text and 'Name="k"' in text and 'Name="Cp"' not in text   # Cp given to none
    O.save(str(tmp_path / "heated.h5"))
    O.reset()
    O.load(str(tmp_path / "heated.h5"))
    assert list(O.temperatures()) == [280.0, 290.0, 300.0, 310.0, 320.0]
    assert O.bodies[0].state.k == 1.5 and math.isnan(O.conductivities()[1])


@pytest.mark.parametrize("bad, message", [
    (("temp", -300), r"state.temp = -300.0 is below absolute zero"),
    (("Cp", 0), r"state.Cp must be > 0"),
    (("k", math.nan), r"state.k must be finite"),
    (("alpha", "1e-5"), r"state.alpha must be a number"),
])
def test_bad_values_refused_without_an_engine(bad, message):
    chain(PyRunner(command="pass", iterPeriod=1))
    with pytest.raises((ValueError, TypeError), match=message):
        setattr(O.bodies[1].state, *bad)
    assert math.isnan(getattr(O, {"temp": "temperatures", "Cp": "heat_capacities", "k": "conductivities",
                                  "alpha": "thermal_expansions"}[bad[0]])()[1])


def test_checkpoint_round_trip_keeps_the_heat_and_old_checkpoints_load(tmp_path):
    """O.save / O.load keeps every body's temp, Cp, k, alpha bit for bit, and the run goes on as
    the uninterrupted one; a checkpoint without the heat datasets (written before the DEM held
    them) loads with none."""
    rod(particleAlpha=1e-5)
    O.bodies[0].state.temp = 400
    O.bodies[2].state.Cp = 800
    O.run(5, True)
    saved = [np.array(a()) for a in (O.temperatures, O.heat_capacities, O.conductivities, O.thermal_expansions)]
    O.save(str(tmp_path / "rod.h5"))
    O.run(5, True)
    uninterrupted = np.array(O.temperatures())
    O.reset()
    O.load(str(tmp_path / "rod.h5"))
    for before, now in zip(saved, (O.temperatures, O.heat_capacities, O.conductivities, O.thermal_expansions)):
        assert np.array_equal(before, now())
    O.run(5, True)
    assert np.array_equal(O.temperatures(), uninterrupted)

    with h5py.File(tmp_path / "rod.h5", "a") as f:
        for name in ("temperature", "heatCapacity", "conductivity", "thermalExpansion"):
            del f["bodies"][name]
    O.reset()
    O.load(str(tmp_path / "rod.h5"))
    assert np.isnan(O.temperatures()).all()
