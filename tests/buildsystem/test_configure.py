"""The configure step switches off what a machine lacks, says why, and still configures the rest.
(CI also builds and tests a tree configured this way: see .ci/run.)"""
import os
import re
import subprocess


def configure(repo_dir, build, *args, env=None):
    done = subprocess.run(["cmake", "-S", str(repo_dir), "-B", str(build),
                           "-DPython3_EXECUTABLE=/usr/bin/python3", *args],
                          capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def summary_line(out, name):
    match = re.search(rf"^-- +{re.escape(name)} +(ON|OFF) +(.*)$", out, re.MULTILINE)
    assert match, f"no summary line for {name} in:\n{out}"
    return match.group(1), match.group(2)


def test_missing_openfoam_and_dolfinx_are_reported(repo_dir, tmp_path):
    # A dolfinx that fails to import stands for a machine without FEniCSx.
    shadow = tmp_path / "shadow" / "dolfinx"
    shadow.mkdir(parents=True)
    (shadow / "__init__.py").write_text("raise ImportError('dolfinx removed for this test')\n")
    env = {**os.environ, "PYTHONPATH": str(shadow.parent)}
    out = configure(repo_dir, tmp_path / "build", "-DTALUS_OPENFOAM_LIB_DIR=/nonexistent",
                    "-DTALUS_TESTS=OFF", env=env)
    state, note = summary_line(out, "foam-solvers")
    assert state == "OFF" and "/nonexistent" in note and "apt-get install openfoam" in note
    state, note = summary_line(out, "fenicsx")
    assert state == "OFF" and "dolfinx removed for this test" in note
    assert summary_line(out, "dem")[0] == "ON"
    assert summary_line(out, "flow")[0] == "ON"
    assert summary_line(out, "fem")[0] == "ON"      # the Gauss-point calls need no driver


def test_options_switch_components_off(repo_dir, tmp_path):
    out = configure(repo_dir, tmp_path / "build", "-DTALUS_WITH_FLOW=OFF", "-DTALUS_WITH_COUPLING=OFF",
                    "-DTALUS_WITH_FOAM_SOLVERS=OFF", "-DTALUS_WITH_FEM=OFF", "-DTALUS_TESTS=OFF")
    for name in ("flow", "coupling", "foam-solvers", "fem"):
        state, note = summary_line(out, name)
        assert state == "OFF" and "switched off by TALUS_WITH_" in note
    config = (tmp_path / "build" / "generated" / "_build_config.py").read_text()
    assert '"flow": (False,' in config and '"dem": (True,' in config
