"""``yade.math``: Yade's math module for a double build, the only precision Talus has.

Yade's ``yade.math`` serves its high-precision library: the functions of Python's ``math`` at
``Real`` precision, and the scopes ``HP1``, ``HP2``, ... of higher ``RealHP<N>`` levels. In Talus
``Real`` is ``float`` (``RealHP<1>``, double) and there is no other level: the functions are
Python's, and the configuration queries (``RealHPConfig``, ``needsMpmathAtN``, ``getDigits10``)
answer for double. The higher levels, their converters and C++ self-tests are outside Talus's
scope (an AttributeError says so).
"""

import math
import sys
from math import *  # noqa: F401,F403  (Real is float: Python's functions are Real's functions)

Real = float


def _level(N: int) -> int:
    if N != 1:
        raise ValueError(f"yade.math: RealHP<{N}> does not exist in Talus, whose only precision is "
                         "double (RealHP<1>)")
    return N


def getDigits10(N: int = 1) -> int:
    """Decimal digits of ``RealHP<N>``: 15 for double."""
    return 15 if _level(N) else 0


def getDigits2(N: int = 1) -> int:
    """Bits of the significand of ``RealHP<N>``: 53 for double."""
    return 53 if _level(N) else 0


def needsMpmathAtN(N: int) -> bool:
    """Whether ``RealHP<N>`` needs mpmath in Python: never for double."""
    return not _level(N)


def isThisSystemLittleEndian() -> bool:
    return sys.byteorder == "little"


def getRealHPCppDigits10() -> tuple:
    return (15,)


getRealHPPythonDigits10 = getRealHPCppDigits10


class RealHPConfig:
    """The precision levels of this build: only ``RealHP<1>`` (double)."""
    extraStringDigits10 = 4          # the digits Yade adds when it prints a Real as a string
    isEnabledRealHP = False
    isFloat128Present = False
    isFloat128Broken = False
    workaroundSlowBoostBinFloat = 1
    getDigits10 = staticmethod(getDigits10)
    getDigits2 = staticmethod(getDigits2)

    @staticmethod
    def getSupportedByMinieigen() -> tuple:
        return (1,)

    getSupportedByEigenCgal = getSupportedByMinieigen


def radiansHP1(degrees: float) -> float:
    """Yade's radians at RealHP<1> (double): Python's."""
    return math.radians(degrees)


def degreesHP1(radians: float) -> float:
    """Yade's degrees at RealHP<1> (double): Python's."""
    return math.degrees(radians)


def toHP1(value) -> float:
    """A number at RealHP<1>: a float."""
    return float(value)


def __getattr__(name: str):
    raise AttributeError(f"yade.math.{name}: not in Talus's yade.math, which has Python's math functions and the "
                         "double-precision configuration only; Yade's higher RealHP<N> levels and their tools are "
                         "outside Talus's scope (Talus computes in double)")
