"""``yade.timing``: per-engine timing (talus.dem.analysis.timing)."""

from talus.dem.analysis.timing import *  # noqa: F401,F403

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.timing")
