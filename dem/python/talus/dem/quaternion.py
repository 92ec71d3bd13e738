"""Yade's Quaternion for scripts: ``b.state.ori * v`` rotates a vector, ``q1 * q2`` composes,
``Quaternion(axis, angle)`` or ``Quaternion(w, x, y, z)`` constructs. A tuple (w, x, y, z), so it
compares, indexes and converts like the plain tuples the C++ core returns."""

from __future__ import annotations

import math

import numpy as np


class Quaternion(tuple):
    __slots__ = ()

    def __new__(cls, *args):
        if len(args) == 2:                       # (axis, angle), as Yade
            axis = np.asarray(args[0], dtype=float).reshape(3)
            n = np.linalg.norm(axis)
            if not n > 0:
                raise ValueError(f"Quaternion: the rotation axis must be non-zero, got {args[0]!r}")
            s = math.sin(float(args[1]) / 2) / n
            wxyz = (math.cos(float(args[1]) / 2), *(axis * s))
        else:
            wxyz = args[0] if len(args) == 1 else args
            wxyz = tuple(float(x) for x in wxyz)
            if len(wxyz) != 4:
                raise ValueError(f"Quaternion: expected (w, x, y, z) or (axis, angle), got {args!r}")
        return super().__new__(cls, wxyz)

    w = property(lambda q: q[0])
    x = property(lambda q: q[1])
    y = property(lambda q: q[2])
    z = property(lambda q: q[3])

    def conjugate(self) -> "Quaternion":
        return Quaternion(self[0], -self[1], -self[2], -self[3])

    def norm(self) -> float:
        return math.sqrt(sum(c * c for c in self))

    def toRotationMatrix(self) -> np.ndarray:
        w, x, y, z = np.array(self) / self.norm()
        return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])

    def toAxisAngle(self) -> tuple[np.ndarray, float]:
        w, v = self[0], np.array(self[1:])
        s = np.linalg.norm(v)
        if s == 0:
            return np.array([1.0, 0.0, 0.0]), 0.0
        return v / s, 2 * math.atan2(s, w)

    def __mul__(self, other):
        if isinstance(other, Quaternion):
            w1, x1, y1, z1 = self
            w2, x2, y2, z2 = other
            return Quaternion(w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                              w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)
        v = np.asarray(other, dtype=float)
        if v.shape != (3,):
            return NotImplemented
        return self.toRotationMatrix() @ v

    def __repr__(self):
        return "Quaternion(%r, %r, %r, %r)" % tuple(self)


Quaternion.Identity = Quaternion(1.0, 0.0, 0.0, 0.0)
