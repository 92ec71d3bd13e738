"""Yade's value types (minieigen's): ``Vector2, Vector3, Vector4, Vector6`` (and the integer ``Vector2i,
Vector3i, Vector6i``), ``Matrix3, Matrix6`` and ``Quaternion``, returned by the per-body and
scene accessors (``b.state.pos``, ``b.state.ori``, ``O.cell.hSize``, ``getStress()``, ...).

The vectors and matrices are numpy arrays of a fixed shape (float64, int64 for the ``i``
types), so numpy code keeps working on them, with minieigen's constructors, methods and class
attributes on top (``Vector3(1, 2, 3)``, ``Vector3.UnitX``, ``v.norm()``, ``m.inverse()``,
``repr`` ``Vector3(1,2,3)``, numbers in their shortest exact form where Yade 2023 prints 19
digits). ``Vector3()``, ``Matrix3()``... are zero (minieigen leaves them uninitialised). Where
minieigen and numpy read an operator differently and numpy would silently give another answer,
minieigen's meaning is kept:

* ``Matrix * Vector`` and ``Matrix * Matrix`` are matrix products (``m *= m2`` too);
  ``Vector * Matrix`` is, as in minieigen, the same product ``Matrix * Vector``;
* ``abs(v)`` is the norm (``np.abs(v)`` and ``v.abs()`` stay element-wise);
* ``Quaternion * Vector3`` rotates and ``Quaternion * Quaternion`` composes.

Everything else is numpy's: ``v * w`` and ``v / w`` are element-wise, ``v + 1`` broadcasts,
``v[-1]`` and slices work (minieigen refuses those). A result whose shape is no longer the
type's (a slice, a reduction along an axis, ``np.outer``, ``np.stack``) is a plain numpy array;
one row of a matrix (``m[0]``, iterating over ``m``) is a vector, as in minieigen.

Equality. minieigen's ``==`` answers one bool, numpy's compares element by element (and
``if v == w:`` then raises). ``==`` and ``!=`` between a value type and another value type, a
list or a tuple give one bool, as in minieigen (False when the shapes differ); against a plain
numpy array or a number they compare element-wise, as numpy does (minieigen itself hands a
numpy array to numpy's element-wise comparison; against a number it answers False, Talus gives
numpy's array so that ``v == 0`` keeps its numpy meaning). Value types are not hashable.

Quaternion follows minieigen: built from ``(axis, angle)``, ``(angle, axis)``, ``(w, x, y, z)``,
a rotation Matrix3, two vectors (the rotation from one to the other) or another Quaternion.
With an axis that is not of unit length, minieigen normalises (cos a/2, sin a/2 axis), which
turns by another angle than ``a``: Talus does the same, so that a script gets Yade's
orientation (give a unit axis for the rotation by ``a``). It is
indexed ``q[0..3] = x, y, z, w`` (Eigen's storage order, so ``list(q)`` and ``np.array(q)`` are
``[x, y, z, w]``); ``repr`` in axis-angle form. It also has ``.w .x .y .z`` (minieigen has not)
and ``Quaternion()`` is the identity (minieigen leaves it uninitialised). The C++ core hands
orientations as (w, x, y, z) tuples: build them with ``Quaternion(*wxyz)``; a single sequence
is refused, since its order would be ambiguous.
"""

from __future__ import annotations

import math
from numbers import Number

import numpy as np

__all__ = ["Vector2", "Vector2i", "Vector3", "Vector3i", "Vector4", "Vector6", "Vector6i", "Matrix3", "Matrix6", "Quaternion"]

# Eigen's default precision for isApprox with doubles.
_DEFAULT_PRECISION = 1e-12


class _Constant:
    """A class attribute (``Vector3.Zero``) built afresh at each access, as in minieigen, so
    that changing the value one got (``z = Vector3.Zero; z += 1``) cannot change the constant."""

    def __init__(self, make):
        self._make = make

    def __get__(self, obj, cls):
        return self._make(cls)


def _number(x) -> str:
    """A component as minieigen prints it: shortest round-trip form, integral values without
    ``.0`` (``1``, ``0.5``, ``-0``, ``1e+20``)."""
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    text = repr(float(x))
    return text[:-2] if text.endswith(".0") else text


def _fit(x):
    """``x`` as the value type its shape and dtype still make it, else as a plain array (a
    Vector3 reshaped, sliced or reduced along an axis must not stay a Vector3); recurses into
    the tuples numpy functions return (named tuples keep their type)."""
    if isinstance(x, _Dense):
        cls = type(x)
        if x.shape == cls._shape and x.dtype == cls._dtype:
            return x
        # Same shape, other dtype (an integer vector divided, a float vector cast to int): the
        # sibling type, if any.
        sibling = _TYPES.get((x.shape, x.dtype.kind)) if x.shape == cls._shape else None
        return x.view(sibling) if sibling else x.view(np.ndarray)
    if isinstance(x, tuple):
        items = [_fit(i) for i in x]
        return type(x)._make(items) if hasattr(type(x), "_make") else tuple(items)
    if isinstance(x, list):
        return [_fit(i) for i in x]
    return x


def _typed(array) -> np.ndarray:
    """The value type of ``array``'s shape and dtype (a matrix product, a cross product...),
    else a plain array."""
    array = np.asarray(array)
    cls = _TYPES.get((array.shape, array.dtype.kind))
    return array.view(cls) if cls else array


def as_value(values) -> np.ndarray:
    """A copy of ``values`` as the value type of its shape (a 3-vector as a Vector3, a 3x3 as a
    Matrix3...), or as a plain array if none has that shape: for accessors that hand the user
    whatever the C++ core holds."""
    return _typed(np.array(values))


def _refit_methods(cls, names):
    """Wrap numpy methods that can change the shape (``reshape``, ``ravel``...) so that their
    results go through ``_fit``."""
    for name in names:
        method = getattr(np.ndarray, name)

        def refit(self, *args, _method=method, **kwargs):
            return _fit(_method(self, *args, **kwargs))
        refit.__name__, refit.__doc__ = name, method.__doc__
        setattr(cls, name, refit)


_ndarray_getitem = np.ndarray.__getitem__


class _Dense(np.ndarray):
    """What the vectors and matrices share: construction, printing, equality, the numpy
    plumbing that keeps the type only while the shape and dtype are the type's."""

    _shape: tuple = ()
    _dtype = np.dtype(np.float64)

    def __new__(cls, *args):
        return cls._from_array(cls._parse(args))

    @classmethod
    def _parse(cls, args):
        """The components from the constructor's arguments (each type adds its own forms)."""
        if not args:
            return np.zeros(cls._shape)
        if len(args) == math.prod(cls._shape) and all(isinstance(a, (Number, np.number)) for a in args):
            return args
        if len(args) == 1:
            return args[0]
        raise TypeError(f"{cls.__name__}: cannot build from {len(args)} arguments {args!r}")

    @classmethod
    def _from_array(cls, values):
        if isinstance(values, np.ndarray) and values.shape == cls._shape and values.dtype == cls._dtype:
            return values.copy().view(cls)   # the common case (a row of the scene's arrays), quick
        try:
            array = np.array(values, dtype=float if cls._dtype.kind == "f" else None)
        except (TypeError, ValueError) as e:
            raise TypeError(f"{cls.__name__}: cannot build from {values!r} ({e})") from None
        if array.size == math.prod(cls._shape) and array.shape != cls._shape and array.ndim == 1:
            array = array.reshape(cls._shape)   # Matrix3 from a flat sequence of 9 numbers
        if array.shape != cls._shape or array.dtype.kind not in "biuf":
            raise TypeError(f"{cls.__name__}: expected {'x'.join(map(str, cls._shape))} numbers, got {values!r}")
        if cls._dtype.kind == "i" and array.dtype.kind == "f":
            if not np.all(array == np.round(array)):
                raise TypeError(f"{cls.__name__}: components must be integers, got {values!r}")
        return array.astype(cls._dtype, copy=False).view(cls)

    # -- numpy plumbing ---------------------------------------------------------------------
    def __array_wrap__(self, out, context=None, return_scalar=False):
        # Ufunc results: a number for a full reduction; the type only for the type's shape.
        if out.ndim == 0:
            return out[()]
        return _fit(out.view(type(self)))

    def __array_function__(self, func, types, args, kwargs):
        return _fit(super().__array_function__(func, types, args, kwargs))

    def __getitem__(self, key):
        item = _ndarray_getitem(self, key)
        return _fit(item) if isinstance(item, np.ndarray) else item     # a component as it is: quick

    # -- printing and comparison ------------------------------------------------------------
    def __repr__(self):
        if self.shape != self._shape:   # a view numpy made without asking (kept printable)
            return repr(self.view(np.ndarray))
        return f"{type(self).__name__}({self._components()})"

    __str__ = __repr__

    def __eq__(self, other):
        if isinstance(other, (_Dense, list, tuple)):
            try:
                other = np.asarray(other, dtype=float)
            except (TypeError, ValueError):
                return np.False_
            return np.bool_(other.shape == self.shape and np.array_equal(self.view(np.ndarray), other))
        return super().__eq__(other)

    def __ne__(self, other):
        if isinstance(other, (_Dense, list, tuple)):
            return ~self.__eq__(other)
        return super().__ne__(other)

    __hash__ = None

    # -- minieigen's methods ----------------------------------------------------------------
    Zero = _Constant(lambda cls: np.zeros(cls._shape, cls._dtype).view(cls))
    Ones = _Constant(lambda cls: np.ones(cls._shape, cls._dtype).view(cls))

    @classmethod
    def Random(cls):
        """Components uniform in [-1, 1], as Eigen's Random (integer types: -10..10)."""
        rng = np.random.default_rng()
        if cls._dtype.kind == "i":
            return rng.integers(-10, 11, cls._shape).astype(cls._dtype).view(cls)
        return rng.uniform(-1, 1, cls._shape).view(cls)

    def maxCoeff(self):
        return self.max()

    def minCoeff(self):
        return self.min()

    def maxAbsCoeff(self):
        return np.abs(self).max()

    def abs(self):
        """The absolute value of each component (the norm is ``abs(v)``, as minieigen)."""
        return np.abs(self)

    def rows(self) -> int:
        return self._shape[0]

    def cols(self) -> int:
        return self._shape[1] if len(self._shape) > 1 else 1

    def isApprox(self, other, prec: float = _DEFAULT_PRECISION) -> bool:
        """Eigen's relative comparison: |self - other| <= prec min(|self|, |other|)."""
        a, b = self.view(np.ndarray), np.asarray(other, dtype=float)
        return bool(np.sum((a - b) ** 2) <= prec * prec * min(np.sum(a * a), np.sum(b * b)))


# numpy's methods that may change the shape; with no argument sum, prod, mean are minieigen's.
_refit_methods(_Dense, ("reshape", "ravel", "flatten", "squeeze", "swapaxes", "take", "repeat", "compress", "astype",
                        "dot", "argsort", "cumsum", "cumprod", "max", "min", "sum", "prod", "mean"))


class _Real(_Dense):
    """Norms, for the floating-point types."""

    def norm(self) -> float:
        return math.sqrt(self.squaredNorm())

    def squaredNorm(self) -> float:
        values = self.view(np.ndarray)
        if values.size >= 8:
            return float(np.sum(values ** 2))
        # numpy adds fewer than eight terms one after the other: the same sum, without the
        # overheads of its calls (scripts take norms body by body, a tenth of the time)
        total = 0.0
        for x in values.ravel().tolist():
            total += x * x
        return total

    def __abs__(self):
        return self.norm()

    def normalized(self):
        return self / self.norm()

    def normalize(self):
        """Scale to unit norm, in place."""
        self /= self.norm()

    def pruned(self, absTol: float = 1e-6):
        """Components of magnitude below ``absTol`` set to zero (a copy)."""
        out = self.copy()
        out[np.abs(out.view(np.ndarray)) < absTol] = 0
        return out


class _Vector(_Dense):
    """Vectors: unit vectors, dot, outer and diagonal products."""

    Identity = _Constant(lambda cls: cls.Unit(0))   # Eigen's Identity of a vector: the first unit vector

    @classmethod
    def Unit(cls, i: int):
        if not 0 <= i < cls._shape[0]:
            raise IndexError(f"{cls.__name__}.Unit: index {i} out of range 0..{cls._shape[0] - 1}")
        out = np.zeros(cls._shape, cls._dtype)
        out[i] = 1
        return out.view(cls)

    UnitX = _Constant(lambda cls: cls.Unit(0))
    UnitY = _Constant(lambda cls: cls.Unit(1))

    def __mul__(self, other):
        # Vector * Matrix is the matrix's product (see Matrix.__rmul__), as in minieigen.
        if isinstance(other, _Matrix):
            return NotImplemented
        return super().__mul__(other)

    def _components(self) -> str:
        # minieigen groups the components of 6-vectors by three: Vector6(1,2,3, 4,5,6)
        parts = [_number(x) for x in self.view(np.ndarray)]
        return ", ".join(",".join(parts[i:i + 3]) for i in range(0, len(parts), 3))

    def outer(self, other):
        """self other^T, a matrix."""
        return _typed(np.outer(self.view(np.ndarray), np.asarray(other)))

    def asDiagonal(self):
        return _typed(np.diag(self.view(np.ndarray)))


class _Vector3Methods(_Vector):
    """The 3-vectors' cross product and 2D projections."""

    UnitZ = _Constant(lambda cls: cls.Unit(2))

    def cross(self, other):
        return _typed(np.cross(self.view(np.ndarray), np.asarray(other)))

    def _pair(self, i, j):
        return _typed(self.view(np.ndarray)[[i, j]])

    xy = lambda self: self._pair(0, 1)
    xz = lambda self: self._pair(0, 2)
    yx = lambda self: self._pair(1, 0)
    yz = lambda self: self._pair(1, 2)
    zx = lambda self: self._pair(2, 0)
    zy = lambda self: self._pair(2, 1)


class _Vector6Methods(_Vector):
    """Vector6(Vector3, Vector3) and its halves."""

    @classmethod
    def _parse(cls, args):
        if len(args) == 2:
            return np.concatenate([np.asarray(a).reshape(3) for a in args])
        return super()._parse(args)

    head = lambda self: _typed(self.view(np.ndarray)[:3])
    tail = lambda self: _typed(self.view(np.ndarray)[3:])


class Vector2(_Vector, _Real):
    _shape = (2,)


class Vector2i(_Vector):
    _shape, _dtype = (2,), np.dtype(np.int64)


class Vector3(_Vector3Methods, _Real):
    _shape = (3,)


class Vector3i(_Vector3Methods):
    _shape, _dtype = (3,), np.dtype(np.int64)


class Vector4(_Vector, _Real):
    # Not among the types accessors make of a bare 4-array (_TYPES): orientations come from the
    # core as (w, x, y, z) arrays, which must not turn into vectors.
    _shape = (4,)


class Vector6(_Vector6Methods, _Real):
    _shape = (6,)


class Vector6i(_Vector6Methods):
    _shape, _dtype = (6,), np.dtype(np.int64)


class _Matrix(_Real):
    """Square matrices: matrix products, rows and columns, decompositions."""

    Identity = _Constant(lambda cls: np.eye(cls._shape[0]).view(cls))

    @classmethod
    def _parse(cls, args):
        n = cls._shape[0]
        if len(args) == n and all(np.ndim(a) == 1 for a in args):    # n rows
            return [np.asarray(a, dtype=float).reshape(n) for a in args]
        if len(args) == 1 and isinstance(args[0], Quaternion) and n == 3:
            return args[0].toRotationMatrix()
        if len(args) == 1 and np.ndim(args[0]) == 1 and len(args[0]) == n:
            return np.diag(np.asarray(args[0], dtype=float))   # the diagonal, as minieigen
        return super()._parse(args)

    # Matrix products where minieigen has them (numpy's * would be element-wise).
    def __mul__(self, other):
        if isinstance(other, (Number, np.number)) or isinstance(other, np.ndarray) and other.ndim == 0:
            return super().__mul__(other)
        try:
            other = np.asarray(other, dtype=float)
        except (TypeError, ValueError):
            return NotImplemented
        return _typed(self.view(np.ndarray) @ other)

    def __rmul__(self, other):
        if isinstance(other, (Number, np.number)) or isinstance(other, np.ndarray) and other.ndim == 0:
            return super().__rmul__(other)
        other = np.asarray(other, dtype=float)
        if other.ndim == 1:      # minieigen: Vector * Matrix is Matrix * Vector
            return self * other
        return _typed(other @ self.view(np.ndarray))

    def __imul__(self, other):
        if isinstance(other, (Number, np.number)):
            return super().__imul__(other)
        self[...] = self * other
        return self

    def __iter__(self):
        return (self[i] for i in range(len(self)))

    def __getitem__(self, key):
        item = super().__getitem__(key)
        # One row is a vector (a view), as minieigen's m[i].
        if isinstance(key, (int, np.integer)):
            return item.view(_TYPES[(item.shape, item.dtype.kind)])
        return item

    def _components(self) -> str:
        return ", ".join(",".join(_number(x) for x in row) for row in self.view(np.ndarray))

    def row(self, i: int):
        return _typed(self.view(np.ndarray)[i].copy())

    def col(self, i: int):
        return _typed(self.view(np.ndarray)[:, i].copy())

    def diagonal(self, *args, **kwargs):
        if args or kwargs:          # numpy's np.diagonal(m, offset, ...)
            return np.ndarray.diagonal(self.view(np.ndarray), *args, **kwargs)
        return _typed(np.diag(self.view(np.ndarray)).copy())

    def determinant(self) -> float:
        return float(np.linalg.det(self.view(np.ndarray)))

    def inverse(self):
        return _typed(np.linalg.inv(self.view(np.ndarray)))

    def spectralDecomposition(self):
        """(eigenvectors as columns, eigenvalues ascending) of the symmetric matrix, as
        minieigen's (only the lower triangle is read, as Eigen's self-adjoint solver)."""
        values, vectors = np.linalg.eigh(self.view(np.ndarray), UPLO="L")
        return _typed(vectors), _typed(values)

    selfAdjointEigenDecomposition = spectralDecomposition

    def svd(self):
        """(U, S, V) with self = U S V^T, S diagonal (singular values decreasing)."""
        u, s, vt = np.linalg.svd(self.view(np.ndarray))
        return _typed(u), _typed(np.diag(s)), _typed(vt.T)

    def polarDecomposition(self):
        """(U, P): U orthogonal, P symmetric positive semi-definite, self = U P."""
        u, s, v = self.svd()
        return u * v.transpose(), v * s * v.transpose()


class Matrix3(_Matrix):
    """3x3 matrix: ``Matrix3(9 numbers row by row)``, ``Matrix3(row, row, row)``,
    ``Matrix3(quaternion)``, ``Matrix3(diagonal)``, ``Matrix3(nested sequence)``."""
    _shape = (3, 3)

    # Eigen computes a 3x3 determinant and inverse from cofactors (exact for small integers,
    # where an LU factorisation rounds): so does Talus, to give Yade's numbers.
    def _cofactors(self) -> np.ndarray:
        a = self.view(np.ndarray)
        return np.array([[a[(i + 1) % 3, (j + 1) % 3] * a[(i + 2) % 3, (j + 2) % 3]
                          - a[(i + 1) % 3, (j + 2) % 3] * a[(i + 2) % 3, (j + 1) % 3] for j in range(3)]
                         for i in range(3)])

    def determinant(self) -> float:
        return float(self.view(np.ndarray)[0] @ self._cofactors()[0])

    def inverse(self):
        cof = self._cofactors()
        return Matrix3(cof.T / (self.view(np.ndarray)[0] @ cof[0]))


class Matrix6(_Matrix):
    """6x6 matrix: ``Matrix6(6 rows)``, ``Matrix6(ul, ur, ll, lr)`` from four Matrix3 blocks,
    ``Matrix6(diagonal)``, ``Matrix6(nested sequence)``."""
    _shape = (6, 6)

    @classmethod
    def _parse(cls, args):
        if len(args) == 4:
            return np.block([[np.asarray(args[0]), np.asarray(args[1])], [np.asarray(args[2]), np.asarray(args[3])]])
        return super()._parse(args)

    def _components(self) -> str:
        rows = ("(" + ",".join(_number(x) for x in row) + ")" for row in self.view(np.ndarray))
        return "\n\t" + ",\n\t".join(rows) + "\n"

    ul = lambda self: _typed(self.view(np.ndarray)[:3, :3].copy())
    ur = lambda self: _typed(self.view(np.ndarray)[:3, 3:].copy())
    ll = lambda self: _typed(self.view(np.ndarray)[3:, :3].copy())
    lr = lambda self: _typed(self.view(np.ndarray)[3:, 3:].copy())


# The value type of each (shape, dtype kind), for results of minieigen operations.
_TYPES = {(cls._shape, cls._dtype.kind): cls for cls in (Vector2, Vector2i, Vector3, Vector3i, Vector6, Vector6i,
                                                          Matrix3, Matrix6)}


class Quaternion:
    """A rotation (Eigen's quaternion): see the module's docstring for the constructors and the
    indexing. ``q * v`` rotates a vector, ``q1 * q2`` composes (q2 first)."""

    __slots__ = ("w", "x", "y", "z")
    __array_ufunc__ = None   # numpy must not turn ``v * q`` into element-wise arithmetic
    __hash__ = None

    def __init__(self, *args, axis=None, angle=None):
        if axis is not None or angle is not None:            # minieigen's keywords
            if args or axis is None or angle is None:
                raise TypeError("Quaternion: give both axis= and angle=, and nothing else")
            args = (axis, angle)
        if len(args) == 1 and isinstance(args[0], tuple) and len(args[0]) == 2:
            args = args[0]                                     # ((axis, angle)) or ((angle, axis))
        if not args:
            w, x, y, z = 1.0, 0.0, 0.0, 0.0
        elif len(args) == 4:
            w, x, y, z = (float(a) for a in args)
        elif len(args) == 1 and isinstance(args[0], Quaternion):
            q = args[0]
            w, x, y, z = q.w, q.x, q.y, q.z
        elif len(args) == 1 and np.shape(args[0]) == (3, 3):
            w, x, y, z = _from_rotation_matrix(np.asarray(args[0], dtype=float))
        elif len(args) == 2 and np.ndim(args[1]) == 0:       # (axis, angle)
            w, x, y, z = _from_axis_angle(args[0], args[1])
        elif len(args) == 2 and np.ndim(args[0]) == 0:       # (angle, axis)
            w, x, y, z = _from_axis_angle(args[1], args[0])
        elif len(args) == 2:                                  # the rotation taking u to v
            w, x, y, z = _from_two_vectors(args[0], args[1])
        else:
            raise TypeError(f"Quaternion: expected (axis, angle), (angle, axis), (w, x, y, z), a rotation "
                            f"matrix, two vectors or a Quaternion, got {args!r} (a (w, x, y, z) sequence: "
                            f"Quaternion(*wxyz))")
        self.w, self.x, self.y, self.z = w, x, y, z

    Identity = _Constant(lambda cls: cls())

    # -- sequence of (x, y, z, w), as minieigen ---------------------------------------------
    def _xyzw(self):
        return (self.x, self.y, self.z, self.w)

    def __len__(self):
        return 4

    def __getitem__(self, i):
        return self._xyzw()[i]

    def __setitem__(self, i, value):
        setattr(self, "xyzw"[range(4)[i]], float(value))

    def __iter__(self):
        return iter(self._xyzw())

    def __array__(self, dtype=None):
        return np.array(self._xyzw(), dtype=dtype)

    def __reduce__(self):
        return (Quaternion, (self.w, self.x, self.y, self.z))

    def __eq__(self, other):
        if not isinstance(other, Quaternion):
            return NotImplemented
        return self._xyzw() == other._xyzw()

    def __ne__(self, other):
        equal = self.__eq__(other)
        return equal if equal is NotImplemented else not equal

    def __repr__(self):
        axis, angle = self.toAxisAngle()
        return f"Quaternion(({_number(axis[0])},{_number(axis[1])},{_number(axis[2])}),{_number(angle)})"

    __str__ = __repr__

    # -- algebra ----------------------------------------------------------------------------
    def __mul__(self, other):
        if isinstance(other, Quaternion):
            w1, x1, y1, z1 = self.w, self.x, self.y, self.z
            w2, x2, y2, z2 = other.w, other.x, other.y, other.z
            return Quaternion(w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                              w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)
        try:
            v = np.asarray(other, dtype=float)
        except (TypeError, ValueError):
            return NotImplemented
        if v.shape != (3,):
            return NotImplemented
        return self.Rotate(v)

    def __imul__(self, other):
        if not isinstance(other, Quaternion):
            return NotImplemented
        product = self * other
        self.w, self.x, self.y, self.z = product.w, product.x, product.y, product.z
        return self

    def Rotate(self, v):
        """``v`` rotated (Eigen's formula: exact for a unit quaternion, as orientations are)."""
        v = np.asarray(v, dtype=float)
        u = np.array([self.x, self.y, self.z])
        t = 2 * np.cross(u, v)
        return Vector3(v + self.w * t + np.cross(u, t))

    def norm(self) -> float:
        return math.sqrt(self.w * self.w + self.x * self.x + self.y * self.y + self.z * self.z)

    __abs__ = norm

    def normalize(self):
        """Scale to unit norm, in place."""
        n = self.norm()
        self.w, self.x, self.y, self.z = self.w / n, self.x / n, self.y / n, self.z / n

    def normalized(self) -> "Quaternion":
        q = Quaternion(self)
        q.normalize()
        return q

    def conjugate(self) -> "Quaternion":
        return Quaternion(self.w, -self.x, -self.y, -self.z)

    def inverse(self) -> "Quaternion":
        n2 = self.norm() ** 2
        if n2 == 0:
            return Quaternion(0.0, 0.0, 0.0, 0.0)
        return Quaternion(self.w / n2, -self.x / n2, -self.y / n2, -self.z / n2)

    def toRotationMatrix(self) -> Matrix3:
        # Eigen's formula, which assumes a unit quaternion (it does not normalise).
        w, x, y, z = self.w, self.x, self.y, self.z
        return Matrix3(1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                       2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                       2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y))

    def toAxisAngle(self) -> tuple[Vector3, float]:
        """(unit axis, angle in [0, pi]); the identity gives ((1, 0, 0), 0), as Eigen."""
        n = math.sqrt(self.x * self.x + self.y * self.y + self.z * self.z)
        if n == 0:
            return Vector3(1, 0, 0), 0.0
        angle = 2 * math.atan2(n, abs(self.w))
        if self.w < 0:
            n = -n
        return Vector3(self.x / n, self.y / n, self.z / n), angle

    def toAngleAxis(self) -> tuple[float, Vector3]:
        axis, angle = self.toAxisAngle()
        return angle, axis

    def toRotationVector(self) -> Vector3:
        axis, angle = self.toAxisAngle()
        return axis * angle

    def angularDistance(self, other: "Quaternion") -> float:
        """The angle of the rotation from one orientation to the other."""
        d = self * other.conjugate()
        return 2 * math.atan2(math.sqrt(d.x * d.x + d.y * d.y + d.z * d.z), abs(d.w))

    def slerp(self, t: float, other: "Quaternion") -> "Quaternion":
        """Spherical interpolation from self (t = 0) to other (t = 1), along the shorter arc."""
        d = self.w * other.w + self.x * other.x + self.y * other.y + self.z * other.z
        if abs(d) >= 1 - np.finfo(float).eps:     # nearly the same rotation: linear
            s0, s1 = 1 - t, t
        else:
            theta = math.acos(abs(d))
            s0, s1 = math.sin((1 - t) * theta) / math.sin(theta), math.sin(t * theta) / math.sin(theta)
        if d < 0:
            s1 = -s1
        return Quaternion(s0 * self.w + s1 * other.w, s0 * self.x + s1 * other.x, s0 * self.y + s1 * other.y,
                          s0 * self.z + s1 * other.z)

    def setFromTwoVectors(self, u, v):
        """Set to the rotation taking direction ``u`` to direction ``v``, in place."""
        self.w, self.x, self.y, self.z = _from_two_vectors(u, v)


def _from_axis_angle(axis, angle) -> tuple[float, float, float, float]:
    # As Yade's minieigen: (cos a/2, sin a/2 axis) with the axis as given, then normalised. For a
    # unit axis that is the rotation by ``angle``; a longer axis turns by more (Yade's scripts
    # that give one get Yade's orientation).
    axis = np.asarray(axis, dtype=float).reshape(3)
    if not np.linalg.norm(axis) > 0:
        raise ValueError(f"Quaternion: the rotation axis must be non-zero, got {axis!r}")
    s = math.sin(float(angle) / 2)
    wxyz = np.array([math.cos(float(angle) / 2), *(axis * s)])
    return tuple(float(c) for c in wxyz / np.linalg.norm(wxyz))


def _from_rotation_matrix(m: np.ndarray) -> tuple[float, float, float, float]:
    # Shepperd's method: take the square root of the largest of w^2, x^2, y^2, z^2 (well away
    # from zero), the other components from sums and differences of off-diagonal terms.
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0:
        t = math.sqrt(trace + 1)
        w, t = 0.5 * t, 0.5 / t
        return w, (m[2, 1] - m[1, 2]) * t, (m[0, 2] - m[2, 0]) * t, (m[1, 0] - m[0, 1]) * t
    i = int(np.argmax(np.diag(m)))
    j, k = (i + 1) % 3, (i + 2) % 3
    t = math.sqrt(m[i, i] - m[j, j] - m[k, k] + 1)
    xyz = [0.0, 0.0, 0.0]
    xyz[i], t = 0.5 * t, 0.5 / t
    xyz[j], xyz[k] = (m[j, i] + m[i, j]) * t, (m[k, i] + m[i, k]) * t
    return ((m[k, j] - m[j, k]) * t, *xyz)


def _from_two_vectors(u, v) -> tuple[float, float, float, float]:
    u = np.asarray(u, dtype=float).reshape(3)
    v = np.asarray(v, dtype=float).reshape(3)
    u, v = u / np.linalg.norm(u), v / np.linalg.norm(v)
    c = float(u @ v)
    if c < -1 + np.finfo(float).eps:
        # Opposite directions: half a turn about any axis normal to both (the null direction of
        # the 2x3 matrix of the two).
        axis = np.linalg.svd(np.vstack([u, v]))[2][2]
        w2 = (1 + max(c, -1)) / 2
        return (math.sqrt(w2), *(axis * math.sqrt(1 - w2)))
    s = math.sqrt((1 + c) * 2)
    return (s / 2, *(np.cross(u, v) / s))
