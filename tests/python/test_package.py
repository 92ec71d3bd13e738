"""The talus package imports from the build tree and reports what the build contains."""
import talus
from talus import _dem


def test_python_and_compiled_versions_agree():
    assert talus.__version__ == _dem.version()
    assert talus.__version__.count(".") == 2


def test_components_match_the_compiled_table():
    compiled = {name: on for kind, name, on, _ in _dem.build_config() if kind == "component"}
    assert talus.components() == compiled
    assert compiled["dem"] is True
    assert set(compiled) == {"dem", "flow", "coupling", "foam-solvers", "fem"}


def test_every_off_item_says_why():
    for table in talus.build_info().values():
        for name, (on, note) in table.items():
            assert note.strip(), f"{name} has no note"


def test_hello_case_runs(talus_cmd, repo_dir):
    done = talus_cmd("run", repo_dir / "cases" / "00_hello_talus.py")
    assert "toolchain OK" in done.stdout
    assert f"Talus {talus.__version__}" in done.stdout
