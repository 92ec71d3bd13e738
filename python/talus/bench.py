"""Side-by-side benchmarks: a command of ours against a peer's (Yade, LIGGGHTS, ...).

Absolute times on shared machines are noise, so both programs run in the same invocation,
alternately (ours, peer, ours, peer, ...), and the figure reported is the ratio of the medians.
The runner installs nothing: a peer that is not on the machine is reported as such.

Each command yields one figure per run: its wall time (default), or a number it prints, picked
out by a regular expression with one group (e.g. ``r"([0-9.]+) iter/sec"``).
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import statistics
import subprocess
import time
from dataclasses import dataclass, field
from typing import Sequence


class PeerNotInstalled(RuntimeError):
    """The peer program of a benchmark is not on this machine."""


class CommandFailed(RuntimeError):
    """A benchmarked command exited with an error, timed out or printed no figure."""


@dataclass
class Side:
    """One side of a benchmark: a command and how to read its figure."""
    label: str
    command: Sequence[str]
    pattern: str | None = None  # regex with one group; None: the figure is the wall time
    cwd: str | None = None      # where to run (peers such as Yade write files where they run)
    env: dict[str, str] = field(default_factory=dict)  # set in the command's environment (e.g. OMP_NUM_THREADS)
    realtime: bool = False      # run under SCHED_FIFO where allowed (see realtime_prefix)
    samples: list[float] = field(default_factory=list)
    last_output: str = ""       # stdout and stderr of the latest run (for figures beside the timed one)

    @property
    def median(self) -> float:
        return statistics.median(self.samples)


@dataclass
class Comparison:
    """Medians of both sides and the ratio (>1 means ours is faster)."""
    ours: float
    theirs: float
    unit: str
    ratio: float
    ours_samples: list[float]
    theirs_samples: list[float]


def talus_command(*args: str) -> list[str]:
    """A command line running ``talus ARGS...`` with this interpreter and this talus package,
    wherever it is (build tree or install), for a benchmark's own side."""
    import os
    import sys

    import talus
    package_parent = os.path.dirname(os.path.dirname(os.path.abspath(talus.__file__)))
    launcher = f"import sys; sys.path.insert(0, {package_parent!r}); from talus.cli import main; sys.exit(main())"
    return [sys.executable, "-c", launcher, *args]


def child_environment() -> dict:
    """The environment for a process a case or test starts (``python -m talus``, under mpirun
    too): this talus package on its PYTHONPATH, wherever it was imported from (a test run adds
    it to sys.path only), and one OpenMP thread."""
    import os

    import talus
    package_parent = os.path.dirname(os.path.dirname(os.path.abspath(talus.__file__)))
    path = os.pathsep.join(filter(None, [package_parent, os.environ.get("PYTHONPATH")]))
    return {**os.environ, "OMP_NUM_THREADS": "1", "PYTHONPATH": path}


def run_talus_script(arguments: Sequence, output, processes: int | None = None, timeout: float = 1800) -> dict:
    """``talus run -j 1 ARGUMENTS`` in one process (``processes`` None) or under ``mpirun -np
    processes`` (oversubscribed; as root too), one OpenMP thread each, with this talus package;
    returns the JSON the script wrote to ``output``. Raises RuntimeError with its output if it fails."""
    import json
    import subprocess
    import sys

    command = [sys.executable, "-m", "talus", "run", "-j", "1", *map(str, arguments)]
    if processes is not None:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(processes), *command]
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=child_environment())
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
    with open(output) as f:
        return json.load(f)


def split_command(command: str | Sequence[str]) -> list[str]:
    """Accept a shell-like string or an argument list."""
    return shlex.split(command) if isinstance(command, str) else list(command)


def require_program(command: Sequence[str], label: str, hint: str = "") -> None:
    """Raise PeerNotInstalled if the command's program is not found."""
    program = command[0] if command else ""
    if not program or shutil.which(program) is None:
        advice = f" ({hint})" if hint else ""
        raise PeerNotInstalled(
            f"{label}: program {program!r} is not installed{advice}; "
            "the benchmark runner installs nothing")


_realtime: list[str] | None = None


def realtime_prefix() -> list[str]:
    """``chrt -f 10`` if this process may give its children real-time (SCHED_FIFO) priority
    (root, or CAP_SYS_NICE) and TALUS_BENCH_REALTIME is not 0, else nothing. On a quiet machine
    the guest's own kernel threads (kdamond, rcu) and daemons still take a vCPU for a moment now
    and then; a thread of a 2-thread run that loses its vCPU holds the other at the next barrier,
    so those moments scatter thread speed-ups far more than one-thread rates. Only for
    programs with no more threads than cores and no busy-polling (OpenMP runs, not MPI ranks):
    FIFO threads are not time-sliced among themselves. The kernel's real-time throttling
    (sched_rt_runtime_us) still leaves the rest of the machine 5 % of each second."""
    global _realtime
    if _realtime is None:
        _realtime = []
        if os.environ.get("TALUS_BENCH_REALTIME", "1") != "0" and shutil.which("chrt"):
            probe = subprocess.run(["chrt", "-f", "10", "true"], capture_output=True)
            if probe.returncode == 0:
                _realtime = ["chrt", "-f", "10"]
    return list(_realtime)


def run_once(side: Side, timeout: float) -> float:
    """Run one side once and return its figure."""
    command = [*realtime_prefix(), *side.command] if side.realtime else list(side.command)
    started = time.perf_counter()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, cwd=side.cwd,
                              env={**os.environ, **side.env} if side.env else None)
    except subprocess.TimeoutExpired:
        raise CommandFailed(f"{side.label}: {shlex.join(side.command)} took longer than {timeout} s") from None
    wall = time.perf_counter() - started
    output = side.last_output = done.stdout + done.stderr
    if done.returncode != 0:
        tail = "\n".join(output.strip().splitlines()[-15:])
        raise CommandFailed(
            f"{side.label}: {shlex.join(side.command)} exited with {done.returncode}:\n{tail}")
    if side.pattern is None:
        return wall
    matches = re.findall(side.pattern, output)
    if not matches:
        raise CommandFailed(f"{side.label}: no match for {side.pattern!r} in the output of "
                            f"{shlex.join(side.command)}")
    return float(matches[-1])


def run_rounds(sides: Sequence[Side], *, repeat: int = 3, unit: str = "s", timeout: float = 3600.0,
               progress=print) -> None:
    """Run every side once per round, in the given order, ``repeat`` rounds; each run's figure is
    appended to its side's samples. Runs that are neighbours in time see the same machine: ratios
    of the same round's samples cancel the drift of a shared host over the benchmark."""
    if repeat < 1:
        raise ValueError(f"repeat must be at least 1, got {repeat}")
    for i in range(repeat):
        for side in sides:
            side.samples.append(run_once(side, timeout))
            if progress:
                progress(f"[bench] run {i + 1}/{repeat} {side.label}: {side.samples[-1]:.6g} {unit}")


def compare(ours: Side, theirs: Side, *, repeat: int = 3, unit: str = "s",
            higher_is_better: bool = False, timeout: float = 3600.0,
            progress=print) -> Comparison:
    """Run both sides alternately ``repeat`` times and compare medians.

    With wall times (or any lower-is-better figure) ratio = theirs / ours; with rates
    (``higher_is_better``) ratio = ours / theirs; either way >1 means Talus is faster.
    """
    if repeat < 1:
        raise ValueError(f"repeat must be at least 1, got {repeat}")
    require_program(ours.command, ours.label)
    require_program(theirs.command, theirs.label, hint="e.g. apt-get install yade")
    run_rounds((ours, theirs), repeat=repeat, unit=unit, timeout=timeout, progress=progress)
    ratio = ours.median / theirs.median if higher_is_better else theirs.median / ours.median
    return Comparison(ours.median, theirs.median, unit, ratio, list(ours.samples),
                      list(theirs.samples))
