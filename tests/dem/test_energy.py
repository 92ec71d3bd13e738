"""The energy tracker (O.trackEnergy, O.energy): exact balance of free fall with damping, closed
balance of damped frictional depositions, no effect on the physics, independence of the thread
count, Yade's mapping interface."""
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import talus
from talus.dem import NewtonIntegrator, Scene, sphere

from energy_deposition import scene as deposition
from test_contact_physics import LINEAR, engines

SCRIPT = Path(__file__).with_name("energy_deposition.py")


def test_free_fall_with_damping_balances_to_round_off():
    # Leap-frog: the change of kinetic energy is exactly the work over the mean velocity, which
    # is how gravity's work and the damping's dissipation are accumulated.
    S = Scene()
    S.bodies.append([sphere((0, 0, 10), 0.1), sphere((1, 0, 10), 0.2)])
    S.bodies[1].state.vel = (0.3, -0.2, 1.0)
    S.bodies[1].state.angVel = (1.0, 2.0, 0.5)
    S.engines = engines(LINEAR, gravity=(0.5, 0, -9.81), damping=0.3)
    S.trackEnergy = True
    S.dt = 1e-3
    before = S.energy.total()
    S.run(3000)
    e = S.energy
    assert e["nonviscDamp"] > 0.1 * e["kinetic"] and e["gravWork"] < 0
    assert abs(e.total() - before) < 1e-12 * abs(e["gravWork"])


@pytest.mark.parametrize("law", ["linear", "viscoelastic", "hertz"])
def test_damped_frictional_deposition_closes_the_balance(law):
    S = deposition(law)
    before = S.energy.total()
    S.run({"linear": 4000, "viscoelastic": 16000, "hertz": 12000}[law])
    e = dict(S.energy.items())
    assert S._cpp.realContactCount() > 150                 # a packing, nearly settled
    assert e["kinetic"] < 0.05 * abs(e["gravWork"])
    assert e["nonviscDamp"] > 0 and e["plastDissip"] > 0
    assert (e["viscDamp"] > 0) == (law != "linear")
    assert abs(S.energy.total() - before) < 0.01 * abs(e["gravWork"])


def test_tracking_does_not_change_the_physics():
    A, B = deposition("hertz", m=4, track=False), deposition("hertz", m=4, track=True)
    A.run(800)
    B.run(800)
    assert np.array_equal(A.positions(), B.positions()) and np.array_equal(A.velocities(), B.velocities())
    assert [v for k, v in A.energy.items() if k not in ("kinetic", "elastPotential")] == [0.0] * 4


@pytest.mark.skipif(not talus.build_info()["features"]["openmp"][0], reason="built without OpenMP")
def test_energies_do_not_depend_on_the_thread_count(build_dir):
    def run(threads):
        env = {**os.environ, "OMP_NUM_THREADS": str(threads), "PYTHONPATH": str(build_dir / "python")}
        # 729 spheres: enough bodies and contacts for the loops to run in parallel
        done = subprocess.run([sys.executable, str(SCRIPT), "hertz", "4000", "9"], capture_output=True, text=True,
                              env=env, timeout=300)
        assert done.returncode == 0, done.stderr
        line = next(l for l in done.stdout.splitlines() if l.startswith("ENERGY "))
        contacts = next(l for l in done.stdout.splitlines() if l.startswith("CONTACTS "))
        return {**json.loads(line[len("ENERGY "):]), "contacts": contacts.split()[1:]}
    one, two = run(1), run(2)
    assert float(one["plastDissip"]) > 0 and float(one["viscDamp"]) > 0
    real, candidates = map(int, one["contacts"])
    assert real > 50 and candidates > 256          # the contact loops did run in parallel
    assert one == two


def test_mapping_interface_as_yade():
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    S.engines = [NewtonIntegrator(gravity=(0, 0, -10), damping=0.0)]
    assert S.trackEnergy is False
    S.trackEnergy = True
    S.dt = 1e-3
    S.run(10)
    assert S.energy.keys() == ["kinetic", "elastPotential", "gravWork", "nonviscDamp", "plastDissip", "viscDamp"]
    assert dict(**S.energy)["gravWork"] == S.energy["gravWork"] < 0
    assert S.energy.total() == pytest.approx(0, abs=1e-15)
    with pytest.raises(KeyError, match="no energy 'potential'"):
        S.energy["potential"]
    S.energy.clear()
    assert S.energy["gravWork"] == 0 and S.energy["kinetic"] > 0
