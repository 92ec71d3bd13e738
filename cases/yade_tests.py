"""Yade's own regression tests (the suite of `yade --test`), run against Talus and against Yade.

Run:      PYTHONPATH=build/python /usr/bin/python3 -m talus run cases/yade_tests.py [--quick]
          [--results DIR] [--only PATTERN] [--programs talus,yade]
Set-up:   the population is what Yade 2023.02a's `yade --test` runs (yade.tests.testAll): every test
          method of the modules in yade/tests/__init__.py's allTests, and the docstring examples
          of the modules in its allModules. At run time Yade's installed test folder
          (TESTS) and the source files of those modules are copied into a temporary folder (none
          of Yade's files is in this repository); cases/yade/unittest_runner.py runs each module
          in its own process with a time limit, under Talus (/usr/bin/python3 with this Talus's
          python folder first on PYTHONPATH, so `import yade` is Talus's package) and under Yade
          (`yade -n -x`, PYTHONPATH unset). A test is out of scope when it needs what Talus does
          not have (OUT_OF_SCOPE: a reason per test id pattern, the first match wins).
Checked:  yade-tests.pass: the fraction of in-scope tests that pass under Talus (>= 0.8); its
          fields give the counts under both programs, the tests that do not pass under Talus with
          their first error line, and the out-of-scope tests with reasons.
          --quick runs the fixed subset QUICK under Talus only (a few seconds).
Produces: the record and results/yade-tests.details.json (the per-test table).
"""
from __future__ import annotations

import ast
import fnmatch
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import talus
from talus import results

YADE_PY = Path("/usr/lib/x86_64-linux-gnu/yade-double/py/yade")
TESTS = YADE_PY / "tests"
RUNNER = Path(__file__).resolve().parent / "yade" / "unittest_runner.py"

# (test id pattern, reason): what Talus does not have. Ids are MODULE.CLASS.METHOD, and
# doctest.yade.MODULE.NAME for docstring examples.
OUT_OF_SCOPE = [
    ("core.TestInteractions.testEraseBodiesInInteraction",
     "local-coordinates contact geometry: its scene is built on Ig2_Sphere_Sphere_L3Geom and "
     "Law2_L3Geom_FrictPhys_ElPerfPl (L3Geom)"),
    ("core.TestBodies.testErasedAndNewlyCreatedSphere",
     "local-coordinates contact geometry: its InteractionLoop holds Ig2_Sphere_Sphere_L3Geom and "
     "Law2_L3Geom_FrictPhys_ElPerfPl (L3Geom)"),
    ("pbc.TestPBC.testL3GeomIncidentVelocity",
     "local-coordinates contact geometry: checks L3Geom's relative displacement u"),
    ("core.TestMaterialStateAssociativity.testThrowsAtBadCombination",
     "concrete (CPM) model: CpmMat with a plain State"),
    ("core.TestMaterialStateAssociativity.testMaterialReturnsState",
     "concrete (CPM) model: CpmMat().newAssocState() is a CpmState"),
    ("cohesive-chain.*", "cylinders: a beam of chainedCylinder elements (ChainedCylinder, "
     "Ig2_ChainedCylinder_ChainedCylinder_ScGeom6D, Ig2_Sphere_ChainedCylinder_CylScGeom)"),
    ("dummyTest.*", "exercises nothing of Yade: the template for writing a test module "
     "(assertTrue(True), a local exception), passes under any Python"),
    ("enumTest.*", "the OpenGL renderer (GUI): assigns OpenGLRenderingEngine.blinkHighlight's "
     "enum values, and returns at once without 'QT5' in yade.config.features"),
    ("testMath.SimpleTests.testDefReadonly", None),  # in scope: TriaxialStressController().porosity
    ("testMath.*", "Yade's high-precision Real library: the RealHP<N> scopes of yade.math (their "
     "math functions against mpmath, constants, CGAL and Eigen number traits, and C++ self-tests); "
     "Talus computes in double only"),
    ("testMinieigenHP.ExtendedMinieigenTests.test*c*",
     "complex-valued minieigen types (Vector2c, Vector3c, Matrix3c) of Yade's high-precision "
     "library; no DEM quantity is complex"),
    ("testMinieigenHP.ExtendedMinieigenTests.testVector3na",
     "Vector3na, the SIMD-aligned vector of Yade's 'vectorize' build option"),
]

# The fixed subset of --quick: the scene, body and cell interface in a few seconds.
QUICK = ["core", "pbc", "clump", "wrapper"]


def yade_test_lists() -> tuple[list[str], list[str]]:
    """allTests and allModules of Yade's yade/tests/__init__.py, read from its text."""
    tree = ast.parse((TESTS / "__init__.py").read_text(encoding="utf-8"))
    tests, modules = [], []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name):
            if node.targets[0].id == "allTests":
                tests = [e.value for e in node.value.elts]
            elif node.targets[0].id == "allModules":
                modules = [ast.unparse(e).removeprefix("yade.") for e in node.value.elts]
    if not tests or not modules:
        raise SystemExit(f"yade_tests: no allTests/allModules in {TESTS / '__init__.py'}")
    # `yade --test` adds yade.qt to allModules when it imports (Yade's GUI; it has no doctests).
    return tests, modules


def scope(test_id: str) -> str | None:
    """None when the test is in scope, else the reason it is not."""
    for pattern, reason in OUT_OF_SCOPE:
        if fnmatch.fnmatchcase(test_id, pattern):
            return reason
    return None


def prepare(work: Path, doc_modules: list[str]) -> list[str]:
    """Yade's test folder and the sources of the doctested modules copied into ``work``; returns
    the runner's WHAT of each doctested module that has a source file."""
    shutil.copytree(TESTS, work, dirs_exist_ok=True)
    shutil.copy2(RUNNER, work / RUNNER.name)
    (work / "sources").mkdir()
    whats = []
    for name in doc_modules:
        source = YADE_PY / f"{name}.py"
        if source.is_file():
            shutil.copy2(source, work / "sources" / source.name)
            whats.append(f"doctest:{name}:{work / 'sources' / source.name}")
    return whats


def last_error_line(message: str) -> str:
    lines = [line for line in message.strip().splitlines() if line.strip()]
    for line in reversed(lines):
        if re.match(r"^[A-Za-z_.]*(Error|Exception|Interrupt|Exit)\b", line.strip()):
            return line.strip()[:300]
    return lines[-1].strip()[:300] if lines else ""


def run_module(command: list[str], what: str, work: Path, timeout: float, env: dict) -> dict:
    """Runs one module's tests in one process; {test id: row}, a "collect error" row under the
    module's name when it could not be imported."""
    out = work / "results.jsonl"
    out.unlink(missing_ok=True)
    t0 = time.perf_counter()
    try:
        p = subprocess.run([*command, RUNNER.name, what, str(out)], cwd=work, capture_output=True,
                           text=True, timeout=timeout, env=env, stdin=subprocess.DEVNULL)
        ended = f"exit status {p.returncode}: " + last_error_line(p.stdout + p.stderr)
    except subprocess.TimeoutExpired:
        ended = f"still running after {timeout:g} s"
    lines = [json.loads(line) for line in out.read_text().splitlines()] if out.exists() else []
    name = f"doctest.yade.{what.split(':')[1]}" if what.startswith("doctest:") else what
    if not lines:
        return {name: {"status": "error", "error": "no result: " + ended, "import_failed": True,
                       "wall_s": round(time.perf_counter() - t0, 2)}}
    if "collect_error" in lines[0]:
        return {name: {"status": "error", "error": "import failed: " + last_error_line(lines[0]["collect_error"]),
                       "message": lines[0]["collect_error"][-2000:], "import_failed": True}}
    rows = {}
    for row in lines[1:]:
        rows[row["id"]] = {"status": row["status"], "wall_s": row["wall_s"],
                           "error": last_error_line(row["message"]) if row["status"] != "ok" else "",
                           **({"message": row["message"][-2000:]} if row["status"] != "ok" else {})}
    for n, test_id in enumerate(t for t in lines[0]["collected"] if t not in rows):
        # the first unfinished test was running when the process ended; the rest never started
        rows[test_id] = {"status": "error", "error": ended if n == 0 else "not run: " + ended}
    return rows


def _import_failed(rows: dict) -> bool:
    return len(rows) == 1 and next(iter(rows.values())).get("import_failed", False)


def main():
    parser = results.case_arguments(__doc__)
    parser.add_argument("--only", default=None, help="regular expression: run only matching modules")
    parser.add_argument("--timeout", type=float, default=None, help="seconds per module and program")
    parser.add_argument("--programs", default=None,
                        help="comma-separated: talus, yade (default: both; talus only with --quick)")
    args = parser.parse_args()
    if not TESTS.is_dir():
        raise SystemExit(f"yade_tests: {TESTS} not found (./setup.sh installs Debian's yade package)")
    case = results.Case("yade-tests.pass", quick=args.quick, folder=args.results)
    programs = (args.programs or ("talus" if args.quick else "talus,yade")).split(",")
    if "yade" in programs and not shutil.which("yade"):
        raise SystemExit("yade_tests: yade is not installed (./setup.sh installs the Debian package)")
    timeout = args.timeout or (120.0 if args.quick else 600.0)
    # This very Talus's package first on the path; Yade with PYTHONPATH unset.
    env_talus = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(Path(talus.__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")]))
    env_yade = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "DISPLAY")}
    runners = {"talus": ([sys.executable], env_talus), "yade": (["yade", "-n", "-x"], env_yade)}

    test_modules, doc_modules = yade_test_lists()
    table: dict[str, dict] = {}
    with tempfile.TemporaryDirectory(prefix="yade_tests_") as tmp:
        work = Path(tmp)
        whats = test_modules + prepare(work, doc_modules)
        if args.quick:
            whats = [w for w in whats if w in QUICK]
        if args.only:
            whats = [w for w in whats if re.search(args.only, w)]
        for what in whats:
            counts, by_program = [], {}
            for program in programs:
                command, env = runners[program]
                by_program[program] = rows = run_module(command, what, work, timeout, env)
                counts.append(f"{program} {sum(r['status'] == 'ok' for r in rows.values())}/{len(rows)}")
            # A module one program could not import: its error stands for each test the other
            # collected (the module is one row only when no program collected a test).
            collected = {t for rows in by_program.values() if not _import_failed(rows) for t in rows}
            for program, rows in by_program.items():
                if _import_failed(rows) and collected:
                    rows = dict.fromkeys(collected, next(iter(rows.values())))
                for test_id, row in rows.items():
                    table.setdefault(test_id, {})[program] = row
            label = what.split(":")[1] if what.startswith("doctest:") else what
            print(f"{label:20s} " + "  ".join(counts), flush=True)

    in_scope = {t: r for t, r in table.items() if scope(t) is None}
    out_of_scope = {t: scope(t) for t in table if scope(t) is not None}
    for test_id, reason in out_of_scope.items():
        table[test_id]["out_of_scope"] = reason
    case.folder.mkdir(parents=True, exist_ok=True)
    if "talus" not in programs:
        (case.folder / "yade-tests.yade-only.json").write_text(json.dumps(table, indent=1))
        return
    # A test only Yade collected (Talus failed to import its module) did not pass under Talus.
    failing = {t: r.get("talus", {}).get("error", "not collected under Talus") for t, r in in_scope.items()
               if r.get("talus", {}).get("status") != "ok"}
    passed = [t for t in in_scope if t not in failing]
    fraction = len(passed) / max(1, len(in_scope))
    (case.folder / "yade-tests.details.json").write_text(json.dumps(
        {"tests": table, "out_of_scope": out_of_scope, "not_passing": failing}, indent=1))
    case.record("fraction of Yade's in-scope regression tests (yade --test) that pass against Talus",
                fraction, "Yade 2023.02a's test suite (the same tests under yade -n -x)", 0.8,
                comparison=">=", tests=len(in_scope), passed=len(passed),
                yade_passed=sum(r.get("yade", {}).get("status") == "ok" for r in in_scope.values()),
                yade_passed_all=sum(r.get("yade", {}).get("status") == "ok" for r in table.values()),
                population=len(table), out_of_scope=out_of_scope, not_passing=failing)
    print(f"yade-tests: {len(passed)} of {len(in_scope)} in-scope tests pass under Talus "
          f"({len(out_of_scope)} out of scope)")


if __name__ == "__main__":
    main()
