"""``yade.ymport``: bodies from mesh and sphere files (talus.dem.ymport)."""

from talus.dem.ymport import *  # noqa: F401,F403
