"""The periodic cell (Yade's ``O.cell``), and Yade's Vector3/Matrix3 constructors as numpy."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from talus.dem.scene import Scene


class Vector3(np.ndarray):
    """``Vector3(x, y, z)`` as in Yade scripts; a numpy array of shape (3,)."""

    def __new__(cls, *xyz):
        return np.array(xyz[0] if len(xyz) == 1 else xyz, dtype=float).reshape(3)


class Matrix3(np.ndarray):
    """``Matrix3(a, b, c, d, e, f, g, h, i)`` (row by row) or ``Matrix3(rows)``, as in Yade
    scripts; a numpy array of shape (3, 3). ``Matrix3.Identity``, ``Matrix3.Zero``."""

    def __new__(cls, *values):
        return np.array(values[0] if len(values) == 1 else values, dtype=float).reshape(3, 3)


Vector3.Zero = np.zeros(3)
Matrix3.Identity = np.eye(3)
Matrix3.Zero = np.zeros((3, 3))


def _matrix(name: str, value) -> np.ndarray:
    m = np.asarray(value, dtype=float)
    if m.shape == (9,):
        m = m.reshape(3, 3)
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise ValueError(f"O.cell.{name} must be a finite 3x3 matrix, got {value!r}")
    return m


class Cell:
    """Edges ``hSize`` (columns), velocity gradient ``velGrad``, accumulated transformation
    ``trsf``, ``homoDeform`` (particles follow the homogeneous deformation), ``volume``."""

    def __init__(self, scene: "Scene"):
        self._scene = scene

    @property
    def _cpp(self):
        return self._scene._cpp.cell

    @property
    def hSize(self) -> np.ndarray:
        return np.array(self._cpp.hSize)

    @hSize.setter
    def hSize(self, value):
        self._scene._cpp.setCellSize(_matrix("hSize", value))

    def setBox(self, *size):
        """An axis-aligned box cell of the given sizes."""
        size = np.asarray(size[0] if len(size) == 1 else size, dtype=float).reshape(3)
        self.hSize = np.diag(size)

    @property
    def size(self) -> np.ndarray:
        """Lengths of the cell's edges."""
        return np.linalg.norm(self.hSize, axis=0)

    @size.setter
    def size(self, value):
        self.setBox(value)

    @property
    def velGrad(self) -> np.ndarray:
        return np.array(self._cpp.velGrad)

    @velGrad.setter
    def velGrad(self, value):
        self._cpp.velGrad = _matrix("velGrad", value)

    @property
    def trsf(self) -> np.ndarray:
        return np.array(self._cpp.trsf)

    @trsf.setter
    def trsf(self, value):
        self._cpp.trsf = _matrix("trsf", value)

    homoDeform = property(lambda s: s._cpp.homoDeform, lambda s, v: setattr(s._cpp, "homoDeform", bool(v)))
    volume = property(lambda s: s._cpp.volume)

    def wrap(self, point) -> np.ndarray:
        """The point moved into the cell by whole periods."""
        frac = np.linalg.solve(self.hSize, np.asarray(point, dtype=float))
        return self.hSize @ (frac - np.floor(frac))
