"""The `talus` command: `talus run` behaves like `yade -x script.py`."""


def test_version_and_info(talus_cmd):
    import talus
    assert talus_cmd("--version").stdout.strip() == f"talus {talus.__version__}"
    info = talus_cmd("info").stdout
    assert "components:" in info and "dem" in info and "features:" in info


def test_run_passes_arguments_and_runs_as_main(talus_cmd, tmp_path):
    script = tmp_path / "case.py"
    script.write_text(
        "import sys\n"
        "import helper\n"              # the script's folder is importable, as with python3 script.py
        "if __name__ == '__main__':\n"
        "    print('args', sys.argv[1:], helper.VALUE)\n")
    (tmp_path / "helper.py").write_text("VALUE = 42\n")
    done = talus_cmd("run", script, "--quick", "x y")
    assert "args ['--quick', 'x y'] 42" in done.stdout


def test_run_sets_thread_count(talus_cmd, tmp_path):
    script = tmp_path / "threads.py"
    # Both the environment (for child processes) and the running OpenMP runtime, which read
    # OMP_NUM_THREADS when talus was imported, before -j was seen.
    script.write_text("import os\nfrom talus import _dem\n"
                      "print('threads', os.environ['OMP_NUM_THREADS'], _dem.threadCount())\n")
    import talus
    expected = "threads 3 3" if talus.build_info()["features"]["openmp"][0] else "threads 3 1"
    assert expected in talus_cmd("run", "-j", "3", script).stdout
    # Without -j the variable still says how many threads run, as yade -x sets it.
    count = talus_cmd("run", script).stdout.split()
    assert count[0] == "threads" and count[1] == count[2]


def test_run_propagates_exit_status_and_errors(talus_cmd, tmp_path):
    exits = tmp_path / "exits.py"
    exits.write_text("raise SystemExit(7)\n")
    assert talus_cmd("run", exits, check=False).returncode == 7

    fails = tmp_path / "fails.py"
    fails.write_text("def f():\n    raise ValueError('bad radius for body 3')\nf()\n")
    done = talus_cmd("run", fails, check=False)
    assert done.returncode == 1
    assert "ValueError: bad radius for body 3" in done.stderr
    assert "runpy" not in done.stderr          # the traceback is the script's, not the runner's


def test_run_missing_script_is_a_clear_error(talus_cmd, tmp_path):
    done = talus_cmd("run", tmp_path / "nope.py", check=False)
    assert done.returncode == 2
    assert "no such script" in done.stderr and "nope.py" in done.stderr


def test_run_warns_when_threads_would_wait_for_busy_cores(monkeypatch, capsys):
    from talus import cli
    monkeypatch.setattr(cli.os, "cpu_count", lambda: 2)
    monkeypatch.setattr(cli.os, "getloadavg", lambda: (3.0, 3.0, 3.0))
    cli._warn_if_oversubscribed(2)
    assert "2 OpenMP threads on 2 cores with a load average of 3.0" in capsys.readouterr().err
    monkeypatch.setattr(cli.os, "getloadavg", lambda: (0.1, 0.1, 0.1))
    cli._warn_if_oversubscribed(2)
    cli._warn_if_oversubscribed(1)
    assert capsys.readouterr().err == ""
