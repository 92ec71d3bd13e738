"""Side by side with Yade (Debian's yade 2023.02a) on identical input: the same script runs in
both programs and the trajectories must agree."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
yade = shutil.which("yade")


def trajectory(cmd, env=None):
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env, cwd=HERE)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    line = next(l for l in done.stdout.splitlines() if l.startswith("TRAJECTORY "))
    return json.loads(line[len("TRAJECTORY "):])


@pytest.mark.skipif(yade is None, reason="yade is not installed (./setup.sh installs it)")
def test_bouncing_sphere_matches_yade(build_dir):
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    ours = trajectory([sys.executable, str(HERE / "bouncing_sphere.py")], env=env)
    theirs = trajectory([yade, "-n", "-j1", "-x", str(HERE / "bouncing_sphere.py")])
    assert ours["dt"] == theirs["dt"]
    z_ours, z_yade = ours["z"], theirs["z"]
    assert min(z_yade) < 1.0            # it did bounce on the support (contact at z = 1)
    assert max(abs(a - b) for a, b in zip(z_ours, z_yade)) < 1e-6


@pytest.mark.skipif(yade is None, reason="yade is not installed (./setup.sh installs it)")
def test_hertz_mindlin_collisions_match_yade(build_dir):
    # Oblique sphere-sphere collision, then a bounce on a fixed sphere under gravity, with
    # restitution 0.7 and friction: positions and angular velocities of both moving spheres.
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    ours = trajectory([sys.executable, str(HERE / "hertz_bounce.py")], env=env)
    theirs = trajectory([yade, "-n", "-j1", "-x", str(HERE / "hertz_bounce.py")])
    a, b = ours["x"], theirs["x"]
    assert len(a) == len(b) == 3000
    spin = max(abs(v) for row in b for body in row for v in body[3:])
    assert spin > 1.0                   # the collisions did make the spheres turn
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[:3], bb[:3])) < 1e-6
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[3:], bb[3:])) < 1e-6 * spin


@pytest.mark.skipif(yade is None, reason="yade is not installed (./setup.sh installs it)")
def test_cohesive_bonds_with_moments_match_yade(build_dir):
    # CohFrict: a bonded sphere spinning on a fixed one (bending and twisting moments), a third
    # sphere bonding on impact, a bond breaking: positions and angular velocities.
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    ours = trajectory([sys.executable, str(HERE / "cohfrict_bond.py")], env=env)
    theirs = trajectory([yade, "-n", "-j1", "-x", str(HERE / "cohfrict_bond.py")])
    a, b = ours["x"], theirs["x"]
    assert len(a) == len(b) == 3000
    assert max(sum(p * p for p in row[0][:3]) ** 0.5 for row in b) > 0.11   # the first bond broke
    spin = max(abs(v) for row in b for body in row for v in body[3:])
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[:3], bb[:3])) < 1e-6
    assert max(abs(p - q) for ra, rb in zip(a, b) for ba, bb in zip(ra, rb) for p, q in zip(ba[3:], bb[3:])) < 1e-6 * spin
