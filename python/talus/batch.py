"""Parameter studies, as with Yade's ``yade-batch``: a table of parameters, one job per line.

A table is a text file of blank-separated columns::

    # comments start with '#', anywhere; blank lines are ignored (but counted)
    radius   n!   !OMP_NUM_THREADS     # the first non-blank line names the columns
    0.1      5    1                    # line 3: one parameter set
    =        6    =                    # '=' repeats the value of the line above
    0.3      =    2

Lines are numbered as in a text editor (line 3 above is the first job). Values are Python
expressions, evaluated with the names of ``math`` (``pi/4``, ``2*0.1``); strings are quoted
(``'glass'``); ``*`` means the script's default. A column named ``description`` names each job;
without one the description is built from the columns whose name ends in ``!`` (the ``!`` is no
part of the name), or from all columns if none does (``n=5``; a repeated description gets
``__line=N__`` added). Columns whose name starts with ``!`` are for the batch runner, not the
script: ``!THREADS`` (or ``!OMP_NUM_THREADS``) sets the job's threads, ``!SCRIPT`` its script,
any other ``!NAME`` an environment variable ``NAME`` of the job.

A script reads its line as in Yade::

    from talus.batch import readParamsFromTable, params      # Yade: from yade import utils
    readParamsFromTable(radius=0.05, n=10)                      # the defaults when run alone
    from talus.batch.params.table import *                      # Yade: from yade.params.table import *
    print(radius, n)                                            # or params.table.radius

``talus batch TABLE script.py`` runs the script once per line, several at a time, each with the
environment variable ``YADE_BATCH=TABLE:LINE`` (Yade's name, so that scripts testing it work
unchanged) and its output in a log file; see :func:`main` and ``talus batch --help``.

Differences from Yade, all where Yade fails silently or oddly: a line with fewer values than
there are columns, a ``=`` on the first line and an expression that cannot be evaluated are
errors naming the file and the line (more values than columns: a warning, the extra ones
ignored as in Yade); a trailing ``!`` is removed from a column name even when the table has a
``description`` column; the last line needs no end-of-line character.
"""

from __future__ import annotations

import argparse
import importlib.abc
import importlib.util
import math
import os
import pickle
import re
import signal
import subprocess
import sys
import time
import types
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, TextIO

__all__ = ["readParamsFromTable", "TableParamReader", "readTable", "Table", "TableError",
           "TableWarning", "saveVars", "loadVars", "waitIfBatch", "runningInBatch", "params", "tags",
           "parseLines", "BATCH_ENV"]

BATCH_ENV = "YADE_BATCH"            # "TABLE:LINE" in a job of a batch, as yade-batch sets it

# The columns the batch runner reads itself (all others starting with '!' become environment
# variables of the job).
_RUNNER_COLUMNS = {"!THREADS", "!OMP_NUM_THREADS", "!SCRIPT"}
_YADE_ONLY_COLUMNS = {"!EXEC", "!AFFINITY", "!COUNT"}


# --------------------------------------------------------------------------------------------
# The table
# --------------------------------------------------------------------------------------------

class TableError(ValueError):
    """A parameter table that cannot be read; the message names the file and the line."""


class TableWarning(UserWarning):
    """A table line that Yade reads without a word but is probably wrong (too many values)."""


@dataclass
class Table:
    """A parameter table read by :func:`readTable`.

    ``columns``: the column names in order (a trailing ``!`` removed; ``description`` included
    only if the file has it). ``lines``: line number (as in a text editor) -> column ->
    the value's text, with ``=`` resolved and ``description`` always present."""
    path: str
    columns: list[str]
    lines: dict[int, dict[str, str]]
    has_description: bool = False

    def paramDict(self) -> dict[int, dict[str, str]]:
        """Yade's ``TableParamReader.paramDict()``: line -> column -> text."""
        return self.lines

    def parameters(self) -> list[str]:
        """The columns that are parameters of the script (not ``description``, not ``!...``)."""
        return [c for c in self.columns if c != "description" and not c.startswith("!")]


def _strip_comment(text: str) -> str:
    return text.split("#", 1)[0].strip()


def readTable(path: str | os.PathLike) -> Table:
    """Read a parameter table (Yade's format, see the module's help)."""
    name = os.fspath(path)
    try:
        with open(name, encoding="utf-8") as source:
            raw = source.read().splitlines()
    except OSError as e:
        raise TableError(f"parameter table {name}: cannot be read ({e.strerror or e})") from None
    rows = [(number, _strip_comment(text).split()) for number, text in enumerate(raw, start=1)]
    rows = [(number, words) for number, words in rows if words]
    if not rows:
        raise TableError(f"parameter table {name}: no header line (the first non-blank line names the columns)")
    header_line, header = rows[0]
    has_description = "description" in header
    bang = [h[:-1] for h in header if h.endswith("!") and len(h) > 1]
    columns = [h[:-1] if h.endswith("!") and len(h) > 1 else h for h in header]
    for k, c in enumerate(columns):
        if c in columns[:k]:
            raise TableError(f"{name}, line {header_line}: column {c!r} appears twice")
    described_by = bang or columns
    lines: dict[int, dict[str, str]] = {}
    previous: dict[str, str] | None = None
    for number, words in rows[1:]:
        if len(words) > len(columns):
            # Yade ignores the values beyond the last column (its own example table has some).
            warnings.warn(f"{name}, line {number}: {len(words)} values for the {len(columns)} columns "
                          f"{' '.join(header)}; the last {len(words) - len(columns)} ignored, as in Yade",
                          TableWarning, stacklevel=2)
            words = words[:len(columns)]
        if len(words) < len(columns):
            raise TableError(f"{name}, line {number}: {len(words)} values for the {len(columns)} columns "
                             f"{' '.join(header)} (line {header_line}); values are separated by blanks and "
                             f"cannot contain any")
        values = dict(zip(columns, words))
        for c, v in values.items():
            if v == "=":
                if previous is None:
                    raise TableError(f"{name}, line {number}: '=' in column {c!r} repeats the line above, "
                                     f"but this is the first line of values")
                values[c] = previous[c]
        lines[number] = values
        previous = values
    if not has_description:
        seen: set[str] = set()
        for number, values in lines.items():
            text = ",".join(f"{c.replace('!', '')}={values[c]}" for c in described_by)
            text = text.replace("'", "").replace('"', "")
            if text in seen:
                text += f"__line={number}__"
            seen.add(text)
            values["description"] = text
    return Table(name, columns, lines, has_description)


class TableParamReader:
    """Yade's ``utils.TableParamReader(file)``: ``.paramDict()`` maps each line to its values."""

    def __init__(self, file: str | os.PathLike):
        self.table = readTable(file)
        self.values = self.table.lines

    def paramDict(self) -> dict[int, dict[str, str]]:
        return self.values


def parseLines(spec: str) -> list[int]:
    """Line numbers from yade-batch's ``--lines`` format: ``2,3-5,8,11-13`` (ranges inclusive)."""
    numbers: list[int] = []
    for part in spec.split(","):
        part = part.strip()
        m = re.fullmatch(r"(\d+)(?:-(\d+))?", part)
        if not m:
            raise ValueError(f"--lines {spec!r}: {part!r} is not a line number or a range like 3-5")
        first, last = int(m.group(1)), int(m.group(2) or m.group(1))
        if last < first:
            raise ValueError(f"--lines {spec!r}: the range {part} is empty")
        numbers += [n for n in range(first, last + 1) if n not in numbers]
    return numbers


# --------------------------------------------------------------------------------------------
# In the script: readParamsFromTable, params, tags, saveVars/loadVars
# --------------------------------------------------------------------------------------------

params = types.ModuleType("talus.batch.params", "Variables saved by saveVars (yade.params): "
                          "readParamsFromTable puts the table's line in params.table.")
params.__all__ = []
params.__path__ = []          # a package, so that `from <params>.table import *` can be imported
sys.modules[params.__name__] = params

tags: dict[str, str] = {}
"""Yade's ``O.tags`` entries set here (``line``, ``description``, ``params``, ...); copied into
``O.tags`` too when the scene has tags."""


class _ParamsModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds ``X.table`` (any mark) when the module ``X`` is :data:`params`, under whatever name
    it is imported (``talus.batch.params``, ``yade.params``), whenever it was imported."""

    def find_spec(self, fullname, path=None, target=None):
        parent, _, mark = fullname.rpartition(".")
        if parent and sys.modules.get(parent) is params and isinstance(getattr(params, mark, None), types.ModuleType):
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        return getattr(params, spec.name.rpartition(".")[2])

    def exec_module(self, module):
        pass


if not any(isinstance(f, _ParamsModules) for f in sys.meta_path):
    sys.meta_path.append(_ParamsModules())


def _scene_tags():
    """``O.tags`` of the default scene if the DEM is loaded and its scene has tags."""
    dem = sys.modules.get("talus.dem")
    scene = getattr(dem, "O", None) if dem else None
    return getattr(scene, "tags", None)


def _set_tags(**values: str) -> None:
    tags.update(values)
    scene = _scene_tags()
    if scene is not None:
        try:
            for k, v in values.items():
                scene[k] = v
        except Exception:  # a scene whose tags are read-only: ours are still in batch.tags
            pass


def _run_id() -> str:
    if "id" not in tags:
        scene = _scene_tags()
        try:
            tags["id"] = scene["id"]
        except Exception:
            tags["id"] = time.strftime("%Y%m%dT%H%M%S") + f"p{os.getpid()}"
    return tags["id"]


def saveVars(mark: str = "", loadNow: bool = True, **kw) -> None:
    """Yade's ``utils.saveVars``: keep variables under ``mark`` (in the tags, pickled, so that a
    checkpoint that saves the tags keeps them) and, with ``loadNow``, load them into
    ``params.<mark>`` (``params`` itself when ``mark`` is empty)."""
    key = "pickledPythonVariablesDictionary" + mark
    saved = pickle.loads(tags[key].encode("latin-1")) if key in tags else {}
    saved.update(kw)
    _set_tags(**{key: pickle.dumps(saved, 0).decode("latin-1")})
    if loadNow:
        loadVars(mark)


def loadVars(mark: str | None = None) -> None:
    """Yade's ``utils.loadVars``: variables saved by :func:`saveVars` into ``params.<mark>``
    (every mark when ``mark`` is None)."""
    prefix = "pickledPythonVariablesDictionary"
    marks = [mark] if mark is not None else [k[len(prefix):] for k in tags if k.startswith(prefix)]
    for m in marks:
        values = pickle.loads(tags[prefix + m].encode("latin-1"))
        if not m:
            params.__dict__.update(values)
            params.__all__ += [k for k in values if k not in params.__all__]
            continue
        module = types.ModuleType(f"{params.__name__}.{m}")
        module.__dict__.update(values)
        module.__all__ = list(values)     # names starting with '_' are imported by * too
        setattr(params, m, module)
        if m not in params.__all__:
            params.__all__.append(m)
        # Under every name the params module has (talus.batch.params, yade.params, ...).
        for name, mod in list(sys.modules.items()):
            if mod is params:
                sys.modules[f"{name}.{m}"] = module


def _evaluate(text: str, where: str, column: str):
    namespace = {k: v for k, v in vars(math).items() if not k.startswith("__")}
    try:
        return eval(text, namespace)
    except Exception as e:
        hint = f" (a text value is quoted: '{text}')" if isinstance(e, (NameError, SyntaxError)) else ""
        raise TableError(f"{where}: the value {text!r} of column {column!r} is not a Python expression: "
                         f"{type(e).__name__}: {e}{hint}") from None


def runningInBatch() -> bool:
    """Whether this script runs as a job of a batch (``talus batch`` or ``yade-batch``)."""
    return BATCH_ENV in os.environ


def waitIfBatch() -> None:
    """Yade's ``utils.waitIfBatch``: wait for the background run to end in a batch job. Talus's
    ``O.run`` always returns at the end of the run, so there is nothing to wait for unless the
    scene has a ``wait``."""
    if runningInBatch():
        dem = sys.modules.get("talus.dem")
        wait = getattr(getattr(dem, "O", None), "wait", None) if dem else None
        if callable(wait):
            wait()


def readParamsFromTable(tableFileLine: str | None = None, noTableOk: bool = True, unknownOk: bool = False,
                        **defaults) -> int:
    """Yade's ``utils.readParamsFromTable``: the parameters of this run, from one line of a table.

    The line is ``tableFileLine`` ("file:line"), or else the one the batch runner gives in the
    environment variable ``YADE_BATCH``; with neither (the script run alone), the keyword
    arguments' values are used (or ``EnvironmentError`` if ``noTableOk`` is False). Every
    parameter, from the table or default, goes to the module ``params.table`` (``from
    talus.batch.params.table import *``; ``yade.params.table`` in Yade's names); they are not
    put in the script's namespace by themselves, as in Yade.

    A table column must have a default here unless ``unknownOk`` (then it is assigned too);
    ``description`` and columns starting with ``!`` are not parameters. Tags as in Yade's
    ``O.tags``: ``line`` (``l3``, or ``l!`` alone), ``description``, ``params`` (``name=text,...``
    from the table), ``defaultParams``, ``id.d``, ``d.id``. Returns the number of parameters
    the table assigned."""
    given = tableFileLine or os.environ.get(BATCH_ENV, "")
    values: dict = {}
    from_table: list[str] = []
    remaining = dict(defaults)
    if not given:
        if not noTableOk:
            raise EnvironmentError(f"readParamsFromTable: no table line: {BATCH_ENV} is not set (run the "
                                   f"script with `talus batch TABLE script.py`, or give tableFileLine='file:line')")
        _set_tags(line="l!")
    else:
        path, sep, number = given.rpartition(":")
        source = "tableFileLine" if tableFileLine else f"{BATCH_ENV}={given!r}"
        if not sep or not path or not number.strip().isdigit():
            raise ValueError(f"readParamsFromTable: {source} must be 'TABLE:LINE' (e.g. 'study.table:4')")
        line = int(number)
        table = readTable(path)
        if line not in table.lines:
            raise RuntimeError(f"readParamsFromTable: the table {path} has no parameter line {line} "
                               f"(its lines of values: {', '.join(map(str, table.lines)) or 'none'})")
        row = table.lines[line]
        where = f"{path}, line {line}"
        for column in table.columns:
            if column == "description" or column.startswith("!"):
                continue
            if column not in defaults and not unknownOk:
                raise NameError(f"readParamsFromTable: {where}: the column {column!r} is no parameter of the "
                                f"script (its parameters: {', '.join(defaults) or 'none'}); give it a default "
                                f"in readParamsFromTable(...) or pass unknownOk=True")
            text = row[column]
            if text == "*":
                if column not in defaults:
                    raise NameError(f"readParamsFromTable: {where}: '*' in column {column!r} asks for the "
                                    f"default, but the script gives none")
                continue                     # stays in `remaining`: a default
            remaining.pop(column, None)
            values[column] = _evaluate(text, where, column)
            from_table.append(f"{column}={text}")
        run_id = _run_id()
        _set_tags(line=f"l{line}", description=row["description"],
                  **{"id.d": f"{run_id}.{row['description']}", "d.id": f"{row['description']}.{run_id}"})
    values.update(remaining)
    _set_tags(params=",".join(from_table), defaultParams=",".join(f"{k}={v}" for k, v in remaining.items()))
    saveVars("table", loadNow=True, **values)
    return len(from_table)


# --------------------------------------------------------------------------------------------
# The batch runner: talus batch TABLE script.py
# --------------------------------------------------------------------------------------------

def _hms(seconds: float) -> str:
    s = int(seconds)
    return f"{s // 3600:02d}:{s % 3600 // 60:02d}:{s % 60:02d}"


@dataclass
class Job:
    num: int
    line: int | None             # table line; None without a table
    description: str
    script: str
    threads: int
    env: dict[str, str]          # set for this job, on top of the runner's environment
    log: str
    status: str = "pending"      # pending, running, ok, failed, timeout
    exit_status: int | None = None
    started: float | None = None
    finished: float | None = None
    process: subprocess.Popen | None = field(default=None, repr=False)
    log_file: TextIO | None = field(default=None, repr=False)
    killed_at: float | None = None

    @property
    def id(self) -> str:
        return self.description + ("" if self.threads == 1 else f"/{self.threads}")

    @property
    def duration(self) -> float:
        if self.started is None:
            return 0.0
        return (self.finished or time.monotonic()) - self.started


def _command(job: Job) -> list[str]:
    """``talus run -j THREADS script``, with the Python and the package of this runner."""
    flags = ["-P"] if sys.version_info >= (3, 11) else []   # the cwd's folders shadow no package
    return [sys.executable, *flags, "-m", "talus", "run", "-j", str(job.threads), job.script]


def _shown(job: Job) -> str:
    env = " ".join(f"{k}={v}" for k, v in job.env.items() if k != "DISPLAY")
    return f"{env} talus run -j {job.threads} {job.script} > {job.log} 2>&1".strip()


def _cores() -> int:
    try:
        n = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        n = os.cpu_count() or 1
    if os.environ.get("OMP_NUM_THREADS", "").isdigit() and int(os.environ["OMP_NUM_THREADS"]) > 0:
        n = min(n, int(os.environ["OMP_NUM_THREADS"]))       # as yade-batch
    return n


def plan(inputs: list[str], lines: str | None = None, job_threads: int = 1, log_format: str = "$.@.log",
         max_cores: int | None = None, force_threads: bool = False, err: TextIO | None = None) -> list[Job]:
    """The jobs of ``talus batch INPUTS``: ``[TABLE, SCRIPT.py]``, ``[TABLE]`` (with a ``!SCRIPT``
    column) or ``[SCRIPT.py[/THREADS], ...]`` (each script once, without parameters).
    Raises ValueError (or TableError) with a message for the user."""
    max_cores = max_cores or _cores()
    err = err or sys.stderr
    if not inputs:
        raise ValueError("give a table and a script (talus batch TABLE script.py)")
    if all(re.fullmatch(r".*\.py(/\d+)?", a) for a in inputs):
        table, scripts = None, inputs
    elif len(inputs) <= 2 and not inputs[0].endswith(".py") and (len(inputs) == 1 or inputs[1].endswith(".py")):
        table, scripts = inputs[0], inputs[1:]
    else:
        raise ValueError(f"expected TABLE [SCRIPT.py] or SCRIPT.py ..., got {' '.join(inputs)} "
                         f"(a table's name must not end in .py, a script's must)")
    rows: dict[int | None, dict[str, str]] = {}
    if table is not None:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", TableWarning)
            t = readTable(table)
        for w in caught:
            print(f"talus batch: warning: {w.message}", file=err)
        use = list(t.lines)
        if lines:
            wanted = parseLines(lines)
            missing = [n for n in wanted if n not in t.lines]
            if missing:
                print(f"talus batch: warning: {table} has no parameter line {', '.join(map(str, missing))}; "
                      f"skipped (its lines: {', '.join(map(str, t.lines)) or 'none'})", file=err)
            use = [n for n in wanted if n in t.lines]
        if not use:
            raise ValueError(f"{table}: no line of parameters to run"
                             + (f" among --lines {lines}" if lines else ""))
        rows = {n: t.lines[n] for n in use}
        if not scripts and not all("!SCRIPT" in r for r in rows.values()):
            raise ValueError(f"{table} has no !SCRIPT column: give the script to run (talus batch {table} script.py)")
        for name in t.columns:
            if name in _YADE_ONLY_COLUMNS:
                print(f"talus batch: warning: column {name} of {table} is yade-batch's only; ignored", file=err)
    else:
        for k, s in enumerate(scripts):
            m = re.fullmatch(r"(.*\.py)(?:/(\d+))?", s)
            rows[-k - 1] = {"description": "default", "!SCRIPT": m.group(1),
                            **({"!THREADS": m.group(2)} if m.group(2) else {})}
    jobs: list[Job] = []
    logs: set[str] = set()
    for line, row in rows.items():
        script = row.get("!SCRIPT", scripts[0] if scripts else "")
        threads = job_threads
        env = {BATCH_ENV: f"{os.path.abspath(table)}:{line}" if table else "", "DISPLAY": ""}
        for column, value in row.items():
            if not column.startswith("!") or column in _YADE_ONLY_COLUMNS:
                continue
            if column in ("!THREADS", "!OMP_NUM_THREADS"):
                if not value.isdigit() or int(value) < 1:
                    raise ValueError(f"{table}, line {line}: {column} must be a number of threads, got {value!r}")
                threads = int(value)
            elif column not in _RUNNER_COLUMNS:
                env[column[1:]] = value
        if threads > max_cores:
            if force_threads:
                threads = max_cores
            else:
                print(f"talus batch: warning: job #{len(jobs)} asks for {threads} threads, "
                      f"but only {max_cores} cores are available", file=err)
        env["OMP_NUM_THREADS"] = str(threads)
        if not Path(script).is_file():
            where = f" ({table}, line {line})" if "!SCRIPT" in row and table else ""
            raise ValueError(f"no such script: {script}{where}")
        description = row["description"].replace(os.sep, "_")
        log = (log_format.replace("$", script).replace("%", str(line if table else len(jobs)))
               .replace("@", description))
        if len(log) > 230:                       # as yade-batch: file names have a length limit
            log = f"{log[:230]}_{line}{log[-4:]}"
        if log in logs:
            k = 0
            while f"{log}.{k}" in logs:
                k += 1
            log = f"{log}.{k}"
        logs.add(log)
        if "!SCRIPT" in row:                    # as yade-batch: several scripts, named apart
            description = f"{script}.{description}"
        jobs.append(Job(len(jobs), line if table else None, description, script, threads, env, log))
    return jobs


def _start(job: Job, nice: int) -> None:
    Path(job.log).parent.mkdir(parents=True, exist_ok=True)
    job.log_file = open(job.log, "w", encoding="utf-8")
    env = {**os.environ, **job.env}
    # The job imports the same talus package as this runner.
    import talus
    root = str(Path(talus.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join([root, *filter(None, [os.environ.get("PYTHONPATH")])])
    job.started = time.monotonic()
    job.status = "running"
    job.process = subprocess.Popen(_command(job), stdin=subprocess.DEVNULL, stdout=job.log_file,
                                   stderr=subprocess.STDOUT, env=env, start_new_session=True,
                                   preexec_fn=(lambda: os.nice(nice)) if nice else None)


def _finish(job: Job, code: int, timed_out: bool, timeout: float | None) -> None:
    job.finished = time.monotonic()
    job.exit_status = code
    job.status = "timeout" if timed_out else "ok" if code == 0 else "failed"
    wall = time.time()
    with open(job.log, "a", encoding="utf-8") as log:
        log.write(f"\n=================== JOB SUMMARY ================\n"
                  f"id      : {job.description}\n"
                  f"status  : {code} ({'OK' if job.status == 'ok' else 'FAILED'}"
                  f"{f', timed out after {timeout:g} s' if timed_out else ''})\n"
                  f"duration: {_hms(job.duration)}\n"
                  f"command : {_shown(job)}\n"
                  f"started : {time.asctime(time.localtime(wall - job.duration))}\n"
                  f"finished: {time.asctime(time.localtime(wall))}\n")
    if job.log_file:
        job.log_file.close()
        job.log_file = None


def _kill(job: Job, sig: int) -> None:
    try:
        os.killpg(job.process.pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def run_jobs(jobs: list[Job], max_cores: int, timeout: float | None = None, nice: int = 0,
             out: TextIO | None = None, poll: float = 0.05) -> None:
    """Run the jobs, at most ``max_cores`` threads at a time (a job asking for more than all runs
    alone), killing any that runs longer than ``timeout`` seconds. Prints a line as each job
    starts and ends."""
    out = out or sys.stdout
    try:
        while any(j.status in ("pending", "running") for j in jobs):
            running = [j for j in jobs if j.status == "running"]
            free = max_cores - sum(j.threads for j in running)
            for job in (j for j in jobs if j.status == "pending"):
                if job.threads <= free or not running:
                    _start(job, nice)
                    running.append(job)
                    free -= job.threads
                    print(f"#{job.num} ({job.id}) started on {time.asctime()}", file=out, flush=True)
            time.sleep(poll)
            for job in running:
                code = job.process.poll()
                if code is None:
                    if timeout and job.duration > timeout:
                        if job.killed_at is None:
                            job.killed_at = time.monotonic()
                            _kill(job, signal.SIGTERM)
                        elif time.monotonic() - job.killed_at > 5:
                            _kill(job, signal.SIGKILL)
                    continue
                _finish(job, code, job.killed_at is not None, timeout)
                what = {"ok": "done", "failed": "FAILED"}.get(job.status, f"FAILED (timeout {timeout or 0:g} s)")
                print(f"#{job.num} ({job.id}) {what} (exit status {code}), duration {_hms(job.duration)}, "
                      f"log {job.log}", file=out, flush=True)
    except KeyboardInterrupt:
        for job in jobs:
            if job.status == "running":
                _kill(job, signal.SIGTERM)
                job.process.wait()
                _finish(job, job.process.returncode, False, None)
                job.status = "failed"
        raise


def summary(jobs: list[Job], wall: float, out: TextIO | None = None) -> bool:
    """Print the summary of a finished batch; True if every job succeeded."""
    out = out or sys.stdout
    ok = [j for j in jobs if j.status == "ok"]
    failed = [j for j in jobs if j.status != "ok"]
    print(f"talus batch: {len(jobs)} job{'s' if len(jobs) != 1 else ''}: {len(ok)} ok, {len(failed)} failed; "
          f"wall time {_hms(wall)} ({wall:.1f} s), jobs' total {sum(j.duration for j in jobs):.1f} s", file=out)
    width = max(len(j.id) for j in jobs)
    for j in jobs:
        state = {"ok": "ok", "failed": f"FAILED ({j.exit_status})", "timeout": "TIMEOUT",
                 "pending": "not run", "running": "not finished"}[j.status]
        where = f"line {j.line}" if j.line is not None else "no table"
        print(f"  #{j.num:<3} {where:<9} {j.id:<{width}}  {state:<12} {j.duration:8.1f} s  {j.log}", file=out)
    print("Log files:", " ".join(j.log for j in jobs), file=out, flush=True)
    return not failed


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``talus batch`` (yade-batch's, where they apply)."""
    p.usage = "talus batch [options] TABLE [SCRIPT.py] | SCRIPT.py[/THREADS] ..."
    p.add_argument("inputs", nargs="+", metavar="INPUT",
                   help="a parameter table and the script run for each of its lines (or a table with a "
                        "!SCRIPT column, or scripts run once each)")
    p.add_argument("-j", "--jobs", type=int, default=None, metavar="NUM",
                   help=f"cores used at once by all jobs (default: the cores available, {_cores()} here)")
    p.add_argument("--job-threads", type=int, default=1, metavar="NUM",
                   help="threads of each job, unless its line has !THREADS (default 1)")
    p.add_argument("--force-threads", action="store_true",
                   help="never give a job more threads than -j, even if its !THREADS asks for more")
    p.add_argument("-l", "--lines", default=None, metavar="LIST",
                   help="the table's lines to run, e.g. 2,3-5,8 (default: all)")
    p.add_argument("--log", default="$.@.log", metavar="FORMAT",
                   help="name of each job's log: $ is the script, %% the line, @ the description "
                        "(default $.@.log, as yade-batch)")
    p.add_argument("--timeout", type=float, default=None, metavar="SECONDS",
                   help="stop a job running longer than this and count it failed (default: none)")
    p.add_argument("--nice", type=int, default=10, help="nice value of the jobs (default 10, as yade-batch)")
    p.add_argument("--dry-run", action="store_true", help="list the jobs without running them")


def main(args: argparse.Namespace, out: TextIO | None = None, err: TextIO | None = None) -> int:
    """``talus batch``: 0 if every job succeeded, 1 if any failed, 2 for bad input."""
    out, err = out or sys.stdout, err or sys.stderr
    for name in ("jobs", "job_threads"):
        value = getattr(args, name)
        if value is not None and value < 1:
            print(f"talus batch: --{name.replace('_', '-')} must be at least 1, got {value}", file=err)
            return 2
    if args.timeout is not None and args.timeout <= 0:
        print(f"talus batch: --timeout must be positive, got {args.timeout:g}", file=err)
        return 2
    if not any(c in args.log for c in "$%@"):
        print(f"talus batch: --log {args.log!r} must contain $, % or @ (else every job writes the same log)",
              file=err)
        return 2
    cores = args.jobs or _cores()
    try:
        jobs = plan(args.inputs, args.lines, args.job_threads, args.log, cores, args.force_threads, err)
    except (ValueError, TableError) as e:
        print(f"talus batch: {e}", file=err)
        return 2
    print(f"talus batch: {len(jobs)} job{'s' if len(jobs) != 1 else ''}, at most {cores} "
          f"core{'s' if cores != 1 else ''} at once" + (f", timeout {args.timeout:g} s" if args.timeout else ""),
          file=out)
    for j in jobs:
        print(f"   #{j.num} ({j.id}): {_shown(j)}", file=out)
    out.flush()
    if args.dry_run:
        return 0
    t0 = time.monotonic()
    try:
        run_jobs(jobs, cores, args.timeout, args.nice, out)
    except KeyboardInterrupt:
        print("talus batch: interrupted", file=err)
        summary(jobs, time.monotonic() - t0, out)
        return 130
    return 0 if summary(jobs, time.monotonic() - t0, out) else 1
