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
