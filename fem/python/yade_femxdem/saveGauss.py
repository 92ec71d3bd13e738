"""Drop-in for Yade's FEMxDEM saveGauss: Gauss-point tensors to text files.

Format as Yade's: per keyword a line ``<name> <count>``, then one line per Gauss point with the
rows of its 2x2 (saveGauss2D) or 3x3 (saveGauss3D) tensor, in the order of
talus.fem.escript.toData (escript's data points). ``pos``: only those points."""
import _compat  # noqa: F401
import numpy as np

from talus.fem.escript import fromData

__all__ = ["saveGauss2D", "saveGauss3D"]


def _save(name, pos, d, tensors):
    with open(name, "w") as out:
        for key, data in tensors.items():
            values = fromData(data).reshape(-1, d, d)
            points = range(len(values)) if len(pos) == 0 else pos
            out.write(f"{key} {len(points)}\n")
            for p in points:
                out.write(" ".join(" ".join(repr(float(x)) for x in row) for row in values[p]) + "\n")


def saveGauss2D(name="", pos=(), **kwargs):
    _save(name, pos, 2, kwargs)


def saveGauss3D(name="", pos=(), **kwargs):
    _save(name, pos, 3, kwargs)
