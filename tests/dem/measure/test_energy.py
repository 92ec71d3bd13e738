"""The energy tracker (O.trackEnergy, O.energy): exact balance of free fall with damping, closed
balance of damped frictional depositions, of a periodic triaxial and a simple shear (the cell's
work), of a compression between servo-controlled walls and of a shaken box (imposed motions), no
effect on the physics, independence of the thread count, Yade's mapping interface."""
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import talus
from talus.dem import (FrictMat, HarmonicMotionEngine, NewtonIntegrator, PeriTriaxController, PWaveTimeStep,
                       Scene, sphere)
from talus.dem.geometry import geom
from talus.dem.packing import pack

from energy_deposition import scene as deposition
from laws.test_contact_physics import LINEAR, engines
from control.test_controllers import frict_engines, periodic_cloud, walled_cloud

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
    S.run({"linear": 4000, "viscoelastic": 24000, "hertz": 12000}[law])
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
    assert [v for k, v in A.energy.items() if k not in ("kinetic", "elastPotential")] == [0.0] * 7


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
    assert S.energy.keys() == ["kinetic", "elastPotential", "gravWork", "nonviscDamp", "plastDissip", "viscDamp",
                               "velGradWork", "kinematicWork", "growthWork"]
    assert dict(**S.energy)["gravWork"] == S.energy["gravWork"] < 0
    assert S.energy.total() == pytest.approx(0, abs=1e-15)
    with pytest.raises(KeyError, match="no energy 'potential'"):
        S.energy["potential"]
    S.energy.clear()
    assert S.energy["gravWork"] == 0 and S.energy["kinetic"] > 0


def imbalance(S, before):
    """Change of O.energy.total() since ``before``."""
    return S.energy.total() - before


def test_periodic_triaxial_closes_the_balance_with_the_cell_work():
    # Isotropic compaction by the cell's stress servo, then a strain-controlled axial compression
    # at constant lateral stress: the only energy input is the cell's deformation (velGradWork).
    S = periodic_cloud(n=300)
    triax = PeriTriaxController(goal=(-2e4, -2e4, -2e4), stressMask=7, dynCell=True, maxStrainRate=(2, 2, 2),
                                maxUnbalanced=.05, relStressTol=2e-3)
    S.engines = frict_engines(triax)
    S.dt = .5 * PWaveTimeStep(S)
    S.trackEnergy = True
    before = S.energy.total()
    S.run(6000)
    triax.goal, triax.stressMask, triax.maxStrainRate = (-2e4, -2e4, -.1), 3, (1, 1, .5)
    S.run(6000)
    e = dict(S.energy.items())
    assert e["velGradWork"] < 0 and e["plastDissip"] > .3 * -e["velGradWork"] and e["kinematicWork"] == 0
    assert abs(imbalance(S, before)) < .01 * -e["velGradWork"]
    # Yade's PeriTriaxController.externalWork is the same work (opposite sign convention), from the
    # Love-Weber stress instead of the bodies' forces and positions: equal to O(dt^2), 2.5e-5 here
    assert e["velGradWork"] == pytest.approx(-triax.externalWork, rel=1e-4)


def test_simple_shear_by_hand_closes_the_balance():
    # velGrad set directly (no controller), with a spin: the affine field's rotation of the
    # spheres is imposed too.
    S = periodic_cloud(n=200, seed=3)
    S.engines = frict_engines(PeriTriaxController(goal=(-1e4, -1e4, -1e4), stressMask=7, dynCell=True,
                                                  maxStrainRate=(2, 2, 2)))
    S.dt = .5 * PWaveTimeStep(S)
    S.run(5000)                      # compacted, not tracked yet
    S.engines = frict_engines()
    S.cell.velGrad = [[0, 0, .3], [0, 0, 0], [0, 0, 0]]
    S.trackEnergy = True
    before = S.energy.total()
    S.run(4000)
    e = dict(S.energy.items())
    assert e["velGradWork"] < 0 and e["plastDissip"] > 0
    assert abs(imbalance(S, before)) < .01 * -e["velGradWork"]


def test_servo_controlled_walls_close_the_balance():
    # Six walls servo-controlled to 10 kPa, then the z walls at a strain rate: the walls change
    # velocity every step, their work is booked over the mean of consecutive velocities.
    S, triax = walled_cloud(n=300, internalCompaction=False)
    S.trackEnergy = True
    before = S.energy.total()
    S.run(8000)
    triax.stressMask, triax.goal3 = 3, -.05
    S.run(4000)
    e = dict(S.energy.items())
    assert e["kinematicWork"] < 0 and e["velGradWork"] == 0 and e["plastDissip"] > .1 * -e["kinematicWork"]
    assert abs(imbalance(S, before)) < .01 * -e["kinematicWork"]


def test_shaken_box_and_a_spinning_sphere_close_the_balance():
    # A bed in a facet box shaken by a HarmonicMotionEngine, and a sphere whose DOFs are all
    # blocked spinning at an imposed rate under it (a mixer): both do work on the bed. (Violent
    # shaking leaves more: the contacts' own bookkeeping is first order in dt under impacts, 0.6 %
    # of the gravity work at 0.5 P-wave for a cloud thrown at 0.5 m/s into a fixed box.)
    S = Scene()
    S.materials.append(FrictMat(young=1e6, poisson=.3, frictionAngle=.5, density=2600))
    box = S.bodies.append(geom.facetBox((.5, .5, .5), (.5, .5, .5), wallMask=31))
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, .3), (1, 1, 1), rMean=.06, rRelFuzz=.3, seed=4)
    sp.toSimulation(S)
    mixer = S.bodies.append(sphere((.5, .5, .1), .08))
    S.bodies[mixer].state.blockedDOFs = "xyzXYZ"
    S.bodies[mixer].state.angVel = (0, 5, 0)
    S.engines = frict_engines(HarmonicMotionEngine(A=(0, 0, .005), f=(0, 0, 5), ids=box), damping=.3,
                              gravity=(0, 0, -9.81))
    S.dt = .3 * PWaveTimeStep(S)
    S.trackEnergy = True
    before = S.energy.total()
    S.run(16000)
    e = dict(S.energy.items())
    assert e["kinematicWork"] < 0 and abs(e["kinematicWork"]) > .3 * abs(e["gravWork"])
    assert abs(imbalance(S, before)) < .01 * (abs(e["kinematicWork"]) + abs(e["gravWork"]))


def restart_continues(S, path, steps=200):
    """Save S to ``path``, run ``steps``, reload and run them again: the energies must be equal to
    the bit. Returns them."""
    S.save(path)
    S.run(steps)
    expected = list(S.energy.values())
    S.load(path)
    S.run(steps)
    assert list(S.energy.values()) == expected
    return dict(S.energy.items())


def test_restart_with_servo_walls_continues_the_energies_bit_identically(tmp_path):
    # The tracker keeps the walls' previous displacements: they are in the checkpoint too.
    S, _ = walled_cloud(n=80, internalCompaction=False)
    S.trackEnergy = True
    S.run(300)
    assert restart_continues(S, tmp_path / "walls.h5")["kinematicWork"] < 0
