"""Shared fixtures: every Python test runs against the build tree (``$TALUS_BUILD_DIR``, default
``<repo>/build``) with Debian's /usr/bin/python3, without installing anything."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("TALUS_BUILD_DIR", REPO / "build")).resolve()

if not (BUILD / "python" / "talus").is_dir():
    raise pytest.UsageError(f"no Talus build in {BUILD}: run ./setup.sh (or set TALUS_BUILD_DIR)")
sys.path.insert(0, str(BUILD / "python"))


@pytest.fixture(scope="session")
def build_dir() -> Path:
    return BUILD


@pytest.fixture(scope="session")
def repo_dir() -> Path:
    return REPO


@pytest.fixture(scope="session")
def talus_cmd(build_dir):
    """Run the build tree's `talus` command; returns the CompletedProcess."""
    def run(*args, check=True, cwd=None, env=None, timeout=120):
        done = subprocess.run([str(build_dir / "bin" / "talus"), *map(str, args)],
                              capture_output=True, text=True, cwd=cwd, env=env, timeout=timeout)
        if check and done.returncode != 0:
            raise AssertionError(f"talus {' '.join(map(str, args))} exited {done.returncode}:\n"
                                 f"{done.stdout}\n{done.stderr}")
        return done
    return run
