"""``yade.wrapper``: Yade's classes (engines, functors, materials, shapes), and ``Omega``."""

from talus.dem import *  # noqa: F401,F403
from talus.dem import O, __all__ as _dem_names


def Omega():
    """Yade's ``Omega()``: the default scene, the same object as ``O``."""
    return O


__all__ = [*_dem_names, "Omega"]
