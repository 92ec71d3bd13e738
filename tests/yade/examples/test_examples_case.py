"""The shim-free status in CI: the examples case's quick mode runs a fixed subset of Yade
2023.02a's own example scripts unchanged under `talus run` (cases/yade_examples.py QUICK, one
script of each kind: plain scenes, default engines, periodic cells, clumps, facets, kinematic
engines, pack predicates, a triaxial test, the VANS coupling, the two-phase injection through
TwoPhaseFlowEngine's clusters) and every one must finish."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path("/usr/share/doc/yade/examples")
CASE = Path(__file__).resolve().parents[3] / "cases" / "yade_examples.py"


@pytest.mark.skipif(not EXAMPLES.is_dir(), reason="Yade's examples not installed (./setup.sh installs the yade package)")
def test_quick_subset_of_yades_examples_finishes(build_dir, tmp_path):
    env = dict(os.environ, PYTHONPATH=str(build_dir / "python"), XDG_CACHE_HOME=str(tmp_path / "cache"))
    done = subprocess.run([sys.executable, "-m", "talus", "run", "-j", "1", str(CASE), "--quick", "--results",
                           str(tmp_path)], capture_output=True, text=True, env=env, timeout=900)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    record = json.loads((tmp_path / "yade-examples.completion.json").read_text())
    table = json.loads((tmp_path / "yade-examples.details.json").read_text())["in_scope"]
    assert len(table) >= 12 and record["scripts"] == len(table)
    failed = {script: row["talus"]["error"] for script, row in table.items() if row["talus"]["status"] != "ok"}
    assert not failed and record["value"] == 1.0
