"""The atomic file write every Talus output uses (records, VTU files, plots and data files): a
reader of the file sees the old one or the whole new one, never a part, and a failed write leaves
the old file as it was and no temporary file behind."""

from __future__ import annotations

import itertools
import os
from typing import Callable

_counter = itertools.count()


def write_atomically(path: str | os.PathLike, content: bytes | Callable[[str], None], *, fsync: bool = False) -> None:
    """Write ``path`` through a temporary file in the same folder (created with it) and a rename.

    ``content`` is the bytes to write, or a function given the temporary file's name that writes
    it (for writers that open the file themselves: matplotlib, h5py, compressed text).
    ``fsync``: the data reach the disk before the rename, so that the new file also survives a
    crash of the machine (records; not needed for outputs written every few steps)."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    temporary = os.path.join(folder, f".{os.path.basename(path)}.tmp-{os.getpid()}-{next(_counter)}")
    try:
        if callable(content):
            content(temporary)
        else:
            with open(temporary, "xb") as f:
                f.write(content)
        if fsync:
            with open(temporary, "rb") as f:
                os.fsync(f.fileno())
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise
