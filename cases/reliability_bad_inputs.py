"""Reliability case: bad inputs end in a clear error naming the problem.

Run:      build/bin/talus run cases/reliability_bad_inputs.py [--quick] [--results DIR]
Set-up:   the bad-input suite's case table (tests/bad_inputs.py: materials, bodies, engines, run
          control, checkpoint files of talus.dem; FlowEngine, VansFluid, HydroForceEngine of
          talus.flow; MultiscaleRVEs and prepareRVE of talus.fem; FoamCoupling's arguments), each
          case run once; then the random bad parameters of tests/bad_input_generator.py (seed
          2024; quick: 400 draws, full: 2 000), in batches of subprocesses.
Checked:  reliability.bad-inputs: the fraction of the table's cases that end in their exception
          with the words naming the problem (1.0). Beside it: the draws that crashed, hung or
          gave non-finite results (must be 0) and the fraction of erroring draws whose message
          names the parameter.
Produces: the record, with the unclear cases and the bad draws listed.
"""
import sys
import tempfile
from collections import Counter
from pathlib import Path

from talus import results

TESTS = Path(__file__).resolve().parents[1] / "tests"
sys.path.insert(0, str(TESTS))

from bad_input_generator import run_draws  # noqa: E402
from bad_inputs import cases, outcome  # noqa: E402

COMPONENTS = ("dem", "flow", "fem", "coupling")


def main():
    args = results.case_arguments(__doc__).parse_args()
    case = results.Case("reliability.bad-inputs", quick=args.quick, folder=args.results)
    outcomes = {}
    with tempfile.TemporaryDirectory() as scratch:
        for component in COMPONENTS:
            for k, c in enumerate(cases(component)):
                folder = Path(scratch) / f"{component}-{k}"
                folder.mkdir()
                outcomes[f"{component}: {c.name}"] = outcome(c, folder)
    unclear = {name: text for name, text in outcomes.items() if text != "clear"}
    clear = 1 - len(unclear) / len(outcomes)
    for name, text in unclear.items():
        print(f"NOT CLEAR  {name}: {text[:200]}")
    per_component = Counter(name.split(":")[0] for name in outcomes)
    draws = run_draws(2024, 400 if args.quick else 2000)
    kinds = Counter(d["outcome"] for d in draws)
    errors = [d for d in draws if d["outcome"] == "error"]
    named = sum(d["named"] for d in errors) / max(1, len(errors))
    bad_draws = [d for d in draws if d["outcome"] not in ("error", "ok")]
    print(f"{len(outcomes)} cases ({dict(per_component)}): {clear:.3f} clear; {len(draws)} random draws: "
          f"{dict(kinds)}, {named:.2f} of the errors name the parameter")
    case.record("fraction of the bad-input suite's cases ending in a clear error", clear,
                "every case: its exception, with the words naming the parameter, body or file", 1.0,
                comparison=">=", cases=len(outcomes), cases_per_component=dict(per_component),
                unclear=unclear, draws=len(draws), draw_outcomes=dict(kinds), bad_draws=bad_draws[:20],
                draw_errors_naming_the_parameter=round(named, 3))
    if bad_draws:
        raise SystemExit(f"{len(bad_draws)} random draws crashed, hung or gave non-finite results")


if __name__ == "__main__":
    main()
