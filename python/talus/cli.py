"""The ``talus`` command.

    talus run SCRIPT [ARGS...]    run a script (as ``yade -x SCRIPT``, with the same namespace)
    talus info                    the toolchain check: version, components and features of this build
    talus report                  write docs/validation.md from a results folder
    talus bench                   time a command of ours against a peer's, side by side
    talus batch TABLE SCRIPT      run a script once per line of a parameter table (as ``yade-batch``)
    talus case KIND --out DIR     write a ready-to-run case: cfd (OpenFOAM, CFD-DEM), permeability, femxdem
"""

from __future__ import annotations

import argparse
import os
import re
import runpy
import sys
import traceback
from pathlib import Path

import talus


def _warn_if_oversubscribed(threads: int) -> None:
    """OpenMP threads spin at every barrier waiting for each other: when other processes keep the
    cores busy, a descheduled thread stalls the rest and 2 threads can run many times slower than
    1 (docs/dem.md, "Measurements behind the code"). Say so at the start instead of leaving the
    user with a mysteriously slow run."""
    cores = os.cpu_count() or 1
    busy = os.getloadavg()[0]
    if threads > 1 and busy + threads > cores + 0.5:
        print(f"talus run: warning: {threads} OpenMP threads on {cores} cores with a load average of {busy:.1f}: "
              f"threads waiting for busy cores can make the run many times slower; use -j "
              f"{max(1, min(threads, int(cores - busy)))} or fewer", file=sys.stderr)


def _note_missing_yade_name(exc: BaseException) -> None:
    """A NameError or ImportError on one of Yade's own names says that Talus lacks it and whether
    it is out of scope, instead of looking like a typo in the script."""
    from yade import _scope
    note = None
    if isinstance(exc, NameError) and exc.name:
        note = _scope.missing_name_note(exc.name)
    elif isinstance(exc, ImportError) and (exc.name or "").startswith("yade"):
        missing = re.match(r"cannot import name '(\w+)'", str(exc))
        if missing:
            note = _scope.missing_name_note(missing[1], exc.name)
        elif exc.name != "yade":        # import yade.mpy
            note = _scope.missing_name_note(exc.name.rpartition(".")[2], "yade")
    if note:
        exc.add_note(note)


def _run(args: argparse.Namespace) -> int:
    script = Path(args.script)
    if not script.is_file():
        print(f"talus run: no such script: {script}", file=sys.stderr)
        return 2
    if args.threads is not None:
        if args.threads < 1:
            print(f"talus run: -j must be at least 1, got {args.threads}", file=sys.stderr)
            return 2
        talus._dem.setThreadCount(args.threads)             # this one's runtime already started
    # As under yade -x, scripts (Yade's checkPerf.py) and child processes read the thread count here.
    os.environ["OMP_NUM_THREADS"] = str(talus._dem.threadCount())
    _warn_if_oversubscribed(talus._dem.threadCount())
    if args.trust_checkpoints:
        from talus.dem.files import trust
        os.environ[trust.ENVIRONMENT] = "1"                  # child processes (batch jobs) too
    sys.argv = [str(script), *args.script_args]
    sys.path.insert(0, str(script.resolve().parent))
    import yade   # the namespace `yade -x` gives a script: Yade's classes, utils, pack, math
    from talus.dem import distributed
    if distributed.RANKS > 1:       # under mpirun: the scene is split over the processes
        distributed.start()
    yade.yade_run_defaults()
    try:
        options = yade.launcher_options(str(script), list(args.script_args), args.threads)
        runpy.run_path(str(script), init_globals={**yade.script_namespace(), "opts": options}, run_name="__main__")
        if distributed.ACTIVE:      # every process is here (a read by id made by some only is named)
            from talus.dem.split import by_id
            if by_id.agree_at_end:
                by_id.agree(by_id.END)
        if yade.O.running:
            print("talus run: the script ended with O.run() still open-ended (no step count, not waited "
                  "for): it stops here, as under yade -x; call O.wait() in the script to run it until "
                  "O.pause(), or give O.run a step count", file=sys.stderr)
        if yade.O.overlapSteps:
            print(f"talus run: {yade.O.overlapSteps} steps had a contact overlapping beyond O.maxOverlapRatio "
                  f"({yade.O.maxOverlapRatio:g} of the smaller radius); the first: {yade.O._cpp.firstOverlap}",
                  file=sys.stderr)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except KeyboardInterrupt:
        print("talus run: interrupted", file=sys.stderr)
        return 130
    except Exception:
        # The script's own traceback, without the runner's frames.
        exc_type, exc, tb = sys.exc_info()
        while tb is not None and tb.tb_frame.f_code.co_filename != str(script):
            tb = tb.tb_next
        _note_missing_yade_name(exc)
        if distributed.ACTIVE:      # reported once, and no process left waiting for another
            return distributed.stop_on_error(exc, lambda: traceback.print_exception(exc_type, exc, tb))
        traceback.print_exception(exc_type, exc, tb)
        return 1
    return 0


def _info(_args: argparse.Namespace) -> int:
    """The toolchain check: the compiled core and the Python layer are the same version and were
    configured together; the build's components and features with the reason for any that is off."""
    info = talus.build_info()
    print(f"Talus {talus.__version__} (compiled core {talus._dem.version()})  ({Path(talus.__file__).parent})")
    for kind in ("components", "features"):
        print(f"{kind}:")
        for name, (on, note) in info[kind].items():
            print(f"  {name:<14}{'ON ' if on else 'OFF'}  {note}")
    cxx = {(kind + "s", name): on for kind, name, on, _note in talus._dem.build_config()}
    py = {(kind, name): on for kind, table in info.items() for name, (on, _n) in table.items()}
    if talus._dem.version() != talus.__version__ or cxx != py:
        print(f"talus info: the compiled core and the Python package disagree: version {talus._dem.version()} "
              f"vs {talus.__version__}, components {cxx} vs {py}; rebuild", file=sys.stderr)
        return 1
    print("toolchain OK")
    return 0


def _report(args: argparse.Namespace) -> int:
    from talus import report
    if not args.results.is_dir():
        print(f"talus report: results folder {args.results} does not exist", file=sys.stderr)
        return 2
    report.render(args.results, args.output)
    print(f"talus report: wrote {args.output}")
    return 0


def _bench(args: argparse.Namespace) -> int:
    from talus import bench, results
    ours = bench.Side("talus", bench.split_command(args.ours), args.parse_ours or args.parse)
    theirs = bench.Side(args.peer_name, bench.split_command(args.peer), args.parse_peer or args.parse)
    case = results.Case(args.name, quick=args.quick, folder=args.results)
    try:
        c = bench.compare(ours, theirs, repeat=args.repeat, unit=args.unit,
                          higher_is_better=args.higher_is_better, timeout=args.timeout)
    except (bench.PeerNotInstalled, bench.CommandFailed) as e:
        print(f"talus bench: {e}", file=sys.stderr)
        return 3
    record = case.record(f"speed ratio against {args.peer_name} (median of {args.repeat} runs)",
                         c.ratio, f"{args.peer_name}, same machine, same invocation",
                         args.target, comparison=">=", peer=args.peer_name, ours=c.ours,
                         theirs=c.theirs, unit=c.unit, ratio=c.ratio,
                         ours_samples=c.ours_samples, theirs_samples=c.theirs_samples)
    print(f"talus bench: {args.name}: ours {c.ours:.6g} {c.unit}, {args.peer_name} "
          f"{c.theirs:.6g} {c.unit}, ratio {c.ratio:.3g} (target >= {args.target:g}) -> "
          f"{'pass' if record['pass'] else 'FAIL'}")
    return 0


def _batch(args: argparse.Namespace) -> int:
    from talus import batch
    return batch.main(args)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="talus", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version=f"talus {talus.__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    run = sub.add_parser("run", help="run a case script")
    run.add_argument("-j", "--threads", type=int, default=None, help="OpenMP threads")
    run.add_argument("--trust-checkpoints", action="store_true",
                     help="let the checkpoints the script loads run their Python commands (PyRunner commands, "
                          "hooks): only for checkpoints you trust, a checkpoint is code")
    run.add_argument("script", help="Python script to run")
    run.add_argument("script_args", nargs=argparse.REMAINDER, help="arguments passed to the script")
    run.set_defaults(func=_run)

    sub.add_parser("info", help="version, components and features").set_defaults(func=_info)

    rep = sub.add_parser("report", help="write the validation page from result records")
    rep.add_argument("--results", type=Path, default=Path("results"))
    rep.add_argument("--output", type=Path, default=Path("docs/validation.md"))
    rep.set_defaults(func=_report)

    b = sub.add_parser("bench", help="side-by-side benchmark against a peer program")
    b.add_argument("--name", required=True, help="record name, e.g. dem.bench.quickperf")
    b.add_argument("--ours", required=True, help="our command (quoted)")
    b.add_argument("--peer", required=True, help="the peer's command (quoted)")
    b.add_argument("--peer-name", default="peer", help="e.g. 'yade 2023.02a, 1 thread'")
    b.add_argument("--repeat", type=int, default=3)
    b.add_argument("--unit", default="s")
    b.add_argument("--parse", default=None, help="regex with one group: the figure both print")
    b.add_argument("--parse-ours", default=None, help="regex for our output only")
    b.add_argument("--parse-peer", default=None, help="regex for the peer's output only")
    b.add_argument("--higher-is-better", action="store_true", help="the figure is a rate")
    b.add_argument("--target", type=float, default=1.0, help="ratio the benchmark must reach")
    b.add_argument("--timeout", type=float, default=3600.0, help="seconds per run")
    b.add_argument("--quick", action="store_true")
    b.add_argument("--results", type=Path, default=None)
    b.set_defaults(func=_bench)

    from talus import batch
    bt = sub.add_parser("batch", help="run a script once per line of a parameter table (yade-batch)",
                        description=batch.__doc__.split("\n\n")[0] + " See docs/dem.md, 'Parameter studies'.")
    batch.add_arguments(bt)
    bt.set_defaults(func=_batch)

    from talus import case_command
    cs = sub.add_parser("case", help="write a ready-to-run case (cfd, permeability, femxdem)",
                        description=case_command.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    case_command.add_arguments(cs)
    return p


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    return args.func(args)
