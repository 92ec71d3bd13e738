"""Result records of validation cases and benchmarks (the project's reporting contract).

Every case and benchmark writes one JSON record per checked quantity into a results folder, plus
PNG charts; ``talus report`` turns the folder into ``docs/validation.md``. A record holds:

``name``       unique dotted name, e.g. ``vans.poiseuille``
``metric``     what ``value`` is, in words
``value``      the number (errors as fractions: 0.01 is 1 %)
``reference``  what it was compared with
``tolerance``  the bound ``value`` must meet, in the sense given by ``comparison``
``pass``       whether it did
``wall_s``, ``quick``, ``git``, ``date``
benchmarks also ``peer``, ``ours``, ``theirs``, ``unit`` and ``ratio`` (>1: Talus is faster).

A case script typically reads::

    from talus import results
    args = results.case_arguments(__doc__).parse_args()
    case = results.Case("dem.bouncing-sphere", quick=args.quick, folder=args.results)
    ...
    case.record("relative error of the rebound height", err, "analytic", tolerance=1e-9)
    case.save_chart(fig, "trajectory")
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from talus.atomic import write_atomically

_NAME = re.compile(r"^[a-z0-9][a-z0-9_-]*(\.[a-z0-9][a-z0-9_-]*)+$")
_COMPARISONS = {"<=": lambda v, t: v <= t, ">=": lambda v, t: v >= t}
REQUIRED_FIELDS = ("name", "metric", "value", "reference", "tolerance", "pass", "wall_s", "quick",
                   "git", "date")
BENCHMARK_FIELDS = ("peer", "ours", "theirs", "unit", "ratio")


def default_folder() -> Path:
    """The results folder: ``$TALUS_RESULTS_DIR`` if set, else ``./results``."""
    return Path(os.environ.get("TALUS_RESULTS_DIR", "results"))


def git_commit() -> str:
    """Short commit of the source tree this build came from ("unknown" outside a checkout);
    a ``+`` marks uncommitted changes, so records from a dirty tree are recognisable."""
    from talus import _build_config
    source = _build_config.SOURCE_DIR
    try:
        commit = subprocess.run(["git", "-C", source, "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True, timeout=10, check=True).stdout
        dirty = subprocess.run(["git", "-C", source, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10, check=True).stdout
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return commit.strip() + ("+" if dirty.strip() else "")


def check_name(name: str) -> str:
    """Validate a record name (lower-case, dotted, at least two parts) and return it."""
    if not _NAME.match(name):
        raise ValueError(f"result name {name!r} must be lower-case and dotted, e.g. 'vans.poiseuille'")
    return name


def _finite(label: str, x: Any) -> float:
    try:
        value = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{label} must be a number, got {x!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{label} must be finite, got {value}")
    return value


def make_record(name: str, metric: str, value: float, reference: str, tolerance: float, *,
                wall_s: float, quick: bool, comparison: str = "<=", **extra: Any) -> dict:
    """Build a record; ``pass`` is ``value <= tolerance`` (or ``>=`` with ``comparison=">="``,
    for figures that must reach a bound, such as a speed ratio)."""
    if comparison not in _COMPARISONS:
        raise ValueError(f"comparison must be one of {sorted(_COMPARISONS)}, got {comparison!r}")
    value = _finite(f"value of {name}", value)
    tolerance = _finite(f"tolerance of {name}", tolerance)
    record = {
        "name": check_name(name),
        "metric": str(metric),
        "value": value,
        "reference": str(reference),
        "tolerance": tolerance,
        "comparison": comparison,
        "pass": bool(_COMPARISONS[comparison](value, tolerance)),
        "wall_s": _finite(f"wall_s of {name}", wall_s),
        "quick": bool(quick),
        "git": git_commit(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    }
    record.update(extra)
    return record


def write_record(record: dict, folder: Path | str | None = None) -> Path:
    """Write one record as ``<folder>/<name>.json`` and return the path."""
    folder = Path(folder) if folder is not None else default_folder()
    missing = [f for f in REQUIRED_FIELDS if f not in record]
    if missing:
        raise ValueError(f"record {record.get('name', '?')!r} lacks fields {missing}")
    path = folder / f"{check_name(record['name'])}.json"
    def write(temporary: str) -> None:
        with open(temporary, "x") as f:
            json.dump(record, f, indent=2, sort_keys=False)
            f.write("\n")

    write_atomically(path, write, fsync=True)
    return path


def read_records(folder: Path | str) -> list[dict]:
    """All records in a folder, sorted by name; a malformed file raises naming the file. A case's
    ``<name>.details.json`` (a table behind its records, such as one row per script) is not a
    record."""
    records = []
    for path in sorted(Path(folder).glob("*.json")):
        if path.name.endswith(".details.json"):
            continue
        try:
            record = json.loads(path.read_text())
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}: not valid JSON ({e})") from None
        missing = [f for f in REQUIRED_FIELDS if f not in record]
        if missing:
            raise ValueError(f"{path}: record lacks fields {missing}")
        records.append(record)
    return sorted(records, key=lambda r: r["name"])


class Case:
    """One run of a case script: holds its name prefix, mode and folder, and times the run."""

    def __init__(self, name: str, *, quick: bool, folder: Path | str | None = None):
        self.name = check_name(name)
        self.quick = quick
        self.folder = Path(folder) if folder is not None else default_folder()
        self.started = time.perf_counter()
        self.written: list[Path] = []

    def elapsed(self) -> float:
        """Wall time since the case started, in seconds."""
        return time.perf_counter() - self.started

    def record(self, metric: str, value: float, reference: str, tolerance: float, *,
               suffix: str | None = None, **extra: Any) -> dict:
        """Write a record named ``<case>`` or ``<case>.<suffix>``; returns it."""
        name = f"{self.name}.{suffix}" if suffix else self.name
        record = make_record(name, metric, value, reference, tolerance,
                             wall_s=self.elapsed(), quick=self.quick, **extra)
        if _writes():
            self.written.append(write_record(record, self.folder))
        return record

    def save_chart(self, figure: Any, suffix: str | None = None) -> Path:
        """Save a matplotlib figure as ``<folder>/<case>[.<suffix>].png``."""
        name = f"{self.name}.{suffix}" if suffix else self.name
        path = self.folder / f"{name}.png"
        if _writes():
            self.folder.mkdir(parents=True, exist_ok=True)
            figure.savefig(path, dpi=120, bbox_inches="tight")
            self.written.append(path)
        return path


def _writes() -> bool:
    """Whether this process writes a case's records and charts: under ``mpirun -np N talus run
    case.py`` every process runs the case (with the same global values: the measurements reduce
    over the processes), process 0 writes them. talus.dem.distributed is looked up, not imported:
    a case that never imported the DEM runs in one process."""
    distributed = sys.modules.get("talus.dem.distributed")
    return distributed is None or not distributed.ACTIVE or distributed.rank() == 0


def case_arguments(description: str | None = None) -> argparse.ArgumentParser:
    """The options every case script takes: ``--quick`` and ``--results DIR``."""
    parser = argparse.ArgumentParser(description=description,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="short run (under a minute on 2 cores), as CI runs it")
    parser.add_argument("--results", type=Path, default=None,
                        help="folder for JSON records and charts (default: $TALUS_RESULTS_DIR or ./results)")
    return parser
