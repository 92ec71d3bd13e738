"""``yade.timing``: per-engine timing (talus.dem.timing)."""

from talus.dem.timing import *  # noqa: F401,F403
