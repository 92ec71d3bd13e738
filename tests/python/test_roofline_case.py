"""cases/bench/dem_roofline.py: its counting model, and its quick mode on a tiny bed writes the records
and the chart, with fractions of the roofs in (0, 1]."""
import importlib.util
import json
from pathlib import Path

import pytest

CASE = Path(__file__).resolve().parents[2] / "cases" / "bench" / "dem_roofline.py"


def load_case():
    spec = importlib.util.spec_from_file_location("dem_roofline", CASE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_model_counts_a_real_contact_as_its_whole_record_read_and_written():
    case = load_case()
    alone = case.stage_model(bodies=2, candidates=1, real=0)
    touching = case.stage_model(bodies=2, candidates=1, real=1)
    assert touching["contacts"][0] - alone["contacts"][0] == 2 * 256 - 64   # the rest of the record, both ways
    assert touching["contacts"][1] - alone["contacts"][1] == 153 - 13
    assert alone["contacts"] == (2 * 80 + 64, 13)
    assert touching["gather"] == alone["gather"] == (2 * 128 + 80, 2 * 6 + 42)
    assert alone["reset"] == (2 * 96, 0)


def test_quick_mode_on_a_tiny_bed_records_the_bound_and_fractions(talus_cmd, tmp_path):
    talus_cmd("run", "-j", "1", CASE, "--quick", "--spheres", "1500", "--results", tmp_path, timeout=600)
    for threads in (1, 2):
        record = json.loads((tmp_path / f"dem.roofline.step-{threads}t.json").read_text())
        assert record["threads"] == threads and abs(record["spheres"] - 1500) < 150   # the lattice nearest 1500
        assert record["bound"] in ("memory", "compute")
        assert 0 < record["value"] <= 1, record["stages"]
        step = record["stages"]["step"]
        assert step["fraction"] == record["value"]
        assert step["bytes_per_particle_step"] > 0 and step["flops_per_particle_step"] > 0
        machine = record["machine"]
        assert machine["triad_bed_gbs"] > 0 and machine["peak_gflops"] > 0
        # the bound named is the roof that is lower at the step's intensity
        memory_roof = step["intensity"] * machine["triad_bed_gbs"]
        assert (record["bound"] == "memory") == (memory_roof < machine["peak_gflops"])
        # the reset is a stage of its own unless the step makes it in the gather's pass
        for name in {"contacts", "gather", "integration"} | ({"reset"} & set(record["stages"])):
            assert record["stages"][name]["ns_per_particle_step"] > 0
    assert (tmp_path / "dem.roofline.png").stat().st_size > 0


@pytest.fixture(autouse=True)
def _quiet_load(monkeypatch):
    monkeypatch.setenv("OMP_PROC_BIND", "false")
