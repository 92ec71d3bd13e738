"""Yade's own example scripts, run unchanged under Talus and under Yade.

Run:      build/bin/talus run cases/yade_examples.py [--quick] [--results DIR] [--only PATTERN]
Set-up:   the population is every script of these folders of Yade 2023.02a's installed examples
          (/usr/share/doc/yade/examples): the top-level scripts, simple-scene, clumps,
          PeriodicBoundaries, triax-tutorial, packs, test, FluidCouplingPFV, FluidCouplingVANS1D,
          FEMxDEM and openfoam. A script is out of scope only when it needs physics Talus does not
          have or input from the network; yade._scope.RULES gives the reason for each (the first
          matching rule of yade._scope.RULES), and modules that other scripts import are not scripts.
          Each in-scope script is copied with its example folder into a fresh temporary folder and
          run in its own folder by `talus run -j 1 SCRIPT` and by `yade -x SCRIPT` (on a virtual display; both one thread), with a wall-time limit. Scripts
          are patched only where they need the GUI or never stop; PATCHES lists every patch and
          both programs get the same patched file.
Checked:  yade-examples.completion: the fraction of in-scope scripts that finish under Talus
          (exit status 0, no traceback) (>= 0.9); its fields list every script with its status
          under both programs and the first error line, and the out-of-scope scripts with reasons.
          --quick runs the fixed subset QUICK (a few seconds each) under Talus only.
Produces: the record, results/yade-examples.details.json (the per-script table) and
          yade-examples.png (status by folder).
"""
from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import talus
from talus import results
from yade._scope import out_of_scope   # the rules shared with the error for a Yade name Talus lacks

EXAMPLES = Path("/usr/share/doc/yade/examples")
FOLDERS = [".", "simple-scene", "clumps", "PeriodicBoundaries", "triax-tutorial", "packs", "test",
           "FluidCouplingPFV", "FluidCouplingVANS1D", "FEMxDEM", "openfoam"]

# Files that are modules or inputs of other scripts, not scripts a user runs (path: why).
NOT_SCRIPTS = {
    "FEMxDEM/biaxialSmooth.py": "run-escript driver (runs under run-escript, see the FEM x DEM case)",
    "FEMxDEM/triaxialRough.py": "run-escript driver",
    "FEMxDEM/footing.py": "run-escript driver",
    "FEMxDEM/retainingSmooth.py": "run-escript driver",
    "FEMxDEM/undrain.py": "run-escript driver",
    "openfoam/example_icoFoamYade/scriptMPI.py": "run by mpiexec with OpenFOAM (the OpenFOAM case)",
    "openfoam/example_pimpleFoamYade/scriptMPI.py": "run by mpiexec with OpenFOAM",
    "openfoam/example_icoFoamYade/scriptYade.py": "run by mpiexec with OpenFOAM",
    "openfoam/example_pimpleFoamYade/scriptYade.py": "run by mpiexec with OpenFOAM",
    "test/batch/sim.py": "a yade-batch job: `talus batch params.table sim.py` runs it, as yade-batch does",
}
# Post-processing scripts that read what a long simulation script wrote (path: what they need).
NOT_STANDALONE = {
    "FluidCouplingVANS1D/twoWayCoupling/biDisperse/postProcess.py":
        "post-processing: reads data.hdf5 written by biDisperseSedimentTransportExample_1DRANSCoupling.py",
    "FluidCouplingVANS1D/validations/DEMCoupling/Maurinetal2015/postProcessValidMaurin2015.py":
        "post-processing: reads the output of three validMaurin2015.py runs",
}
# Scripts Yade 2023.02a itself cannot run here, whatever the DEM (path: what fails under yade -x).
BROKEN_IN_YADE = {
    "test/multi/multi.py": "Python 2 (`file(...)`): NameError under Yade 2023.02a's Python 3",
    "test/qt4-attributes.py": "a Qt4 GUI demonstration: needs PyQt4, which Python 3 and Yade 2023.02a lack",
    "test/qt4-pyqglviewer.py": "a Qt4 GUI demonstration: needs PyQGLViewer, which Yade 2023.02a lacks",
}
# Folders of the examples that are not for this Yade (folder: why).
OTHER_PROGRAM_FOLDERS = {
    "FluidCouplingVANS1D/twoWayCoupling/shapeVariation/":
        "needs a modified Yade (its README: the hydro_force_engine branch of a fork), driven by its own batch scripts",
}
NOT_SCRIPT_NAMES = re.compile(r"(^|/)(params|defaultParams|measures|simulationDefinition|frameworkCreationUtils)\.py$")

# Patches applied identically for both programs: (path, old text, new text, why).
PATCHES: list[tuple[str, str, str, str]] = []

QUICK = ["billiard.py", "ViscElMatchMaker.py", "simple-scene/simple-scene.py",
         "simple-scene/simple-scene-default-engines.py", "PeriodicBoundaries/periodic-simple.py",
         "clumps/clump-viscoelastic.py", "clumps/addToClump-example.py", "test/facet-sphere.py",
         "test/kinematic.py", "test/pack-predicates.py", "test/triax-basic.py",
         "FluidCouplingVANS1D/oneWayCoupling/sedimentTransportExample.py",
         "FluidCouplingPFV/TwoPhaseFlowInjection.py"]


def population() -> list[str]:
    scripts = []
    for folder in FOLDERS:
        base = EXAMPLES / folder
        found = base.glob("*.py") if folder == "." else base.rglob("*.py")
        scripts += sorted(str(p.relative_to(EXAMPLES)) for p in found)
    return scripts


def scope(script: str) -> str | None:
    """None when the script is in scope, else the reason it is not."""
    for table in (NOT_SCRIPTS, NOT_STANDALONE, BROKEN_IN_YADE):
        if script in table:
            return table[script]
    for folder, why in OTHER_PROGRAM_FOLDERS.items():
        if script.startswith(folder):
            return why
    if NOT_SCRIPT_NAMES.search(script):
        return "module imported by other scripts"
    return out_of_scope((EXAMPLES / script).read_text(errors="replace"))


def prepare(script: str, work: Path) -> Path:
    """A copy of the script's example folder in ``work``, with the patches applied; returns the
    script. The whole first-level folder is copied, as scripts read their siblings
    (``../common/frameworkCreationUtils.py``); a top-level script gets the top-level files."""
    parts = Path(script).parts
    if len(parts) == 1:
        for f in EXAMPLES.iterdir():
            if f.is_file():
                shutil.copy2(f, work / f.name)
    else:
        shutil.copytree(EXAMPLES / parts[0], work / parts[0], symlinks=True)
    path = work / script
    text = path.read_text(errors="replace")
    for patched, old, new, _why in PATCHES:
        if patched == script:
            if old not in text:
                raise RuntimeError(f"yade_examples: patch for {script} no longer applies: {old!r}")
            text = text.replace(old, new)
    path.write_text(text)
    return path


# A usercustomize module on the path of both programs: at Python's exit it writes the scene's end
# state (iteration, time, body positions) to $YADE_EXAMPLES_STATE, for the agreement between the
# two, and prints EXIT_MARKER, so that an abort in Yade's C++ teardown after a finished script is
# told apart from a crash in the run.
EXIT_MARKER = "<<yade_examples: Python exited normally>>"
EXIT_HOOK = f"""import atexit, json, os, sys

def _end_state():
    try:
        O = sys.modules["builtins"].O
        bodies = [[b.id, *map(float, b.state.pos), type(b.shape).__name__] for b in O.bodies if b is not None]
        with open(os.environ["YADE_EXAMPLES_STATE"], "w") as out:
            json.dump({{"iter": O.iter, "time": O.time, "bodies": bodies}}, out)
    except Exception as e:
        print("yade_examples: no end state:", repr(e), file=sys.stderr)
    print({EXIT_MARKER!r}, file=sys.stderr, flush=True)

atexit.register(_end_state)
"""


def first_error(output: str) -> str:
    """The line naming the error: the last line of the last traceback, else the last line."""
    lines = [line for line in output.strip().splitlines() if line.strip()]
    if "Traceback" in output:
        tail = output[output.rindex("Traceback"):].strip().splitlines()
        for line in reversed(tail):
            if re.match(r"^[A-Za-z_.]*(Error|Exception|Interrupt|Exit)\b", line):
                return line.strip()[:300]
        return tail[-1].strip()[:300]
    return lines[-1][:300] if lines else ""


def run_one(command: list[str], script: Path, timeout: float, env: dict) -> dict:
    """Runs one prepared script; its row: status, wall time, first error, and the end state the
    exit hook wrote ("state", popped by the caller)."""
    state_file = script.parent / ".end_state.json"
    env = dict(env, YADE_EXAMPLES_STATE=str(state_file))
    t0 = time.perf_counter()
    try:
        # Enter pressed for every input() a script asks (clumps/releaseFromClump-example.py).
        p = subprocess.run([*command, script.name], cwd=script.parent, capture_output=True, text=True,
                           timeout=timeout, env=env, input="\n" * 100)
    except subprocess.TimeoutExpired as e:
        out = (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
        return {"status": "timeout", "wall_s": timeout, "error": f"still running after {timeout:g} s",
                "tail": out[-400:]}
    output = p.stdout + p.stderr
    traceback = "Traceback (most recent call last)" in output
    # Yade 2023.02a often aborts while tearing down after the script and Python have finished (a
    # boost bad_weak_ptr, a bus error when a simulation thread still runs as -x exits): that counts
    # as finished when Python's own exit ran (EXIT_MARKER).
    exit_abort = not traceback and p.returncode != 0 and EXIT_MARKER in output
    ok = (p.returncode == 0 or exit_abort) and not traceback
    row = {"status": "ok" if ok else "error", "wall_s": round(time.perf_counter() - t0, 2),
           "error": "" if ok else first_error(output), "returncode": p.returncode}
    if exit_abort:
        row["note"] = f"aborted after the script and Python finished (exit status {p.returncode})"
    if ok and state_file.is_file():
        row["state"] = json.loads(state_file.read_text())
    return row


# Yade's rows and end states of the last run with Yade, so that Talus-only runs (--programs talus)
# are still set against Yade's: running all of Yade's examples is slow (docs/yade-scripts.md).
YADE_CACHE = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "talus" / "yade_examples.json"

# A script is compared number for number only when nothing in it is random: both programs then
# start from the same bodies and run the same steps.
RANDOM = re.compile(r"random|makeCloud|Factory|psd|\bshuffle|TriaxialTest")   # random* covers the dense packs
AGREE = 1e-6   # end positions of the spheres agree within this fraction of the scene's size


def compare_end_states(talus_state: dict, yade_state: dict) -> dict:
    """How far Talus's end state is from Yade's: same iteration, same bodies, position difference."""
    if talus_state["iter"] != yade_state["iter"]:
        return {"compared": False, "why": f"iterations differ: {talus_state['iter']} and {yade_state['iter']}"}
    # The spheres: walls, boxes and facets are placed otherwise (aabbWalls are planes in Talus).
    mine = {b[0]: b[1:4] for b in talus_state["bodies"] if b[4:] in ([], ["Sphere"])}
    theirs = {b[0]: b[1:4] for b in yade_state["bodies"] if b[4:] in ([], ["Sphere"])}
    if mine.keys() != theirs.keys():
        return {"compared": False, "why": f"bodies differ: {len(mine)} and {len(theirs)}"}
    if not mine:
        return {"compared": False, "why": "no bodies"}
    ids = sorted(mine)
    a, b = np.array([mine[i] for i in ids]), np.array([theirs[i] for i in ids])
    size = float(np.linalg.norm(b.max(axis=0) - b.min(axis=0))) or 1.0
    difference = float(np.abs(a - b).max()) / size
    return {"compared": True, "iter": talus_state["iter"], "bodies": len(ids),
            "position_difference": difference, "agree": difference <= AGREE}


@contextlib.contextmanager
def virtual_display():
    """A display for Yade, whose examples import its Qt GUI (which refuses to start without one):
    the user's, else one Xvfb server for the whole run (one per script races for server numbers)."""
    if os.environ.get("DISPLAY"):
        yield os.environ["DISPLAY"]
        return
    if not shutil.which("Xvfb"):
        raise SystemExit("yade_examples: no DISPLAY and no Xvfb (./setup.sh installs xvfb)")
    number = next(n for n in range(90, 200) if not Path(f"/tmp/.X{n}-lock").exists())
    server = subprocess.Popen(["Xvfb", f":{number}", "-screen", "0", "1280x1024x24", "-nolisten", "tcp"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(100):
            if Path(f"/tmp/.X11-unix/X{number}").exists():
                break
            time.sleep(0.1)
        yield f":{number}"
    finally:
        server.terminate()
        server.wait()


def run_all(scripts, programs, runners, timeout, out_of_scope, yade_cache) -> dict:
    """Runs each in-scope script under each program; the table by script (out_of_scope is filled).
    Yade's rows and end states come from ``yade_cache`` when Yade is not run, and go to it when it
    is."""
    table = {}
    for script in scripts:
        reason = scope(script)
        if reason:
            out_of_scope[script] = reason
            continue
        row = {}
        for name, command, env in runners:
            if name not in programs:
                continue
            with tempfile.TemporaryDirectory(prefix="yade_example_") as work:
                row[name] = run_one(command, prepare(script, Path(work)), timeout, env)
        if "yade" not in row and script in yade_cache:
            row["yade"] = dict(yade_cache[script], cached=True)
        states = {name: r.pop("state", None) for name, r in row.items()}
        if "yade" in programs:     # kept after every script: an interrupted run keeps what it did
            yade_cache[script] = dict(row["yade"], state=states["yade"])
            YADE_CACHE.parent.mkdir(parents=True, exist_ok=True)
            YADE_CACHE.write_text(json.dumps(yade_cache))
        if states.get("talus") and states.get("yade") and not RANDOM.search((EXAMPLES / script).read_text()):
            row["agreement"] = compare_end_states(states["talus"], states["yade"])
        table[script] = row
        runs = {name: r for name, r in row.items() if name in ("talus", "yade")}
        print(f"{script:70s} " + " ".join(f"{name} {r['status']:7s}" for name, r in runs.items())
              + "".join(f"  {name}: {r['error']}" for name, r in runs.items() if r["status"] != "ok")
              + (f"  end positions differ by {row['agreement']['position_difference']:.1e}"
                 if row.get("agreement", {}).get("compared") else ""), flush=True)
    return table


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--only", default=None, help="regular expression: run only matching scripts")
    parser.add_argument("--timeout", type=float, default=None, help="seconds per script and program")
    parser.add_argument("--programs", default=None,
                        help="comma-separated: talus, yade (default: both; talus only with --quick)")
    args = parser.parse_args()
    if not EXAMPLES.is_dir():
        raise SystemExit(f"yade_examples: {EXAMPLES} not found (./setup.sh installs Debian's yade package)")
    case = results.Case("yade-examples.completion", quick=args.quick, folder=args.results)
    # This very Talus: its package first on the path of `python -m talus run`. One thread, as
    # `yade -x` runs: the same work in both, and OpenMP threads on cores that other processes keep
    # busy wait for each other at every barrier (small DEM steps then take many times longer).
    talus_cmd = [sys.executable, "-m", "talus", "run", "-j", "1"]
    env_talus = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(Path(talus.__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")]))
    yade_cmd = ["yade", "-x"]
    timeout = args.timeout or (60.0 if args.quick else 120.0)
    programs = (args.programs or ("talus" if args.quick else "talus,yade")).split(",")
    if "yade" in programs and not shutil.which("yade"):
        raise SystemExit("yade_examples: yade is not installed (./setup.sh installs the Debian package)")

    out_of_scope: dict[str, str] = {}
    scripts = QUICK if args.quick else population()
    if args.only:
        scripts = [s for s in scripts if re.search(args.only, s)]
    yade_cache = json.loads(YADE_CACHE.read_text()) if YADE_CACHE.is_file() else {}
    with contextlib.ExitStack() as stack:
        hook = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="yade_exit_hook_")))
        (hook / "usercustomize.py").write_text(EXIT_HOOK)
        env_talus["PYTHONPATH"] += os.pathsep + str(hook)
        env_yade = dict(os.environ, PYTHONPATH=str(hook))     # Yade's own modules, not Talus's
        if "yade" in programs:
            env_yade["DISPLAY"] = stack.enter_context(virtual_display())
        table = run_all(scripts, programs, [("talus", talus_cmd, env_talus), ("yade", yade_cmd, env_yade)],
                        timeout, out_of_scope, yade_cache)


    case.folder.mkdir(parents=True, exist_ok=True)
    if "talus" not in programs:
        print(f"yade-examples: Yade's rows are in {YADE_CACHE}, for runs with --programs talus")
        return
    finished = sum(r["talus"]["status"] == "ok" for r in table.values())
    completion = finished / max(1, len(table))
    errors: dict[str, int] = {}
    for r in table.values():
        if r["talus"]["status"] != "ok":
            errors[r["talus"]["error"]] = errors.get(r["talus"]["error"], 0) + 1
    (case.folder / "yade-examples.details.json").write_text(json.dumps(
        {"in_scope": table, "out_of_scope": out_of_scope, "patches": PATCHES}, indent=1))
    case.record("fraction of in-scope scripts that finish under talus run (unchanged but for PATCHES)",
                completion, "Yade 2023.02a's examples (the same scripts under yade -x)", 0.9,
                comparison=">=", scripts=len(table), finished=finished,
                yade_finished=sum(r.get("yade", {}).get("status") == "ok" for r in table.values()),
                out_of_scope=len(out_of_scope),
                errors=dict(sorted(errors.items(), key=lambda kv: -kv[1])))
    compared = {script: r["agreement"] for script, r in table.items() if r.get("agreement", {}).get("compared")}
    if compared:
        agreeing = sum(a["agree"] for a in compared.values())
        results.Case("yade-examples.agreement", quick=args.quick, folder=args.results).record(
            f"fraction of deterministic scripts finished by both whose end positions agree to {AGREE:g} of the "
            "scene size", agreeing / len(compared), "Yade 2023.02a on the same script", 0.9, comparison=">=",
            compared=len(compared), agreeing=agreeing,
            differences={script: a["position_difference"] for script, a in compared.items()})
        print(f"yade-examples: {agreeing} of {len(compared)} deterministic scripts agree with Yade")
    print(f"yade-examples: {finished} of {len(table)} in-scope scripts finish under Talus "
          f"({len(out_of_scope)} out of scope)")


if __name__ == "__main__":
    main()
