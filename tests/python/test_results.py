"""Result records follow the reporting contract; bad records are refused with a clear error."""
import json

import pytest

from talus import results


def test_case_writes_a_complete_record(tmp_path):
    case = results.Case("demo.free-fall", quick=True, folder=tmp_path)
    rec = case.record("relative error of the position", 3e-10, "analytic", 1e-9)
    path = tmp_path / "demo.free-fall.json"
    on_disk = json.loads(path.read_text())
    assert on_disk == rec
    for field in results.REQUIRED_FIELDS:
        assert field in on_disk
    assert on_disk["pass"] is True and on_disk["quick"] is True
    assert on_disk["wall_s"] >= 0 and on_disk["git"]


def test_pass_follows_the_comparison(tmp_path):
    case = results.Case("demo.bounds", quick=False, folder=tmp_path)
    assert case.record("error", 0.02, "x", 0.01, suffix="error")["pass"] is False
    assert case.record("ratio", 6.0, "yade", 5.0, suffix="speed", comparison=">=")["pass"] is True
    assert case.record("ratio", 4.0, "yade", 5.0, suffix="slow", comparison=">=")["pass"] is False
    assert {p.name for p in tmp_path.iterdir()} == {
        "demo.bounds.error.json", "demo.bounds.speed.json", "demo.bounds.slow.json"}


@pytest.mark.parametrize("name", ["NoDots", "Upper.Case", "trailing.", "a..b", "spa ce.x"])
def test_bad_names_are_refused(name, tmp_path):
    with pytest.raises(ValueError, match="dotted"):
        results.Case(name, quick=True, folder=tmp_path)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), "abc", None])
def test_non_finite_values_are_refused(value, tmp_path):
    case = results.Case("demo.nan", quick=True, folder=tmp_path)
    with pytest.raises(ValueError, match="value of demo.nan"):
        case.record("error", value, "x", 1.0)
    assert not list(tmp_path.glob("*.json"))


def test_a_failed_write_keeps_the_previous_record(tmp_path, monkeypatch):
    case = results.Case("demo.atomic", quick=True, folder=tmp_path)
    case.record("error", 0.5, "x", 1.0)
    before = (tmp_path / "demo.atomic.json").read_text()

    def broken_dump(*_a, **_k):
        raise OSError("disk full")
    monkeypatch.setattr(results.json, "dump", broken_dump)
    with pytest.raises(OSError, match="disk full"):
        case.record("error", 0.7, "x", 1.0)
    assert (tmp_path / "demo.atomic.json").read_text() == before
    assert [p.name for p in tmp_path.iterdir()] == ["demo.atomic.json"]   # no temp file left


def test_reading_a_malformed_record_names_the_file(tmp_path):
    (tmp_path / "demo.broken.json").write_text("{not json")
    with pytest.raises(ValueError, match="demo.broken.json"):
        results.read_records(tmp_path)
    (tmp_path / "demo.broken.json").write_text('{"name": "demo.broken"}')
    with pytest.raises(ValueError, match="lacks fields"):
        results.read_records(tmp_path)


def test_case_arguments():
    args = results.case_arguments("doc").parse_args(["--quick", "--results", "out"])
    assert args.quick and str(args.results) == "out"
