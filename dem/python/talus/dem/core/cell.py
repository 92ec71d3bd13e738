"""The periodic cell (Yade's ``O.cell``): its edges, velocity gradient and transformation as
Matrix3, its size as a Vector3."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from talus.dem.base.linalg import Matrix3, Vector3

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene


def _matrix(name: str, value) -> np.ndarray:
    m = np.asarray(value, dtype=float)
    if m.shape == (9,):
        m = m.reshape(3, 3)
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise ValueError(f"O.cell.{name} must be a finite 3x3 matrix, got {value!r}")
    return m


class CellError(ValueError, RuntimeError):
    """A cell that cannot be (degenerate, left-handed): a ValueError, and Yade's RuntimeError."""


class Cell:
    """Edges ``hSize`` (columns), velocity gradient ``velGrad``, accumulated transformation
    ``trsf``, ``homoDeform`` (particles follow the homogeneous deformation), ``volume``."""

    def __init__(self, scene: "Scene"):
        self._scene = scene

    @property
    def _cpp(self):
        return self._scene._cpp.cell

    @property
    def hSize(self) -> Matrix3:
        return Matrix3(self._cpp.hSize)

    @hSize.setter
    def hSize(self, value):
        try:
            self._scene._cpp.setCellSize(_matrix("hSize", value))
        except ValueError as e:   # Yade raises RuntimeError for a degenerate cell: both catch it
            raise CellError(str(e)) from None

    def setBox(self, *size):
        """An axis-aligned box cell of the given sizes."""
        size = np.asarray(size[0] if len(size) == 1 else size, dtype=float).reshape(3)
        self.hSize = np.diag(size)

    @property
    def refHSize(self) -> Matrix3:
        """The cell before the accumulated transformation: ``hSize = trsf @ refHSize`` (Yade)."""
        return Matrix3(np.linalg.solve(self.trsf, self.hSize))

    hSize0 = refHSize   # Yade's other name: trsf^-1 hSize

    @property
    def refSize(self) -> Vector3:
        """Edge lengths of ``refHSize``; setting it makes a new box cell of these sizes with no
        accumulated transformation (Yade's deprecated ``O.cell.refSize = ...``)."""
        return Vector3(np.linalg.norm(self.refHSize, axis=0))

    @refSize.setter
    def refSize(self, value):
        self.setBox(value)
        self.trsf = np.eye(3)

    @property
    def size(self) -> Vector3:
        """Lengths of the cell's edges."""
        return Vector3(np.linalg.norm(self.hSize, axis=0))

    @size.setter
    def size(self, value):
        self.setBox(value)

    @property
    def velGrad(self) -> Matrix3:
        return Matrix3(self._cpp.velGrad)

    @velGrad.setter
    def velGrad(self, value):
        self._cpp.velGrad = _matrix("velGrad", value)

    @property
    def trsf(self) -> Matrix3:
        return Matrix3(self._cpp.trsf)

    @trsf.setter
    def trsf(self, value):
        self._cpp.trsf = _matrix("trsf", value)

    prevVelGrad = property(lambda s: Matrix3(s._cpp.prevVelGrad),
                           doc="the velocity gradient of the last step (Yade's Cell.prevVelGrad)")
    homoDeform = property(lambda s: s._cpp.homoDeform, lambda s, v: setattr(s._cpp, "homoDeform", bool(v)))
    volume = property(lambda s: s._cpp.volume)

    def wrap(self, point) -> Vector3:
        """The point moved into the cell by whole periods."""
        h = np.asarray(self.hSize)
        frac = np.linalg.solve(h, np.asarray(point, dtype=float))
        return Vector3(h @ (frac - np.floor(frac)))
