"""Spheres from a text file: Yade's ``ymport.textExt`` and ``ymport.text``, the reader of the
files ``export.textExt`` writes (talus.dem.files.text_export).

    O.bodies.append(ymport.textExt("packing.spheres", "x_y_z_r", material="spheres"))

One sphere a line, numbers separated by blanks; lines starting with ``#`` are comments, except
``#format <name>``, which sets the format of the lines after it (as in Yade, it overrides the
``format`` argument). Formats: ``x_y_z_r``, ``x_y_z_r_matId`` (and the index of the material),
``id_x_y_z_r_matId`` (the body id first, not kept) and ``x_y_z_r_attrs`` (the columns after the
radius are appended, as strings, to the ``attrs`` list passed in, one list a sphere). Columns
after those a format reads are ignored, as Yade does. A line that cannot be read raises
``TextImportError`` naming the file and the line.
"""

from __future__ import annotations

import math

from talus.dem import distributed
from talus.dem.core.bodies import BodySpec, sphere
from talus.dem.files import slabs

__all__ = ["TextImportError", "textExt", "text"]

# format -> (index of x, index of r, index of the material id or None)
_COLUMNS = {
    "x_y_z_r": (0, 3, None),
    "x_y_z_r_matId": (0, 3, 4),
    "id_x_y_z_r_matId": (1, 4, 5),
    "x_y_z_r_attrs": (0, 3, None),
}


class TextImportError(ValueError):
    """A sphere file could not be read (the message names the file and the line)."""


def _sphere(words: list[str], format: str, where: str, shift, scale: float, kw: dict) -> BodySpec:
    x, r, mat = _COLUMNS[format]
    needed = (r if mat is None else mat) + 1
    if len(words) < needed:
        raise TextImportError(f"{where}: format {format} needs {needed} columns, got {len(words)}: "
                              f"{' '.join(words)!r}")
    try:
        numbers = [float(w) for w in words[x:r + 1]]
        material = int(words[mat]) if mat is not None else None
    except ValueError:
        raise TextImportError(f"{where}: format {format} needs numbers (and an integer material index), "
                              f"got {' '.join(words)!r}") from None
    if not all(math.isfinite(v) for v in numbers):
        raise TextImportError(f"{where}: non-finite number in {' '.join(words)!r}")
    if numbers[3] <= 0:
        raise TextImportError(f"{where}: the radius must be positive, got {words[r]}")
    center = tuple(s + scale * c for s, c in zip(shift, numbers[:3]))
    if material is None:
        return sphere(center, scale * numbers[3], **kw)
    return sphere(center, scale * numbers[3], material=material, **kw)


def _line(words: list[str], format: str, where: str, shift, scale: float, kw: dict) -> BodySpec:
    """The sphere of a line's ``words`` in ``format``."""
    if format not in _COLUMNS:
        raise TextImportError(f"{where}: format {format!r} is not one of {', '.join(_COLUMNS)}")
    if _COLUMNS[format][2] is not None and "material" in kw:
        raise TypeError(f"textExt: format {format} takes the material from the file; do not pass material=")
    return _sphere(words, format, where, shift, scale, kw)


def textExt(fileName: str, format: str = "x_y_z_r", shift=(0.0, 0.0, 0.0), scale: float = 1.0,
            attrs: list | None = None, **kw) -> list[BodySpec]:
    """The spheres of ``fileName`` in ``format`` (or the format its ``#format`` line names),
    centres scaled by ``scale`` then shifted by ``shift``, radii scaled; ``kw`` go to
    ``utils.sphere`` (material, color, fixed, mask...). Append them to ``O.bodies``. Under
    mpirun (without ``attrs``) each process reads its own slab of the file
    (talus.dem.files.slabs.SphereSlab), which O.bodies.append takes as it takes the list."""
    shift = tuple(float(s) for s in shift)
    if len(shift) != 3:
        raise ValueError(f"textExt: shift must have 3 components, got {len(shift)}")
    if distributed.ACTIVE and attrs is None:    # under mpirun each process reads its own slab only
        try:
            return slabs.read(fileName, format, distributed.rank(), distributed.RANKS,
                              lambda words, format, where: _line(words, format, where, shift, float(scale), kw))
        except OSError as e:
            raise TextImportError(f"{fileName}: cannot read ({e.strerror or e})") from None
    try:
        with open(fileName) as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise TextImportError(f"{fileName}: cannot read ({e.strerror or e})") from None
    spheres = []
    for number, line in enumerate(lines, 1):
        words = line.split()
        where = f"{fileName}, line {number}"
        if not words:
            continue
        if words[0] == "#format":
            if len(words) < 2:
                raise TextImportError(f"{where}: '#format' without a format name")
            format = words[1]
            continue
        if words[0].startswith("#"):
            continue
        spheres.append(_line(words, format, where, shift, float(scale), kw))
        if format == "x_y_z_r_attrs" and attrs is not None:
            attrs.append(words[4:])
    return spheres


def text(fileName: str, shift=(0.0, 0.0, 0.0), scale: float = 1.0, **kw) -> list[BodySpec]:
    """``textExt`` with format ``x_y_z_r`` (Yade's ``ymport.text``)."""
    return textExt(fileName, "x_y_z_r", shift=shift, scale=scale, **kw)
