"""``yade.export``: ParaView output and text exports (talus.dem.files.export)."""

from talus.dem.files.export import *  # noqa: F401,F403
from talus.dem.core.clumps import exportTextClumps as textClumps  # noqa: F401
from talus.dem.files.text_export import text, text2vtk, text2vtkSection, textExt  # noqa: F401

from yade._scope import module_getattr  # noqa: E402

__getattr__ = module_getattr("yade.export")
