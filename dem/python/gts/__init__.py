"""``gts``: the triangulated surfaces of PyGTS, which Yade's scripts import (``import gts``),
served by Talus's own implementation (talus.dem.gts; no GTS library needed)."""

from talus.dem.gts import *  # noqa: F401,F403
from talus.dem.gts import __all__  # noqa: F401
