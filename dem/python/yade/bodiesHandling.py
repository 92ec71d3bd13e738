"""``yade.bodiesHandling``: extents of spheres and facets, moving, scaling and copying spheres
(talus.dem.packing.bodies_handling)."""

from talus.dem.packing.bodies_handling import *  # noqa: F401,F403

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.bodiesHandling")
