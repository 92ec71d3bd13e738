"""`cmake --install` gives a usable Talus: library, headers, CMake package, Python package and the
`talus` command, all working from a prefix other than the build tree."""
import os
import subprocess

import pytest


def run(*cmd, env=None, cwd=None):
    done = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, env=env, cwd=cwd,
                          timeout=300)
    assert done.returncode == 0, f"{' '.join(map(str, cmd))} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


@pytest.fixture(scope="module")
def prefix(build_dir, tmp_path_factory):
    prefix = tmp_path_factory.mktemp("prefix")
    run("cmake", "--install", build_dir, "--prefix", prefix)
    return prefix


def test_installed_command_and_package(prefix):
    import talus
    assert run(prefix / "bin" / "talus", "--version").strip() == f"talus {talus.__version__}"
    site = next(prefix.glob("lib/python3*/dist-packages"))
    env = {**os.environ, "PYTHONPATH": str(site)}
    out = run("/usr/bin/python3", "-c", "import talus; print(talus.__file__, talus.components()['dem'])",
              env=env, cwd=prefix)
    assert out.startswith(str(site)) and out.strip().endswith("True")


def test_find_package_from_another_cmake_project(prefix, repo_dir, tmp_path):
    build = tmp_path / "consumer-build"
    run("cmake", "-S", repo_dir / "tests" / "buildsystem" / "consumer", "-B", build,
        f"-DCMAKE_PREFIX_PATH={prefix}")
    run("cmake", "--build", build)
    out = run(build / "consumer")
    import talus
    assert f"talus {talus.__version__}" in out
    assert "component dem ON" in out
    assert (prefix / "include" / "talus" / "dem" / "base" / "build_config.h").is_file()
