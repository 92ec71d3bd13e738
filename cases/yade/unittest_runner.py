"""Runs one of Yade's test modules, or the doctests of one of Yade's modules, and writes one JSON
line per test: the runner of cases/yade_tests.py, started once per module by
``python3 unittest_runner.py WHAT OUT.jsonl`` (Talus) or ``yade -n -x unittest_runner.py WHAT
OUT.jsonl`` (Yade), in a folder holding copies of Yade's test modules.

WHAT is a test module's file name without ``.py`` (``core``, ``cohesive-chain``), or
``doctest:NAME:SOURCE`` for the docstring examples of module ``yade.NAME`` as written in Yade's
source file SOURCE (Yade's own testAll runs them with doctest.DocTestSuite; here the examples are
read from Yade's text and run in the namespace of whichever ``yade.NAME`` this Python imports).

The first line lists the collected test ids, then one line per finished test, flushed at once, so
that a crash or a time limit loses only the test that was running.
"""
import ast
import doctest
import importlib.util
import io
import json
import sys
import time
import traceback
import unittest
from pathlib import Path


def collect_unittests(module_name: str) -> list:
    """(id, TestCase) of every test method of the module file ``module_name.py`` in the working
    folder (imported under that name, as Yade's loader imports ``yade.tests.<name>``)."""
    here = Path.cwd()  # the copied test folder (under `yade -x`, __file__ is Yade's launcher)
    sys.path.insert(0, str(here))  # the modules import their helpers (testMathHelper) by name
    spec = importlib.util.spec_from_file_location(module_name, here / f"{module_name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    spec.loader.exec_module(module)
    suite = unittest.defaultTestLoader.loadTestsFromModule(module)
    cases = []

    def flatten(s):
        for t in s:
            if isinstance(t, unittest.TestSuite):
                flatten(t)
            else:
                cases.append((f"{module_name}.{type(t).__name__}.{t._testMethodName}", t))
    flatten(suite)
    return cases


def docstrings(source: Path):
    """(qualified name, docstring, line) of the module, its functions, classes and their
    methods, in the order DocTestFinder would visit them."""
    tree = ast.parse(source.read_text(encoding="utf-8"))
    found = []
    if ast.get_docstring(tree, clean=False):
        found.append(("", ast.get_docstring(tree, clean=False), 1))

    def visit(body, prefix):
        for node in body:
            if isinstance(node, (ast.If, ast.Try, ast.With)):  # definitions made conditionally
                for block in ("body", "orelse", "finalbody"):
                    visit(getattr(node, block, []), prefix)
                for handler in getattr(node, "handlers", []):
                    visit(handler.body, prefix)
            elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                doc = ast.get_docstring(node, clean=False)
                if doc:
                    found.append((prefix + node.name, doc, node.lineno))
                if isinstance(node, ast.ClassDef):
                    visit(node.body, prefix + node.name + ".")
    visit(tree.body, "")
    return found


class DocTestCase(unittest.TestCase):
    """One docstring's examples, run as doctest.DocTestSuite runs them (default option flags,
    the module's globals copied for each docstring)."""

    def __init__(self, test: doctest.DocTest):
        super().__init__("runTest")
        self.test = test

    def runTest(self):
        output = io.StringIO()
        runner = doctest.DocTestRunner(verbose=False)
        result = runner.run(self.test, out=output.write)
        if result.failed:
            self.fail(output.getvalue())


def collect_doctests(name: str, source: str) -> list:
    """The docstrings of Yade's source file that hold examples, as tests run in the namespace of
    ``yade.<name>`` (imported only when there is an example to run)."""
    parser = doctest.DocTestParser()
    found = [(qualname, doc, line) for qualname, doc, line in docstrings(Path(source))
             if parser.get_examples(doc)]
    if not found:
        return []
    module = importlib.import_module(f"yade.{name}")
    # Yade's modules start with `from yade.wrapper import *`, so their globals (which
    # DocTestSuite gives the examples) hold every class; a thin module may not: the same names
    # first, then the module's own.
    wrapper = importlib.import_module("yade.wrapper")
    exported = getattr(wrapper, "__all__", [n for n in dir(wrapper) if not n.startswith("_")])
    namespace = {n: getattr(wrapper, n) for n in exported}
    cases = []
    for qualname, doc, line in found:
        test = parser.get_doctest(doc, {**namespace, **module.__dict__}, f"yade.{name}.{qualname}".rstrip("."),
                                  source, line)
        cases.append((f"doctest.{test.name}", DocTestCase(test)))
    return cases


def outcome(case: unittest.TestCase) -> tuple:
    """(status, message) of running one test: ok, fail, error or skip."""
    result = unittest.TestResult()
    case.run(result)
    for kind, entries in (("error", result.errors), ("fail", result.failures)):
        if entries:
            return kind, entries[0][1]
    if result.skipped:
        return "skip", result.skipped[0][1]
    return "ok", ""


def main():
    what, out = sys.argv[1], Path(sys.argv[2])
    with out.open("w") as sink:
        def write(row):
            sink.write(json.dumps(row) + "\n")
            sink.flush()
        try:
            if what.startswith("doctest:"):
                _, name, source = what.split(":", 2)
                cases = collect_doctests(name, source)
            else:
                cases = collect_unittests(what)
        except BaseException:  # an import error fails the whole module: say so, with the cause
            write({"collect_error": traceback.format_exc()})
            return
        write({"collected": [test_id for test_id, _ in cases]})
        for test_id, case in cases:
            t0 = time.perf_counter()
            status, message = outcome(case)
            write({"id": test_id, "status": status, "message": message,
                   "wall_s": round(time.perf_counter() - t0, 3)})


main()
