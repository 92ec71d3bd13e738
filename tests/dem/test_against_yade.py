"""Side by side with Yade (Debian's yade 2023.02a) on identical input: the same script runs in
both programs and the trajectories must agree."""
from pathlib import Path

import pytest

from talus.dem import twin

HERE = Path(__file__).parent
yade_missing = pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")


def both(script):
    """The RESULT of ``script`` run by Talus and by Yade."""
    return twin.run(HERE / script, {}, "talus"), twin.run(HERE / script, {}, "yade")


@yade_missing
def test_bouncing_sphere_matches_yade():
    ours, theirs = both("bouncing_sphere.py")
    assert ours["dt"] == theirs["dt"]
    z_ours, z_yade = ours["z"], theirs["z"]
    assert min(z_yade) < 1.0            # it did bounce on the support (contact at z = 1)
    assert max(abs(a - b) for a, b in zip(z_ours, z_yade)) < 1e-6


@yade_missing
def test_hertz_mindlin_collisions_match_yade():
    # Oblique sphere-sphere collision, then a bounce on a fixed sphere under gravity, with
    # restitution 0.7 and friction: positions and angular velocities of both moving spheres.
    ours, theirs = both("hertz_bounce.py")
    a, b = ours["x"], theirs["x"]
    assert len(a) == len(b) == 3000
    spin = max(abs(v) for row in b for body in row for v in body[3:])
    assert spin > 1.0                   # the collisions did make the spheres turn
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[:3], bb[:3])) < 1e-6
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[3:], bb[3:])) < 1e-6 * spin


@yade_missing
def test_cohesive_bonds_with_moments_match_yade():
    # CohFrict: a bonded sphere spinning on a fixed one (bending and twisting moments), a third
    # sphere bonding on impact, a bond breaking: positions and angular velocities.
    ours, theirs = both("cohfrict_bond.py")
    a, b = ours["x"], theirs["x"]
    assert len(a) == len(b) == 3000
    assert max(sum(p * p for p in row[0][:3]) ** 0.5 for row in b) > 0.11   # the first bond broke
    spin = max(abs(v) for row in b for body in row for v in body[3:])
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[:3], bb[:3])) < 1e-6
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[3:], bb[3:])) < 1e-6 * spin
