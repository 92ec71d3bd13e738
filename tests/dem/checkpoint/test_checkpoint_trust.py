"""A checkpoint's Python commands (PyRunner commands, hooks) run only when it is trusted: a file
the user saved (signed with the user's key), O.load(path, trusted=True), or talus run
--trust-checkpoints. Others are loaded with their commands held, listed in a warning, and
refused when they come due. Each user is a data folder (XDG_DATA_HOME) holding its key."""
import os
import subprocess
import sys
import textwrap
import warnings

import pytest

from talus.dem import ForceResetter, NewtonIntegrator, PeriTriaxController, PyRunner, Scene, sphere
from talus.dem.files import io, trust

pytestmark = pytest.mark.skipif(not io.available(), reason="built without HDF5")


def scene(marker) -> Scene:
    """A sphere and a PyRunner whose command leaves a mark (a file) when it runs."""
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 0.1))
    S.engines = [ForceResetter(), NewtonIntegrator(),
                 PyRunner(command=f"open({str(marker)!r}, 'a').write('ran')", iterPeriod=2),
                 PeriTriaxController(goal=(-1, -1, -1), stressMask=7, doneHook="print('done')", dead=True)]
    S.dt = 1e-4
    return S


WRITER = """
import sys
sys.path.insert(0, sys.argv[3])
from test_checkpoint_trust import scene
scene(sys.argv[2]).save(sys.argv[1])
"""


@pytest.fixture
def me(tmp_path, monkeypatch):
    """This process's user: the data folder of its key."""
    home = tmp_path / "me"
    monkeypatch.setenv("XDG_DATA_HOME", str(home))
    monkeypatch.delenv(trust.ENVIRONMENT, raising=False)
    monkeypatch.setattr(trust, "_key_cache", None)
    return home


def saved_by(user, path, marker, build_dir):
    """The checkpoint written by another process of ``user`` (a data folder)."""
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python"), "XDG_DATA_HOME": str(user)}
    done = subprocess.run([sys.executable, "-c", WRITER, str(path), str(marker), os.path.dirname(__file__)],
                          capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 0, done.stderr


def test_commands_of_someone_elses_checkpoint_are_held_until_allowed(tmp_path, build_dir, me):
    path, marker = tmp_path / "shared.h5", tmp_path / "mark"
    saved_by(tmp_path / "someone-else", path, marker, build_dir)
    S = Scene()
    with pytest.warns(io.CheckpointWarning) as caught:
        S.load(path)
    message = str(caught[0].message)
    assert "holds Python commands, loaded but not run" in message
    assert f"PyRunner: \"open({str(marker)!r}, 'a').write('ran')\"" in message
    assert "doneHook: \"print('done')\"" in message
    assert f"O.load({str(path)!r}, trusted=True)" in message and "talus run --trust-checkpoints" in message
    # The engines are there, with their commands as saved; the command does not run.
    assert S.engines[2].command == f"open({str(marker)!r}, 'a').write('ran')"
    with pytest.raises(trust.UntrustedCommandError, match=r"PyRunner command .* of checkpoint .*shared.h5' was not "
                                                           r"run: the checkpoint is not trusted"):
        S.run(5)
    assert not marker.exists()
    # Allowed: the same file loads and runs its commands.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        S.load(path, trusted=True)
    S.run(5)
    assert marker.read_text() == "ran" * 2


def test_the_users_own_checkpoints_are_trusted(tmp_path, build_dir, me):
    """Yade scripts that save and load their own checkpoints, in one run or across runs, run
    unchanged."""
    path, marker = tmp_path / "own.h5", tmp_path / "mark"
    S = scene(marker)
    S.save(path)
    assert oct(trust.key_path().stat().st_mode & 0o777) == "0o600"
    T = Scene()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        T.load(path)
        T.reload()
    T.run(5)
    assert marker.read_text() == "ran" * 2
    # Saved by an earlier run of the same user.
    saved_by(me, path, marker, build_dir)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        T.load(path)
    # Told not to trust it, even one's own file is held.
    with pytest.warns(io.CheckpointWarning, match="loaded but not run"):
        T.load(path, trusted=False)
    # Memory slots never leave the process.
    S.saveTmp("a")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        S.loadTmp("a")


def test_saving_held_commands_does_not_make_them_the_users(tmp_path, build_dir, me):
    path, marker = tmp_path / "shared.h5", tmp_path / "mark"
    saved_by(tmp_path / "someone-else", path, marker, build_dir)
    S = Scene()
    with pytest.warns(io.CheckpointWarning, match="loaded but not run"):
        S.load(path)
    S.save(tmp_path / "mine.h5")
    with pytest.warns(io.CheckpointWarning, match="loaded but not run"):
        Scene().load(tmp_path / "mine.h5")
    # Once allowed, they are: the user vouched for them.
    S.load(path, trusted=True)
    S.save(tmp_path / "mine.h5")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Scene().load(tmp_path / "mine.h5")


LOADER = """
from talus.dem import O
import sys
O.load(sys.argv[1])
O.run(5)
print("marked", open(sys.argv[2]).read())
"""


def test_talus_run_trust_checkpoints(tmp_path, build_dir, talus_cmd, me):
    path, marker = tmp_path / "shared.h5", tmp_path / "mark"
    saved_by(tmp_path / "someone-else", path, marker, build_dir)
    script = tmp_path / "loader.py"
    script.write_text(textwrap.dedent(LOADER))
    env = {k: v for k, v in os.environ.items() if k != trust.ENVIRONMENT}
    refused = talus_cmd("run", script, path, marker, check=False, env=env)
    assert refused.returncode != 0 and "UntrustedCommandError" in refused.stderr
    assert "talus run --trust-checkpoints" in refused.stderr and not marker.exists()
    allowed = talus_cmd("run", "--trust-checkpoints", script, path, marker, env=env)
    assert "marked ranran" in allowed.stdout
