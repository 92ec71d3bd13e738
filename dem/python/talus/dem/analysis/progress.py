"""A progress line for long runs: iteration, simulated time, steps per second, time left.

Two ways to use it:

- ``run(O, n)`` runs ``n`` steps like ``O.run(n)`` (the same steps, so the same result) and shows
  the line while it runs;
- ``ProgressReporter(target=...)`` is an engine for ``O.engines``, for runs driven otherwise.

The line goes to stderr about every ``interval`` seconds (2 by default). On a terminal it is
rewritten in place (carriage return); otherwise (a log file, CI) each report is a plain line.
"""

from __future__ import annotations

import sys
import time as _time
from typing import TYPE_CHECKING, TextIO

from talus.dem.step.engines import PyRunner
from talus.dem.files.io import owner_scene

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

__all__ = ["format_line", "Progress", "ProgressReporter", "run"]


def _duration(seconds: float) -> str:
    if seconds != seconds or seconds == float("inf"):
        return "?"
    seconds = int(round(seconds))
    hours, rest = divmod(seconds, 3600)
    return f"{hours}:{rest // 60:02d}:{rest % 60:02d}"


def format_line(iteration: int, sim_time: float, rate: float, target: int | None = None,
                elapsed: float | None = None) -> str:
    """``iter 1200/5000 (24%)  t=1.2e-03 s  8.41e+03 steps/s  ETA 0:00:05``."""
    parts = [f"iter {iteration}" + (f"/{target} ({100 * iteration / target:.0f}%)" if target else "")]
    parts.append(f"t={sim_time:.4g} s")
    parts.append(f"{rate:.3g} steps/s" if rate > 0 else "- steps/s")
    if target:
        left = max(target - iteration, 0)
        parts.append("ETA " + (_duration(left / rate) if rate > 0 else "?"))
    if elapsed is not None:
        parts.append(f"elapsed {_duration(elapsed)}")
    return "  ".join(parts)


class Progress:
    """The line's state: call :meth:`update` often (it prints at most every ``interval`` s),
    :meth:`finish` at the end."""

    def __init__(self, target: int | None = None, interval: float = 2.0, stream: TextIO | None = None):
        self.target = target
        self.interval = float(interval)
        self.stream = stream if stream is not None else sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._start = self._last = _time.monotonic()
        self._last_iter: int | None = None
        self._rate = 0.0
        self._width = 0

    def _emit(self, line: str, final: bool = False):
        if self.tty:
            self.stream.write("\r" + line.ljust(self._width) + ("\n" if final else ""))
            self._width = len(line)
        else:
            self.stream.write(line + "\n")
        self.stream.flush()

    def update(self, iteration: int, sim_time: float, force: bool = False) -> bool:
        """Report if ``interval`` has passed since the last report; returns whether it did."""
        now = _time.monotonic()
        if self._last_iter is None:
            self._last_iter, self._last = iteration, now
            return False
        if not force and now - self._last < self.interval:
            return False
        if now > self._last:
            self._rate = (iteration - self._last_iter) / (now - self._last)
        self._last_iter, self._last = iteration, now
        self._emit(format_line(iteration, sim_time, self._rate, self.target))
        return True

    def finish(self, iteration: int, sim_time: float, steps: int | None = None):
        """Final line: where the run ended, its mean speed and how long it took."""
        elapsed = _time.monotonic() - self._start
        rate = steps / elapsed if steps is not None and elapsed > 0 else self._rate
        self._emit(format_line(iteration, sim_time, rate, self.target, elapsed) + "  done", final=True)


def run(scene: "Scene", nSteps: int, interval: float = 2.0, stream: TextIO | None = None) -> None:
    """Run ``nSteps`` steps of ``scene`` (as ``scene.run(nSteps)``) with a progress line.

    The steps are run in chunks sized to take about a tenth of ``interval`` each, so the line
    is updated on time without slowing the run; the result is the same as one ``run``."""
    if nSteps < 0:
        raise ValueError(f"run: nSteps must be >= 0, got {nSteps}")
    target = scene.iter + int(nSteps)
    progress = Progress(target, interval, stream)
    progress.update(scene.iter, scene.time)
    chunk, done = 1, 0
    try:
        while done < nSteps:
            step = min(chunk, nSteps - done)
            t0 = _time.monotonic()
            scene.run(step)
            spent = _time.monotonic() - t0
            done += step
            progress.update(scene.iter, scene.time)
            # Aim at chunks of interval / 10 (at most 4x growth at a time).
            wanted = step * (0.1 * progress.interval) / spent if spent > 0 else 4 * step
            chunk = max(1, min(int(wanted), 4 * step))
    finally:
        progress.finish(scene.iter, scene.time, done)


class ProgressReporter(PyRunner):
    """An engine printing the progress line (put it last in ``O.engines``). ``target``: the
    iteration the run ends at, for the percentage and the ETA (none if 0). It checks the clock
    a few times per ``interval`` and adapts its own period to the speed of the run."""

    def __init__(self, target: int = 0, interval: float = 2.0, label: str = ""):
        super().__init__(command=self._tick, iterPeriod=1, label=label)
        self.target = int(target)
        self.interval = float(interval)
        self._progress: Progress | None = None
        self._mark: tuple[int, float] | None = None

    def _tick(self):
        scene = owner_scene(self)
        if self._progress is None:
            self._progress = Progress(self.target or None, self.interval)
        self._progress.target = self.target or None
        self._progress.update(scene.iter, scene.time)
        # Measure the speed over >= 50 ms and be called about 5 times per interval.
        now = _time.monotonic()
        if self._mark is None:
            self._mark = (scene.iter, now)
        elif now - self._mark[1] >= 0.05:
            rate = (scene.iter - self._mark[0]) / (now - self._mark[1])
            self._cpp.iterPeriod = max(1, int(rate * self.interval / 5))
            self._mark = (scene.iter, now)
