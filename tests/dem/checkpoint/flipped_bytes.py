"""The damage the checkpoint tests apply to a file: one byte flipped, at evenly spread places."""
from pathlib import Path
from typing import Callable

from talus.dem import Scene
from talus.dem.files import io


def load_flipped_copies(source: Path, path: Path, places: int, new_scene: Callable[[], Scene],
                        check_loaded: Callable[[Scene], None], check_untouched: Callable[[Scene], None]) -> tuple:
    """Load about `places` copies of the checkpoint `source` (written to `path`), each with one
    byte flipped, into scenes made by `new_scene`: each load must either fail with a
    CheckpointError naming the file, leaving the scene untouched (`check_untouched`), or
    restore what `check_loaded` expects (a byte nothing reads). Returns (refused, copies)."""
    data = source.read_bytes()
    offsets = range(0, len(data), len(data) // places | 1)   # odd stride
    refused = 0
    for offset in offsets:
        damaged = bytearray(data)
        damaged[offset] ^= 0x5A
        path.write_bytes(damaged)
        scene = new_scene()
        try:
            io.load(scene, path, engines="current")
        except io.CheckpointError as e:
            assert f"checkpoint '{path}'" in str(e)
            check_untouched(scene)
            refused += 1
            continue
        check_loaded(scene)
    return refused, len(offsets)
