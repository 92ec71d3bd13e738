"""``gts``: the triangulated surfaces of PyGTS, which Yade's scripts import (``import gts``),
served by Talus's own implementation (talus.dem.geometry.gts; no GTS library needed)."""

from talus.dem.geometry.gts import *  # noqa: F401,F403
from talus.dem.geometry.gts import __all__  # noqa: F401
