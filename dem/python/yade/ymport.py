"""``yade.ymport``: bodies from mesh and sphere files (talus.dem.files.ymport)."""

from talus.dem.files.ymport import *  # noqa: F401,F403
from talus.dem.core.clumps import importTextClumps as textClumps  # noqa: F401
from talus.dem.files.text_import import textExt, text  # noqa: F401

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.ymport")
