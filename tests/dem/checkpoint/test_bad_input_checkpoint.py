"""A checkpoint edited to hold a body field no scene can have (a negative radius, a zero mass
on a dynamic body, a NaN position) is refused at load with the body and the field named, and the
scene is left as it was (not a step later, as a non-finite force blamed on the time step)."""
import subprocess
import sys
import textwrap

import pytest

from talus.dem import FrictMat, Scene, sphere, wall
from talus.dem.files import io

EDITS = {
    "negative radius": ("bodies/radius", 1, "-0.1", r"body 1: radius -0.100000 is not positive and finite"),
    "zero radius": ("bodies/radius", 0, "0.0", r"body 0: radius 0.000000 is not positive and finite"),
    "zero mass": ("bodies/mass", 1, "0.0", r"body 1: mass is 0 but the body is dynamic"),
    "NaN mass": ("bodies/mass", 0, "float('nan')", r"body 0: mass nan is not finite"),
    "NaN position": ("bodies/pos", 1, "[0, float('nan'), 0]", r"body 1: position is not finite"),
}


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    S = Scene()
    S.materials.append(FrictMat(density=2600))
    S.bodies.append([sphere((0, 0, 0.1), 0.05), sphere((0.2, 0, 0.1), 0.05), wall(0, axis=2)])
    path = tmp_path_factory.mktemp("ck") / "ok.h5"
    io.save(S, path)
    return path


@pytest.mark.parametrize("edit", EDITS.values(), ids=list(EDITS))
def test_an_edited_body_field_is_named_at_load(tmp_path, saved, edit):
    pytest.importorskip("h5py")
    dataset, body, value, message = edit
    path = tmp_path / "edited.h5"
    path.write_bytes(saved.read_bytes())
    # h5py in a process of its own (its HDF5 is not the one Talus links); it rewrites the checksums.
    subprocess.run([sys.executable, "-c", textwrap.dedent(f"""
        import h5py
        with h5py.File({str(path)!r}, "r+") as f:
            f[{dataset!r}][{body}] = {value}
        """)], check=True, timeout=60)
    T = Scene()
    T.bodies.append(sphere((0, 0, 0), 0.5))
    with pytest.raises(io.CheckpointError, match=r"edited.h5.*" + message):
        io.load(T, path)
    assert len(T.bodies) == 1 and T.iter == 0
    io.load(T, saved)                # the file it came from loads
    assert len(T.bodies) == 3
