"""Friction on facets as Yade's: spheres sliding and rolling in a facet box follow Yade's
trajectories (Yade takes the shear lever arms of facet contacts to the contact point)."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).parent


def positions(cmd, env=None):
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env, cwd=HERE)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return np.array(json.loads(next(l for l in done.stdout.splitlines() if l.startswith("TRAJECTORY "))[11:]))


@pytest.mark.skipif(shutil.which("yade") is None, reason="yade is not installed")
def test_sliding_and_rolling_in_a_facet_box_match_yade(build_dir):
    script = str(HERE / "facet_friction_side_by_side.py")
    ours = positions([sys.executable, script], env={**os.environ, "PYTHONPATH": str(build_dir / "python")})
    theirs = positions([shutil.which("yade"), "-n", "-j1", "-x", script])
    assert ours.shape == theirs.shape
    moved = np.abs(theirs[-1] - theirs[0]).max()
    assert moved > 0.05                                # they did slide and roll
    assert np.abs(ours - theirs).max() < 1e-8          # 30000 steps with impacts and friction
