"""Random bad parameters for the main constructors (bad_input_generator.py: materials, bodies,
engines, FlowEngine, VansFluid, MultiscaleRVEs), a few hundred draws with a fixed seed: each ends
in a clean Python exception or a valid run with finite results, never a crash, a hang or NaN."""
import json
from pathlib import Path

from bad_input_generator import run_draws

SEED, DRAWS = 2024, 400


def test_random_bad_parameters_never_crash_hang_or_give_nan():
    results = run_draws(SEED, DRAWS)
    assert [r["index"] for r in results] == list(range(DRAWS))
    bad = [r for r in results if r["outcome"] not in ("error", "ok")]
    assert not bad, "\n".join(json.dumps(r)[:600] for r in bad)
    # The draws reach every target and mostly end in an error.
    assert len({r["target"] for r in results}) == 13
    assert sum(r["outcome"] == "error" for r in results) > DRAWS / 2


def test_a_crash_and_a_hang_are_pinned_to_their_draw(tmp_path, monkeypatch):
    """A copy of the generator whose draw 3 kills its process and draw 6 sleeps: both named, the
    other draws run."""
    import bad_input_generator
    source = Path(bad_input_generator.__file__).read_text().replace(
        "def run_one(seed: int, index: int) -> dict:\n",
        "def run_one(seed: int, index: int) -> dict:\n"
        "    if index == 3:\n        os.kill(os.getpid(), 11)\n"
        "    if index == 6:\n        __import__('time').sleep(100)\n", 1)
    (tmp_path / "probe_generator.py").write_text(source)
    monkeypatch.syspath_prepend(str(tmp_path))
    import probe_generator
    outcomes = [(r["index"], r["outcome"]) for r in probe_generator.run_draws(SEED, 9, hang_seconds=3)]
    assert [o for _, o in outcomes].count("crash") == 1 and (3, "crash") in outcomes
    assert [o for _, o in outcomes].count("hang") == 1 and (6, "hang") in outcomes
    assert [i for i, _ in outcomes] == list(range(9))
