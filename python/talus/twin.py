"""Run one scenario script in Talus and in Yade (its twin run), for side-by-side cases.

A scenario script runs unchanged in both programs (``try: O / except NameError: from talus.dem
import *``); it reads its parameters from the JSON in the environment variable
``TALUS_SCENARIO`` and prints its result as one line ``RESULT {json}``. Yade runs it with
``yade -n -j1 -x`` in the script's folder (Yade scripts have no ``__file__``); Talus runs it with
this interpreter and this talus package, single-threaded like Yade.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

ENV = "TALUS_SCENARIO"


class ScenarioFailed(RuntimeError):
    """The scenario exited with an error or printed no RESULT line."""


def yade_available() -> bool:
    return shutil.which("yade") is not None


def run(script: str | os.PathLike, params: dict, program: str = "talus", timeout: float = 3600,
        threads: int = 1) -> dict:
    """Run ``script`` with ``params`` in ``program`` ("talus" or "yade") on ``threads`` threads
    (Yade's ``-j``, OMP_NUM_THREADS); returns its RESULT."""
    script = Path(script).resolve()
    env = {**os.environ, ENV: json.dumps(params), "OMP_NUM_THREADS": str(threads)}
    if program == "yade":
        if not yade_available():
            raise ScenarioFailed("yade is not installed")
        command = [shutil.which("yade"), "-n", f"-j{threads}", "-x", str(script)]
    elif program == "talus":
        import talus
        package_parent = str(Path(talus.__file__).resolve().parent.parent)
        env["PYTHONPATH"] = os.pathsep.join([package_parent, env.get("PYTHONPATH", "")])
        command = [sys.executable, str(script)]
    else:
        raise ValueError(f"program must be 'talus' or 'yade', got {program!r}")
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=env, cwd=script.parent)
    lines = [l for l in done.stdout.splitlines() if l.startswith("RESULT ")]
    if done.returncode != 0 or not lines:
        raise ScenarioFailed(f"{program} {script.name} failed (exit {done.returncode}):\n"
                             + done.stdout[-3000:] + done.stderr[-3000:])
    return json.loads(lines[-1][len("RESULT "):])


def run_seeds(script: str | os.PathLike, params_of, seeds, workers: int = 2) -> tuple[list[dict], list[dict]]:
    """Run ``script`` with ``params_of(seed)`` for every seed in Talus and, where Yade is installed,
    in Yade, ``workers`` single-threaded runs at a time; returns Talus's RESULTs and Yade's (empty
    without Yade), each in the order of ``seeds``."""
    programs = ["talus", "yade"] if yade_available() else ["talus"]
    jobs = [(program, seed) for seed in seeds for program in programs]
    with ThreadPoolExecutor(max_workers=workers) as pool:
        done = list(pool.map(lambda job: run(script, params_of(job[1]), job[0]), jobs))
    return ([r for (program, _), r in zip(jobs, done) if program == "talus"],
            [r for (program, _), r in zip(jobs, done) if program == "yade"])


def print_seeds(seeds, ours: list[dict], theirs: list[dict], describe) -> None:
    """One line per seed and program, ``seed <seed>: Talus|Yade  <describe(result)>``."""
    for k, seed in enumerate(seeds):
        for label, runs in (("Talus", ours), ("Yade ", theirs)):
            if runs:
                print(f"seed {seed}: {label} {describe(runs[k])}")


def record_mean_difference(case, metric: str, key: str, ours: list[dict], theirs: list[dict], tolerance: float,
                           suffix: str, reference: str = "yade 2023.02a on the same scenario file", **extra) -> None:
    """Record in ``case`` (talus.results.Case) the relative difference of the mean of ``r[key]`` over
    Talus's results ``ours`` from that over Yade's ``theirs`` (the seeds of run_seeds), with both
    means; ``metric`` is the record's metric."""
    o, t = float(np.mean([r[key] for r in ours])), float(np.mean([r[key] for r in theirs]))
    case.record(metric, abs(o / t - 1), reference, tolerance, suffix=suffix, ours=o, theirs=t, **extra)


def plot_seeds(seeds, ours: list[dict], theirs: list[dict], x, xlabel: str, panels):
    """A chart of one panel per ``(y, ylabel, title)`` of ``panels``: ``y(r)`` against ``x(r)`` for
    every seed's result ``r`` of Talus (solid) and Yade (dashed), a colour per seed, the legend on
    the first panel. Returns the figure and its axes."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 4))
    for runs, style, label in ((ours, "-", "Talus"), (theirs, "--", "Yade")):
        for k, r in enumerate(runs):
            for ax, (y, _, _) in zip(axes, panels):
                ax.plot(x(r), y(r), style, color=f"C{k}", label=f"{label}, seed {seeds[k]}")
    for ax, (_, ylabel, title) in zip(axes, panels):
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(title)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    return fig, axes
