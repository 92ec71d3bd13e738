"""Side by side with Yade (Debian's yade 2023.02a) on identical input: the same script runs in
both programs and the trajectories must agree."""
from pathlib import Path

import numpy as np
import pytest

from talus import twin

TWINS = Path(__file__).parents[1] / "yade_twins" / "laws"  # the scripts Yade and Talus both run
yade_missing = pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed (./setup.sh installs it)")


def both(script):
    """The RESULT of ``script`` run by Talus and by Yade."""
    return twin.run(TWINS / script, {}, "talus"), twin.run(TWINS / script, {}, "yade")


@yade_missing
def test_bouncing_sphere_matches_yade():
    ours, theirs = both(Path(__file__).parents[3] / "cases" / "yade" / "bouncing_sphere.py")   # the tutorial case's scenario
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


@yade_missing
def test_body_stress_tensors_match_yade():
    # A jittered lattice of slightly overlapping spheres on a wall, 3 steps: per-sphere stresses
    # on the same contacts. The bottom layer also touches the wall, where Yade's contact point
    # lies on the wall's plane and Talus's mid-overlap (as between spheres), so its a_z f_z
    # terms differ by the overlap: only the spheres off the wall are compared.
    ours, theirs = both("contact_measures_side_by_side.py")
    assert ours["contacts"] == theirs["contacts"] > 100
    a, b = np.array(ours["stress"]), np.array(theirs["stress"])
    # body 0 is the wall: Yade divides its sum by a volume a wall does not have, Talus gives zero
    assert np.all(a[0] == 0)
    off_wall = [i for i in range(1, len(a)) if i not in ours["onWall"]]
    assert len(off_wall) == 48 and ours["onWall"] == theirs["onWall"]
    assert np.max(np.abs(a[off_wall] - b[off_wall])) < 1e-9 * np.max(np.abs(b[off_wall]))


@yade_missing
def test_spheres_on_boxes_match_yade():
    # A sphere on a box's face (Yade's simple-scene), one on an edge, one rolling down a tilted
    # box: both sides of a box-sphere contact take the sphere's radius, as Yade's Ig2_Box_Sphere.
    ours, theirs = both("box_bounce.py")
    a, b = np.array(ours["x"]), np.array(theirs["x"])
    assert a.shape == b.shape == (119, 3, 6)
    assert np.abs(b[-1, :, :3] - b[0, :, :3]).max() > 0.1      # they did fall, bounce and roll
    assert np.abs(a[..., :3] - b[..., :3]).max() < 1e-8
    assert np.abs(a[..., 3:] - b[..., 3:]).max() < 1e-6 * np.abs(b[..., 3:]).max()
