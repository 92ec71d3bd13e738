"""``yade.pack``: packings and predicates (talus.dem.pack, talus.dem.densepack)."""

from talus.dem import densepack
from talus.dem import pack as _pack
from talus.dem.densepack import *  # noqa: F401,F403
from talus.dem.pack import *  # noqa: F401,F403

__all__ = [*_pack.__all__, *densepack.__all__]

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.pack")
