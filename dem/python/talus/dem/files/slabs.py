"""A sphere file read in slabs under mpirun: ``ymport.text``/``textExt`` give each process one
contiguous part (a slab) of the file's spheres instead of all of them, so that no process ever
holds the whole packing (talus.dem.distributed; docs/distributed-dem.md).

    O.bodies.append(ymport.text("packing.spheres"))   # the serial script, unchanged

``O.bodies.append`` gives the slab's spheres the ids they have in one process (every process
counts the file's spheres and moves its next id past them) and adds only this process's slab; the
scene's split at its first step offers each process's slab to Zoltan, which moves every sphere
to the process whose region holds it. Until then each process holds its slab: the file's spheres
cannot be iterated or indexed, and the whole-scene reads (extrema, energies, positions) are
refused by name before the first step.
"""

from __future__ import annotations

#: Spheres made (and appended) at a time: a slab's specs never all exist at once.
CHUNK = 10_000


class SphereSlab:
    """This process's slab of the spheres of a file: ``len()`` is the whole file's count, the
    slab is spheres ``first .. first + size - 1`` of the file (in its order), made on demand."""

    def __init__(self, fileName: str, format: str, count: int, first: int, size: int, offset: int, line: int,
                 make):
        self.fileName, self.format = fileName, format
        self.count, self.first, self.size = count, first, size
        self._offset, self._line, self._make = offset, line, make

    def __len__(self) -> int:
        return self.count

    def __iter__(self):
        from talus.dem import distributed
        raise distributed.NotDistributed(f"the spheres of {self.fileName} were read in slabs (ymport under mpirun: each process "
                        f"holds its own part of the file): append them to O.bodies as they are "
                        f"(O.bodies.append(ymport.text(...))), then read the bodies after the first step")

    __getitem__ = __iter__

    def chunks(self):
        """The slab's specs, CHUNK at a time, in the file's order."""
        format, chunk, made = self.format, [], 0
        with open(self.fileName, "rb") as f:
            f.seek(self._offset)
            for number, raw in enumerate(f, self._line):
                if made == self.size:
                    break
                words = raw.decode().split()
                if not words:
                    continue
                if words[0] == "#format":
                    format = words[1] if len(words) > 1 else ""
                    continue
                if words[0].startswith("#"):
                    continue
                chunk.append(self._make(words, format, f"{self.fileName}, line {number}"))
                made += 1
                if len(chunk) == CHUNK:
                    yield chunk
                    chunk = []
        if chunk:
            yield chunk


def read(fileName: str, format: str, rank: int, ranks: int, make) -> SphereSlab:
    """Slab ``rank`` of ``ranks`` of the spheres of ``fileName`` (``format`` until a ``#format``
    line changes it); ``make(words, format, where)`` makes a sphere's BodySpec from a line's words.
    Every process reads the file through (to count its spheres) and keeps only where its slab
    starts."""
    count = 0
    with open(fileName, "rb") as f:
        for raw in f:
            words = raw.split(maxsplit=1)
            count += bool(words) and not words[0].startswith(b"#")
    first, last = count * rank // ranks, count * (rank + 1) // ranks
    offset, line, seen = 0, 1, 0
    with open(fileName, "rb") as f:
        for raw in f:
            words = raw.split()
            if words and words[0] == b"#format" and len(words) > 1:
                format = words[1].decode()
            elif words and not words[0].startswith(b"#"):
                if seen == first:
                    break
                seen += 1
            offset += len(raw)
            line += 1
    return SphereSlab(fileName, format, count, first, last - first, offset, line, make)


def is_slab(spec) -> bool:
    """Whether ``spec`` (what O.bodies.append was given) is a slab of a file's spheres."""
    return isinstance(spec, SphereSlab)
