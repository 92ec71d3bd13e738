"""``yade.pack``: packings and predicates (talus.dem.packing.pack, talus.dem.packing.densepack)."""

from talus.dem.packing import densepack
from talus.dem.packing import pack as _pack
from talus.dem.packing.densepack import *  # noqa: F401,F403
from talus.dem.packing.pack import *  # noqa: F401,F403

__all__ = [*_pack.__all__, *densepack.__all__]

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.pack")
