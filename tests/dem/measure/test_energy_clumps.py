"""The energy tracker with clumps: gravity's work and Cundall damping booked on the clump body
(its members carry neither), the kinetic energy of a clump as one rigid body with its full inertia
tensor, a free tumbling fall, and the damped frictional clump deposition side by side with Yade."""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from talus.dem import NewtonIntegrator, Scene, FrictMat, sphere
from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "clumps"  # the scripts Yade and Talus both run
SCRIPT = TWINS / "clump_energy_deposition.py"
yade = shutil.which("yade")


def free_clump(damping=0.0):
    """An unequal three-sphere clump (three distinct principal moments) alone under gravity."""
    S = Scene()
    S.materials.append(FrictMat(density=2000))
    cid, _ = S.bodies.appendClumped([sphere((0, 0, 5), 0.1), sphere((0.25, 0, 5.05), 0.08),
                                     sphere((0, 0.2, 5.1), 0.06)])
    S.engines = [NewtonIntegrator(gravity=(0.3, 0, -9.81), damping=damping)]
    S.dt = 1e-4
    S.trackEnergy = True
    c = S.bodies[cid].state
    c.vel = (0.5, -0.2, 2.0)
    return S, c


def rigid_kinetic(c):
    """1/2 m v^2 + 1/2 w.(R I R^T) w: the clump as one rigid body, inertia tensor in world axes."""
    R = c.ori.toRotationMatrix()
    tensor = R @ np.diag(c.inertia) @ R.T
    w = np.array(c.angVel)
    return 0.5 * c.mass * np.dot(c.vel, c.vel) + 0.5 * w @ tensor @ w


def test_spinning_clump_in_free_fall_conserves_energy_exactly():
    # Spin about a principal axis: the exact aspherical rotation keeps it (the body-frame angular
    # velocity stays on the axis), and translation balances gravity's work to round-off.
    S, c = free_clump()
    axes = c.ori.toRotationMatrix()
    c.angVel = tuple(axes @ np.array([0, 0, 7.0]))
    before = S.energy.total()
    S.run(20000)
    e = S.energy
    assert e["kinetic"] == pytest.approx(rigid_kinetic(c), rel=1e-13)
    assert e["gravWork"] < -10 and e["nonviscDamp"] == 0
    assert abs(e.total() - before) < 1e-9 * abs(e["gravWork"])


def test_tumbling_clump_in_free_fall_drifts_only_by_the_rotation_scheme():
    # Off the principal axes the clump tumbles; gravity's work still balances the translation to
    # round-off, and the rotational energy drifts by the exact aspherical scheme's error alone,
    # first order in dt (as in the Dzhanibekov test of test_clumps.py).
    def drift(dt):
        S, c = free_clump()
        S.dt = dt
        c.angVel = (3.0, -4.0, 5.0)
        rotation0 = rigid_kinetic(c) - 0.5 * c.mass * np.dot(c.vel, c.vel)
        before = S.energy.total()
        S.run(int(round(2.0 / dt)))
        return (S.energy.total() - before) / rotation0
    coarse, fine = drift(1e-4), drift(5e-5)
    assert abs(coarse) < 1e-3
    assert abs(fine) < 0.6 * abs(coarse)


def test_damped_tumbling_clump_books_the_damping():
    # Cundall damping on the clump's translation (exact) and on its aspherical rotation (the
    # damping torque's work over the mean angular velocity): the balance closes to the rotation
    # scheme's error.
    S, c = free_clump(damping=0.3)
    c.angVel = (3.0, -4.0, 5.0)
    rotation0 = rigid_kinetic(c) - 0.5 * c.mass * np.dot(c.vel, c.vel)
    before = S.energy.total()
    S.run(20000)
    e = S.energy
    assert e["nonviscDamp"] > 0.2 * abs(e["gravWork"])
    assert abs(e.total() - before) < 1e-3 * rotation0


def test_damped_clump_deposition_closes_the_balance():
    # 18 clumps of two and three spheres fall onto a wall, with friction and damping. What is left
    # (0.35 % at dt = 0.08 PWaveTimeStep, 2 % at 0.33) is the frictional contacts' first-order
    # error under sliding impacts, the same for spheres whose rotation is blocked (clumps do not
    # roll) and the same order in Yade (0.24 %).
    r = twin.run(SCRIPT, {"steps": 32000, "dt": 5e-5}, "talus")
    e = r["energy"]
    assert r["contacts"] >= 18 and e["kinetic"] < 0.05 * abs(e["gravWork"])
    assert e["nonviscDamp"] > 0 and e["plastDissip"] > 0
    assert e["kinetic"] == pytest.approx(r["rigidKinetic"], rel=1e-12)
    assert abs(r["total"] - r["startKinetic"]) < 0.01 * abs(e["gravWork"])


@pytest.mark.skipif(yade is None, reason="yade is not installed (./setup.sh installs it)")
def test_clump_deposition_energies_side_by_side_with_yade():
    # The same deposition through the first impacts (0.2 s; later the runs part by round-off, as
    # any granular flow): the clumps' states agree (rigid kinetic energy 2e-12), so do the
    # frictional dissipation (same slips, same definition: 7e-11) and, to the velocity each takes
    # within the step (Yade one end of it, Talus the mean, which closes the balance),
    # gravity's work (1e-4) and the damping (9e-4). Yade's own 'kinetic' key lags by half a step.
    ours, theirs = (twin.run(SCRIPT, {"steps": 4000, "dt": 5e-5}, who) for who in ("talus", "yade"))
    a, b = ours["energy"], theirs["energy"]
    assert a["plastDissip"] > 1
    assert ours["rigidKinetic"] == pytest.approx(theirs["rigidKinetic"], rel=1e-9)
    assert a["kinetic"] == pytest.approx(ours["rigidKinetic"], rel=1e-12)
    assert a["plastDissip"] == pytest.approx(b["plastDissip"], rel=1e-9)
    assert a["gravWork"] == pytest.approx(b["gravWork"], rel=1e-3)
    assert a["nonviscDamp"] == pytest.approx(b["nonviscDamp"], rel=2e-3)
