"""Parameter studies as with yade-batch: talus.batch (the table, readParamsFromTable, saveDataTxt)
and `talus batch TABLE script.py`, checked against Yade's own reader on the same tables."""
import importlib
import json
import os
import shutil
import subprocess
import sys
import textwrap
import warnings

import pytest

from talus import batch, plot

yade_missing = pytest.mark.skipif(shutil.which("yade") is None, reason="yade is not installed (./setup.sh installs it)")

# Yade's format: comments, blank lines (counted), '=' repeats the line above (recursively), '!'
# columns: a trailing '!' picks the columns of the description, a leading one is the runner's.
BANG_TABLE = """\
# a parameter study
radius   n!   !OMP_NUM_THREADS   name!     # the header
0.1      5    1                  'glass'

# a blank line and a comment line: counted, not used
=        6    =                  =         # repeats 0.1, 1, 'glass'
2*pi     =    2                  'steel'
0.4      6    1                  'steel'
0.5      6    1                  'steel'
"""

# yade's examples/test/batch/params.table (its line 8 has one value too many, ignored by both)
YADE_EXAMPLE_TABLE = """\
!OMP_NUM_THREADS important! unimportant this! more
# comment
\t# comment and empty line

2 51 'hummm' 3.1415  'a'
1 51 'paaah' = 'b'
= 52 = 'fff' = 'c'
= =  'not' = 'd'\x20
3 52 'yes' 2.71828 'e'
"""

DESCRIPTION_TABLE = """\
description   radius   steps   !OMP_NUM_THREADS
small         0.1      100     1
big           0.3      =       =
tiny          1e-3     50      1
"""


@pytest.fixture(autouse=True)
def no_batch_environment(monkeypatch):
    monkeypatch.delenv(batch.BATCH_ENV, raising=False)
    batch.tags.clear()


def write(folder, name, text):
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


# -- the table ---------------------------------------------------------------------------------

def test_table_with_bang_columns_and_repeats(tmp_path):
    t = batch.readTable(write(tmp_path, "study.table", BANG_TABLE))
    assert t.columns == ["radius", "n", "!OMP_NUM_THREADS", "name"]
    assert list(t.lines) == [3, 6, 7, 8, 9]          # as a text editor numbers them
    assert t.lines[6] == {"radius": "0.1", "n": "6", "!OMP_NUM_THREADS": "1", "name": "'glass'",
                          "description": "n=6,name=glass"}
    assert t.lines[7]["n"] == "6"                     # '=' below '=': the value two lines up
    assert t.lines[3]["description"] == "n=5,name=glass"
    # A description already taken gets the line number.
    assert t.lines[7]["description"] == "n=6,name=steel"
    assert t.lines[8]["description"] == "n=6,name=steel__line=8__"
    assert t.lines[9]["description"] == "n=6,name=steel__line=9__"
    assert t.parameters() == ["radius", "n", "name"]
    assert batch.TableParamReader(tmp_path / "study.table").paramDict() == t.lines


def test_table_with_description_column(tmp_path):
    t = batch.readTable(write(tmp_path, "d.table", DESCRIPTION_TABLE))
    assert t.has_description
    assert {n: r["description"] for n, r in t.lines.items()} == {2: "small", 3: "big", 4: "tiny"}
    assert t.lines[3] == {"description": "big", "radius": "0.3", "steps": "100", "!OMP_NUM_THREADS": "1"}


def test_table_without_bang_columns_describes_with_all(tmp_path):
    t = batch.readTable(write(tmp_path, "plain.table", "a b\n1 'x'\n2 'y'"))   # no final newline
    assert [r["description"] for r in t.lines.values()] == ["a=1,b=x", "a=2,b=y"]


@pytest.mark.parametrize("text, line, words", [
    ("a b c\n1 2 3\n4 5\n", 3, "2 values for the 3 columns"),
    ("a b\n= 2\n", 2, "'=' in column 'a'"),
    ("a a\n1 2\n", 1, "column 'a' appears twice"),
])
def test_bad_tables_name_the_file_and_line(tmp_path, text, line, words):
    path = write(tmp_path, "bad.table", text)
    with pytest.raises(batch.TableError) as e:
        batch.readTable(path)
    assert f"{path}, line {line}" in str(e.value) and words in str(e.value)


def test_extra_values_are_ignored_with_a_warning(tmp_path):
    path = write(tmp_path, "extra.table", "a b\n1 2\n3 4 5\n")
    with pytest.warns(batch.TableWarning, match=f"{path}, line 3: 3 values for the 2 columns"):
        t = batch.readTable(path)
    assert t.lines[3] == {"a": "3", "b": "4", "description": "a=3,b=4"}


def test_empty_or_missing_table(tmp_path):
    with pytest.raises(batch.TableError, match="no header line"):
        batch.readTable(write(tmp_path, "empty.table", "# nothing\n\n"))
    with pytest.raises(batch.TableError, match="cannot be read"):
        batch.readTable(tmp_path / "nope.table")


def test_line_ranges():
    assert batch.parseLines("2,3-5,8,11-13") == [2, 3, 4, 5, 8, 11, 12, 13]
    assert batch.parseLines("4,4,2-3") == [4, 2, 3]
    for bad in ("2-", "a", "5-3", ""):
        with pytest.raises(ValueError):
            batch.parseLines(bad)


# -- readParamsFromTable ------------------------------------------------------------------------

def test_defaults_when_run_alone():
    assert not batch.runningInBatch()
    assert batch.readParamsFromTable(radius=0.05, name="sand") == 0
    from talus.batch.params.table import name, radius
    assert (radius, name) == (0.05, "sand")
    assert batch.params.table.radius == 0.05
    assert batch.tags["line"] == "l!" and batch.tags["defaultParams"] == "radius=0.05,name=sand"
    with pytest.raises(EnvironmentError, match="YADE_BATCH"):
        batch.readParamsFromTable(noTableOk=False, radius=1)
    batch.waitIfBatch()               # nothing to wait for


def test_line_from_the_environment(tmp_path, monkeypatch):
    path = write(tmp_path, "study.table", BANG_TABLE)
    monkeypatch.setenv("YADE_BATCH", f"{path}:7")
    assert batch.runningInBatch()
    assert batch.readParamsFromTable(radius=1.0, n=1, name="x", extra=[1, 2]) == 3
    ns = {}
    exec("from talus.batch.params.table import *", ns)
    assert ns["radius"] == pytest.approx(6.283185307179586)    # evaluated with math's names
    assert (ns["n"], ns["name"], ns["extra"]) == (6, "steel", [1, 2])
    assert "OMP_NUM_THREADS" not in str(ns.keys())           # the runner's column
    assert batch.tags["line"] == "l7" and batch.tags["description"] == "n=6,name=steel"
    assert batch.tags["params"] == "radius=2*pi,n=6,name='steel'"
    assert batch.tags["defaultParams"] == "extra=[1, 2]"
    assert batch.tags["id.d"].endswith(".n=6,name=steel") and batch.tags["d.id"].startswith("n=6,name=steel.")
    # tableFileLine wins over the environment; '*' keeps the default.
    star = write(tmp_path, "star.table", "radius n\n* 3\n")
    batch.readParamsFromTable(f"{star}:2", radius=0.7, n=1)
    assert (batch.params.table.radius, batch.params.table.n) == (0.7, 3)
    assert batch.tags["defaultParams"] == "radius=0.7"


def test_params_under_another_name(tmp_path):
    """yade.params is talus.batch.params: `from yade.params.table import *` works whether the
    alias was made before or after readParamsFromTable."""
    sys.modules["fakeyade_params_before"] = batch.params
    try:
        table = write(tmp_path, "t.table", "a\n3\n")
        batch.readParamsFromTable(f"{table}:2", a=0)
        sys.modules["fakeyade_params_after"] = batch.params
        for alias in ("fakeyade_params_before", "fakeyade_params_after"):
            assert importlib.import_module(f"{alias}.table").a == 3
    finally:
        for name in [m for m in sys.modules if m.startswith("fakeyade_params")]:
            del sys.modules[name]


def test_bad_parameters_name_the_file_and_line(tmp_path):
    path = write(tmp_path, "study.table", "radius colour\n0.1 'red'\n0.2 blue\n")
    with pytest.raises(NameError) as e:                       # no default for colour
        batch.readParamsFromTable(f"{path}:2", radius=0.05)
    assert f"{path}, line 2" in str(e.value) and "'colour'" in str(e.value)
    assert batch.readParamsFromTable(f"{path}:2", unknownOk=True, radius=0.05) == 2
    assert batch.params.table.colour == "red"
    with pytest.raises(RuntimeError) as e:                    # no such line
        batch.readParamsFromTable(f"{path}:9", radius=0.05, colour="")
    assert str(path) in str(e.value) and "no parameter line 9" in str(e.value) and "2, 3" in str(e.value)
    with pytest.raises(batch.TableError) as e:                # an unquoted string
        batch.readParamsFromTable(f"{path}:3", radius=0.05, colour="")
    assert f"{path}, line 3" in str(e.value) and "quoted" in str(e.value)
    with pytest.raises(ValueError, match="TABLE:LINE"):
        batch.readParamsFromTable(f"{path}", radius=0.05, colour="")


# -- saveDataTxt ---------------------------------------------------------------------------------

def test_save_data_txt_in_yades_format(tmp_path):
    plot.reset()
    plot.addData(a=1, b=2.5)
    plot.addData(a=2, b=3.0)
    plot.saveDataTxt(tmp_path / "d.txt", headers={"radius": 0.1, "n": 5})
    # Yade 2023.02a writes exactly this for the same data (ints kept as ints).
    assert (tmp_path / "d.txt").read_text() == "# radius=\t0.1\n# n=\t5\n# a\t\tb\n1\t2.5\n2\t3.0\n"
    plot.saveDataTxt(tmp_path / "d.txt.gz", vars=["b"])
    import gzip
    assert gzip.open(tmp_path / "d.txt.gz", "rt").read() == "# b\n2.5\n3.0\n"
    import numpy as np
    assert list(np.genfromtxt(tmp_path / "d.txt", names=True, skip_header=2)["b"]) == [2.5, 3.0]
    with pytest.raises(KeyError, match="'zz'"):
        plot.saveDataTxt(tmp_path / "x.txt", vars=["zz"])
    plot.reset()


# -- side by side with Yade's reader ---------------------------------------------------------------

YADE_PROBE = """\
import json, sys
from yade import utils, plot
import yade.params
tables = sys.argv[1:]
out = {"tables": {}, "reads": []}
for t in tables:
    out["tables"][t] = {str(k): v for k, v in utils.TableParamReader(t).paramDict().items()}
    for line in utils.TableParamReader(t).paramDict():
        defaults = dict(radius=1.0, n=0, name="none", steps=1, extra=7)
        count = utils.readParamsFromTable("%s:%d" % (t, line), unknownOk=True, **defaults)
        values = {k: getattr(yade.params.table, k) for k in yade.params.table.__all__}
        tags = {k: O.tags[k] for k in ("line", "description", "params", "defaultParams")}
        out["reads"].append([t, line, count, values, tags])
plot.addData(a=1.0, b=2.5); plot.addData(a=2.0, b=3.0)
plot.saveDataTxt("yade_data.txt", headers={"radius": 0.1, "n": 5})
print("RESULT " + json.dumps(out))
"""


@yade_missing
def test_reader_matches_yade(tmp_path):
    tables = [write(tmp_path, "bang.table", BANG_TABLE), write(tmp_path, "desc.table", DESCRIPTION_TABLE),
              write(tmp_path, "example.table", YADE_EXAMPLE_TABLE)]
    probe = write(tmp_path, "probe.py", YADE_PROBE)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "YADE_BATCH")}
    done = subprocess.run(["yade", "-n", "-j1", "-x", str(probe), *map(str, tables)], capture_output=True,
                          text=True, cwd=tmp_path, env=env, timeout=300)
    result = [l for l in done.stdout.splitlines() if l.startswith("RESULT ")]
    assert result, done.stdout[-2000:] + done.stderr[-2000:]
    theirs = json.loads(result[-1][len("RESULT "):])
    for t in tables:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", batch.TableWarning)
            assert {str(k): v for k, v in batch.readTable(t).lines.items()} == theirs["tables"][str(t)]
    assert len(theirs["reads"]) == 13
    for t, line, count, values, tags in theirs["reads"]:
        defaults = dict(radius=1.0, n=0, name="none", steps=1, extra=7)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", batch.TableWarning)
            assert batch.readParamsFromTable(f"{t}:{line}", unknownOk=True, **defaults) == count
        ours = {k: getattr(batch.params.table, k) for k in batch.params.table.__all__}
        assert ours == pytest.approx(values), (t, line)
        assert {k: batch.tags[k] for k in tags} == tags, (t, line)
    plot.reset()
    plot.addData(a=1.0, b=2.5)
    plot.addData(a=2.0, b=3.0)
    plot.saveDataTxt(tmp_path / "ours.txt", headers={"radius": 0.1, "n": 5})
    assert (tmp_path / "ours.txt").read_text() == (tmp_path / "yade_data.txt").read_text()
    plot.reset()


# -- talus batch -----------------------------------------------------------------------------------

FALL = """\
# One sphere falling freely for `steps` steps; the table gives its radius.
from talus.batch import readParamsFromTable
from talus.dem import O, FrictMat, ForceResetter, NewtonIntegrator, sphere
readParamsFromTable(radius=0.1, steps=100)
from talus.batch.params.table import *
if radius <= 0:
    raise ValueError(f"radius must be positive, got {radius}")
O.materials.append(FrictMat(density=1000))
O.bodies.append(sphere((0, 0, 1), radius))
O.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -10), damping=0)]
O.dt = 1e-3
O.run(steps)
s = O.bodies[0].state
print(f"RESULT radius={radius} mass={s.mass:.9g} z={s.pos[2]:.9g} iter={O.iter}")
"""


def results(log):
    line = next(l for l in log.read_text().splitlines() if l.startswith("RESULT "))
    return dict(kv.split("=") for kv in line.split()[1:])


def test_batch_runs_each_line(talus_cmd, tmp_path):
    write(tmp_path, "fall.py", FALL)
    write(tmp_path, "fall.table", """\
        description radius steps   # three sizes
        small       0.05   100
        medium      0.1    =
        large       0.2    =
        """)
    done = talus_cmd("batch", "-j", "2", "fall.table", "fall.py", cwd=tmp_path)
    out = done.stdout
    assert "talus batch: 3 jobs: 3 ok, 0 failed" in out and "wall time" in out
    for line, name, radius in ((2, "small", 0.05), (3, "medium", 0.1), (4, "large", 0.2)):
        log = tmp_path / f"fall.py.{name}.log"                     # yade-batch's $.@.log
        assert f"line {line}" in out and f"fall.py.{name}.log" in out and f"({name}) done" in out
        r = results(log)
        assert float(r["radius"]) == radius and r["iter"] == "100"
        assert float(r["mass"]) == pytest.approx(1000 * 4 / 3 * 3.141592653589793 * radius ** 3)
        assert float(r["z"]) == pytest.approx(1 - 0.5 * 10 * 0.1 ** 2, abs=1e-3)   # falls alike
        text = log.read_text()
        assert "JOB SUMMARY" in text and "status  : 0 (OK)" in text and f"fall.table:{line}" in text
    # --lines and --log as in yade-batch
    done = talus_cmd("batch", "--lines", "3-4", "--log", "runs/%.log", "fall.table", "fall.py", cwd=tmp_path)
    assert "2 jobs: 2 ok" in done.stdout
    assert sorted(p.name for p in (tmp_path / "runs").iterdir()) == ["3.log", "4.log"]


def test_failing_job_is_reported(talus_cmd, tmp_path):
    write(tmp_path, "fall.py", FALL)
    write(tmp_path, "fall.table", "radius\n0.1\n-1\n0.2\n")
    done = talus_cmd("batch", "fall.table", "fall.py", cwd=tmp_path, check=False)
    assert done.returncode == 1
    assert "3 jobs: 2 ok, 1 failed" in done.stdout
    assert "#1 (radius=-1) FAILED (exit status 1)" in done.stdout
    assert "line 3" in done.stdout and "FAILED (1)" in done.stdout
    log = (tmp_path / "fall.py.radius=-1.log").read_text()
    assert "ValueError: radius must be positive, got -1" in log and "status  : 1 (FAILED)" in log
    assert results(tmp_path / "fall.py.radius=0.2.log")["radius"] == "0.2"


def test_unknown_parameter_fails_its_job_with_file_and_line(talus_cmd, tmp_path):
    write(tmp_path, "fall.py", FALL)
    write(tmp_path, "fall.table", "radius colour\n0.1 'red'\n")
    done = talus_cmd("batch", "fall.table", "fall.py", cwd=tmp_path, check=False)
    assert done.returncode == 1 and "1 failed" in done.stdout
    log = (tmp_path / "fall.py.radius=0.1,colour=red.log").read_text()
    assert "NameError" in log and "fall.table, line 2" in log and "'colour'" in log


def test_runner_columns_timeout_and_dry_run(talus_cmd, tmp_path):
    write(tmp_path, "env.py", """\
        import os, time
        from talus.batch import readParamsFromTable, params
        readParamsFromTable(wait=0.0)
        print("ENV", os.environ["OMP_NUM_THREADS"], os.environ["MY_SETTING"], os.environ["YADE_BATCH"])
        time.sleep(params.table.wait)
        """)
    write(tmp_path, "env.table", """\
        wait  !THREADS  !MY_SETTING
        0     1         alpha
        30    2         beta
        """)
    done = talus_cmd("batch", "--timeout", "1.5", "env.table", "env.py", cwd=tmp_path, check=False)
    assert done.returncode == 1
    assert "2 jobs: 1 ok, 1 failed" in done.stdout and "TIMEOUT" in done.stdout
    logs = sorted(p.name for p in tmp_path.glob("*.log"))
    assert logs == ["env.py.wait=0,THREADS=1,MY_SETTING=alpha.log", "env.py.wait=30,THREADS=2,MY_SETTING=beta.log"]
    assert f"ENV 1 alpha {tmp_path / 'env.table'}:2" in (tmp_path / logs[0]).read_text()
    slow = (tmp_path / logs[1]).read_text()
    assert "ENV 2 beta" in slow and "timed out after 1.5 s" in slow
    dry = talus_cmd("batch", "--dry-run", "env.table", "env.py", cwd=tmp_path)
    assert "#1 (wait=30,THREADS=2,MY_SETTING=beta/2)" in dry.stdout and "talus run -j 2 env.py" in dry.stdout


def test_bad_batch_input(talus_cmd, tmp_path):
    write(tmp_path, "fall.py", FALL)
    write(tmp_path, "short.table", "radius steps\n0.1 10\n0.2\n")
    done = talus_cmd("batch", "short.table", "fall.py", cwd=tmp_path, check=False)
    assert done.returncode == 2 and "short.table, line 3: 1 values for the 2 columns" in done.stderr
    write(tmp_path, "ok.table", "radius\n0.1\n")
    done = talus_cmd("batch", "--lines", "7", "ok.table", "fall.py", cwd=tmp_path, check=False)
    assert done.returncode == 2
    assert "ok.table has no parameter line 7" in done.stderr and "no line of parameters to run" in done.stderr
    done = talus_cmd("batch", "ok.table", "nope.py", cwd=tmp_path, check=False)
    assert done.returncode == 2 and "no such script: nope.py" in done.stderr
    done = talus_cmd("batch", "ok.table", cwd=tmp_path, check=False)
    assert done.returncode == 2 and "no !SCRIPT column" in done.stderr
    done = talus_cmd("batch", "--jobs", "0", "ok.table", "fall.py", cwd=tmp_path, check=False)
    assert done.returncode == 2 and "--jobs must be at least 1" in done.stderr
    assert not list(tmp_path.glob("*.log"))
