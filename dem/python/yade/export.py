"""``yade.export``: ParaView output and text exports (talus.dem.export)."""

from talus.dem.export import *  # noqa: F401,F403
