"""docs/getting-started.md, "Your first runs": every command of the section runs as written, in a
scratch folder that holds links to the clone's build/ and cases/ (so the commands' own outputs
land there; cases write their records to $TALUS_RESULTS_DIR), after the page's Python block
(`# falling.py: ...`) is saved under its name. Each command must exit 0 and every picture the
page shows must exist (committed, or produced by the command in the scratch folder)."""
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("TALUS_BUILD_DIR", REPO / "build")).resolve()
PAGE = REPO / "docs" / "getting-started.md"


def section() -> str:
    text = PAGE.read_text()
    start = text.index("## Your first runs")
    return text[start:text.index("\n## ", start + 1)]


def blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", section(), re.S)


def commands() -> list[str]:
    return [line for block in blocks("sh") for line in block.splitlines() if line.strip()]


def test_the_page_has_each_kind_of_run():
    text = " ".join(commands())
    for what in ("01_demo_cfd_dem.py", "case cfd", "falling.py", "case permeability", "case femxdem",
                 "vans_sediment_transport.py"):
        assert what in text
    for picture in re.findall(r"!\[[^]]*\]\(([^)]+)\)", section()):
        assert (PAGE.parent / picture).is_file(), f"{picture} is not committed"


@pytest.mark.skipif(not (BUILD / "bin" / "talusVolumeAveragedFoam").exists() or shutil.which("mpirun") is None,
                    reason="coupling, foam-solvers or mpirun missing")
def test_every_command_runs(tmp_path):
    (tmp_path / "build").symlink_to(BUILD)
    (tmp_path / "cases").symlink_to(REPO / "cases")
    for block in blocks("python"):
        name = re.match(r"# (\S+\.py):", block).group(1)
        (tmp_path / name).write_text(block)
    env = dict(os.environ, TALUS_RESULTS_DIR=str(tmp_path / "results"), PYTHONPATH=str(BUILD / "python"))
    for command in commands():
        done = subprocess.run(command, shell=True, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, f"{command}\n{done.stdout[-2000:]}\n{done.stderr[-3000:]}"
    for produced in ("results/demo.cfd_dem.png", "results/demo_cfd_dem/case.foam", "results/demo_cfd_dem/VTK/beads.pvd",
                     "my_column/processor1", "falling.png", "perm/permeability.csv", "perm/permeability.png",
                     "femxdem/biaxial.png", "results/vans.sediment-transport.series.png"):
        assert (tmp_path / produced).exists(), produced
