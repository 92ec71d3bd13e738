"""``yade.timing``: per-engine timing (talus.dem.timing)."""

from talus.dem.timing import *  # noqa: F401,F403

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.timing")
