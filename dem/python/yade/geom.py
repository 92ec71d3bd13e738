"""``yade.geom``: facet boxes and cylinders (talus.dem.geometry.geom)."""

from talus.dem.geometry.geom import *  # noqa: F401,F403

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.geom")
