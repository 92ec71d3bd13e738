"""The source tree's shape: dem/'s folders include only from the folders above them in the layer
table of dem/README.md, and no source folder grows past the size one reads in a sitting.

Both are read from the sources (no build needed), so a new include arrow pointing up or a folder
that has grown too large fails here, naming it.
"""
import re
import subprocess
from collections import Counter
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SOURCE_SUFFIXES = {".py", ".cpp", ".h", ".hpp", ".H", ".C", ".sh"}
MAX_SOURCES_PER_FOLDER = 18
# Folders whose file names are fixed from outside: `import yade.X` finds the module X in this
# folder, one file per module of Yade 2023.02a that scripts import.
NAMES_FIXED_OUTSIDE = {"dem/python/yade"}


def dem_layers() -> list[str]:
    """dem/'s folders in the order of dem/README.md's table, top layer first."""
    table = (REPO / "dem" / "README.md").read_text()
    return re.findall(r"^\| `(\w+)/` \|", table, flags=re.MULTILINE)


def test_dem_includes_point_only_upwards():
    layers = dem_layers()
    assert {"base", "core", "step"} <= set(layers), f"dem/README.md's layer table not found: {layers}"
    rank = {folder: k for k, folder in enumerate(layers)}
    upward = []
    for folder in layers:
        for source in sorted((REPO / "dem" / folder).rglob("*")):
            if source.suffix not in {".h", ".cpp"}:
                continue
            for included in re.findall(r'#include "dem/(\w+)/', source.read_text()):
                if included in rank and rank[included] > rank[folder]:
                    upward.append(f"{source.relative_to(REPO)} includes dem/{included}/ (a layer below)")
    assert not upward, "\n".join(upward)


def test_every_dem_folder_is_in_the_layer_table():
    folders = {p.name for p in (REPO / "dem").iterdir() if p.is_dir()}
    # distributed/ is an optional feature on top of the library, described below the table.
    assert folders - set(dem_layers()) == {"distributed"}


def test_no_source_folder_is_oversized():
    files = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    sizes = Counter(str(Path(f).parent) for f in files if Path(f).suffix in SOURCE_SUFFIXES)
    oversized = {folder: n for folder, n in sizes.items()
                 if n > MAX_SOURCES_PER_FOLDER and folder not in NAMES_FIXED_OUTSIDE}
    assert not oversized, f"folders of more than {MAX_SOURCES_PER_FOLDER} source files: {oversized}"
