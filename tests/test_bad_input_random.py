"""Random bad parameters for the main constructors (bad_input_generator.py: materials, bodies,
engines, FlowEngine, VansFluid, MultiscaleRVEs), a few hundred draws with a fixed seed: each ends
in a clean Python exception or a valid run with finite results, never a crash, a hang or NaN."""
import json

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
