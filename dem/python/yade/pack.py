"""``yade.pack``: packings and predicates (talus.dem.pack)."""

from talus.dem.pack import *  # noqa: F401,F403
from talus.dem.pack import __all__  # noqa: F401

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.pack")
