"""``yade.config``: what this build is (Yade's names; the values describe Talus).

Yade's ``features`` list its optional parts (``'VTK'``, ``'OPENMP'``, ``'QT5'``, ...); Talus lists the
ones it has under the same names, so that a script's ``'X' in yade.config.features`` asks the
right question: ``'QT5'`` is absent (no 3D view), ``'PFVFLOW'`` is there when the flow component
is built. Reals are double precision only (``highPrecision*``).
"""

import os

import talus
from talus import _build_config

version = revision = _build_config.VERSION
prefix = os.path.dirname(os.path.dirname(os.path.abspath(talus.__file__)))
suffix = ""
libDir = os.path.dirname(os.path.abspath(talus.__file__))
confDir = os.path.join(os.path.expanduser("~"), ".config", "talus")


def _features() -> list[str]:
    components = talus.components()
    found = {"VTK": True,  # talus.dem.files.export writes VTK files itself
             "OPENMP": _build_config.FEATURES.get("openmp", (False,))[0],
             "CGAL": components.get("flow", False),
             "PFVFLOW": components.get("flow", False),
             "TWOPHASEFLOW": components.get("flow", False),
             "LINSOLV": components.get("flow", False),
             "MPI": components.get("coupling", False),
             "FEMLIKE": components.get("fem", False),
             "POTENTIAL_PARTICLES": True,
             "POTENTIAL_BLOCKS": _build_config.FEATURES.get("clp", (False,))[0]}
    return [name for name, present in found.items() if present]


features = _features()

# Yade's precision settings for a double build (RealHP<1> is double; there is no other level).
highPrecisionBits = 64
highPrecisionDecimalPlaces = 15
highPrecisionName = "PrecisionDouble"
highPrecisionMpmath = False
