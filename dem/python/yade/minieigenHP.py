"""``yade.minieigenHP``: Yade's value types (minieigen's vectors, matrices and quaternion) at
double precision, the only one Talus has.

Yade serves each precision level ``RealHP<N>`` in a scope ``HPN`` and the first level at the top;
here ``HP1`` holds the same types as the module. The complex-valued types (``Vector3c``,
``Matrix3c``, ...), the dynamic-size ``VectorX``/``MatrixX``, the aligned boxes and the SIMD
``Vector3na`` are not in Talus (an AttributeError names them).
"""

from types import SimpleNamespace

from talus.dem.base.linalg import (Matrix3, Matrix6, Quaternion, Vector2, Vector2i, Vector3, Vector3i, Vector4,
                              Vector6, Vector6i)
from yade import math as _math

__all__ = ["Vector2", "Vector2i", "Vector3", "Vector3i", "Vector4", "Vector6", "Vector6i", "Matrix3", "Matrix6",
           "Quaternion", "HP1", "vectorize"]

vectorize = False  # Yade's build option for SIMD-aligned Vector3na: not in Talus
RealHPConfig = _math.RealHPConfig
HP1 = SimpleNamespace(**{name: globals()[name] for name in __all__ if name not in ("HP1",)})


def __getattr__(name: str):
    raise AttributeError(f"yade.minieigenHP.{name}: not among Talus's value types ({', '.join(__all__[:10])}); "
                         "Yade's complex, dynamic-size, aligned-box and higher-precision (HP2...) types are not "
                         "in Talus")
