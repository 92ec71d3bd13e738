"""The side-by-side benchmark runner: medians, ratio direction, missing peers, failing runs."""
import json
import sys

import pytest

from talus import bench

PY = sys.executable


def printer(*figures):
    """A command that prints the next figure of a cycle each time it runs (state in a file)."""
    return lambda state: [PY, "-c",
                          "import sys,os;p=sys.argv[1];i=int(open(p).read()) if os.path.exists(p) else 0;"
                          f"open(p,'w').write(str(i+1));print('rate', {list(figures)}[i % {len(figures)}])",
                          str(state)]


def test_rates_use_medians_and_ours_over_theirs(tmp_path):
    ours = bench.Side("talus", printer(290, 300, 900)(tmp_path / "a"), r"rate ([0-9.]+)")
    peer = bench.Side("yade", printer(100, 50, 101)(tmp_path / "b"), r"rate ([0-9.]+)")
    c = bench.compare(ours, peer, repeat=3, unit="it/s", higher_is_better=True, progress=None)
    assert (c.ours, c.theirs) == (300, 100)        # medians, not means: outliers do not count
    assert c.ratio == pytest.approx(3.0)
    assert c.ours_samples == [290, 300, 900]


def test_wall_times_give_theirs_over_ours():
    ours = bench.Side("talus", [PY, "-c", "pass"])
    peer = bench.Side("slow", [PY, "-c", "import time; time.sleep(0.4)"])
    c = bench.compare(ours, peer, repeat=1, progress=None)
    assert c.ratio > 1.5 and c.unit == "s"


def test_a_missing_peer_is_reported_not_installed():
    ours = bench.Side("talus", [PY, "-c", "pass"])
    peer = bench.Side("yade", ["no-such-peer-program-xyz", "-n"])
    with pytest.raises(bench.PeerNotInstalled, match="no-such-peer-program-xyz.*not installed.*installs nothing"):
        bench.compare(ours, peer, progress=None)


def test_a_failing_command_shows_its_output():
    ours = bench.Side("talus", [PY, "-c", "import sys; print('diverged at step 12'); sys.exit(4)"])
    peer = bench.Side("peer", [PY, "-c", "pass"])
    with pytest.raises(bench.CommandFailed, match="(?s)exited with 4.*diverged at step 12"):
        bench.compare(ours, peer, progress=None)


def test_a_missing_figure_is_an_error():
    ours = bench.Side("talus", [PY, "-c", "print('nothing here')"], r"rate ([0-9.]+)")
    peer = bench.Side("peer", [PY, "-c", "pass"])
    with pytest.raises(bench.CommandFailed, match="no match"):
        bench.compare(ours, peer, progress=None)


def test_cli_writes_a_benchmark_record(talus_cmd, tmp_path):
    done = talus_cmd("bench", "--name", "demo.bench.rates", "--repeat", "2",
                     "--ours", f"{PY} -c \"print('rate 500')\"",
                     "--peer", f"{PY} -c \"print('rate 100')\"", "--peer-name", "fake peer",
                     "--parse", r"rate ([0-9.]+)", "--higher-is-better", "--unit", "it/s",
                     "--target", "5", "--results", tmp_path)
    assert "ratio 5" in done.stdout
    record = json.loads((tmp_path / "demo.bench.rates.json").read_text())
    assert record["ratio"] == 5.0 and record["pass"] is True
    assert (record["ours"], record["theirs"], record["unit"], record["peer"]) == (500, 100, "it/s", "fake peer")


def test_cli_says_when_the_peer_is_missing(talus_cmd, tmp_path):
    done = talus_cmd("bench", "--name", "demo.bench.missing", "--ours", f"{PY} -c pass",
                     "--peer", "no-such-peer-program-xyz", "--results", tmp_path, check=False)
    assert done.returncode == 3
    assert "not installed" in done.stderr
    assert not list(tmp_path.glob("*.json"))


@pytest.mark.parametrize("allowed", ["1", "0"])
def test_realtime_sides_run_under_fifo_only_where_allowed(monkeypatch, allowed):
    import os
    import shutil
    monkeypatch.setenv("TALUS_BENCH_REALTIME", allowed)
    monkeypatch.setattr(bench, "_realtime", None)  # probe again under this setting
    policy = [PY, "-c", "import os; print('policy', os.sched_getscheduler(0))"]
    fifo = bench.Side("fifo", policy, r"policy ([0-9]+)", realtime=True)
    plain = bench.Side("plain", policy, r"policy ([0-9]+)")
    bench.run_rounds([fifo, plain], repeat=1, progress=None)
    if allowed == "0":
        assert bench.realtime_prefix() == []
    elif os.geteuid() == 0 and shutil.which("chrt"):
        assert bench.realtime_prefix() == ["chrt", "-f", "10"]
    expected = os.SCHED_FIFO if bench.realtime_prefix() else os.SCHED_OTHER
    assert (fifo.samples, plain.samples) == ([expected], [os.SCHED_OTHER])


def test_a_side_keeps_the_output_of_its_latest_run(tmp_path):
    side = bench.Side("talus", printer(7, 8)(tmp_path / "a"), r"rate ([0-9.]+)")
    bench.run_rounds([side], repeat=2, progress=None)
    assert side.samples == [7, 8] and side.last_output.strip() == "rate 8"


def test_the_scene_kinds_benchmark_runs_a_small_drum(talus_cmd, tmp_path):
    """cases/bench/dem_bench_kinds.py --quick on its smallest facet scene: Talus's figure and each
    installed peer's (Yade's process time, LIGGGHTS's from /proc) are positive CPU times."""
    import shutil
    from pathlib import Path
    case = Path(__file__).resolve().parents[2] / "cases" / "bench" / "dem_bench_kinds.py"
    talus_cmd("run", "-j", "1", case, "--quick", "--only", "drum", "--results", tmp_path, timeout=300)
    peers = [p for p in ("yade", "liggghts") if shutil.which(p)]
    if not peers:
        pytest.skip("neither yade nor liggghts is installed: the case records nothing")
    for peer in peers:
        record = json.loads((tmp_path / f"dem.bench.kind.drum-{peer}.json").read_text())
        assert record["ours"] > 0 and record["theirs"] > 0 and record["spheres"] == 1500
        assert record["ratio"] == pytest.approx(record["theirs"] / record["ours"])
        assert record["fused_steps"] == 501           # 1 + 500 steps, the drum above 1024 bodies
    # the chart alone, drawn from those records (kinds run one at a time): nothing run, a PNG written
    charted = tmp_path / "chart"
    talus_cmd("run", case, "--chart-from", tmp_path, "--results", charted, timeout=120)
    assert (charted / "dem.bench.kind.png").stat().st_size > 0 and not list(charted.glob("*.json"))
