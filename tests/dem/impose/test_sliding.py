"""talus.dem.analysis.sliding, the sliding-block experiments of the block and particle cases: a free
sphere under a gravity ramp and a tilted gravity against the closed forms of its motion."""
import math

import numpy as np
import pytest

from talus.dem import ForceResetter, FrictMat, NewtonIntegrator, Scene, sphere
from talus.dem.analysis.sliding import coulombAcceleration, fittedAcceleration, rampGravity, slide, tilted


def free_sphere():
    S = Scene()
    m = S.materials.append(FrictMat(density=1000))
    S.bodies.append(sphere((0, 0, 0), 0.1, material=m))
    S.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, 0), damping=0.0)]
    S.dt = 1e-3
    return S


def test_a_ramp_ends_at_the_full_load_after_its_duration():
    S = free_sphere()
    rampGravity(S, S.engines[-1], lambda f: (0.0, 0.0, -10.0 * f), 0.2, stages=4)
    assert S.time == pytest.approx(0.2) and tuple(S.engines[-1].gravity) == (0.0, 0.0, -10.0)
    # Stages of 0.05 s at 2.5, 5, 7.5, 10 m/s^2: velocity 0.05 (2.5 + 5 + 7.5 + 10) = 1.25 m/s.
    assert S.bodies[0].state.vel[2] == pytest.approx(-1.25, rel=1e-12)


def test_a_free_slide_gives_the_tilted_gravity_along_the_slope():
    S = free_sphere()
    theta = math.radians(30)
    S.engines[-1].gravity = tilted(9.81, theta)
    times, moved = slide(S, 0, 0.5, direction=(1.0, 0.0, 0.0))
    assert len(times) == 25 and moved[0] > 0
    assert fittedAcceleration(times, moved) == pytest.approx(9.81 * math.sin(theta), rel=1e-9)
    # Across the slope nothing moves.
    assert np.max(np.abs(slide(S, 0, 0.1, direction=(0.0, 1.0, 0.0))[1])) == 0.0


def test_coulomb_holds_below_the_friction_angle():
    phi = math.radians(30)
    assert coulombAcceleration(9.81, math.radians(29), phi) == 0.0
    assert coulombAcceleration(9.81, math.radians(40), phi) == pytest.approx(
        9.81 * (math.sin(math.radians(40)) - math.cos(math.radians(40)) * math.tan(phi)), rel=1e-15)
