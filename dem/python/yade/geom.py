"""``yade.geom``: facet boxes and cylinders (talus.dem.geom)."""

from talus.dem.geom import *  # noqa: F401,F403
