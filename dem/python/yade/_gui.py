"""Yade's OpenGL classes (``Gl1_Sphere``, ``OpenGLRenderer``, ``SnapshotEngine``, ...): the 3D
view's settings and screenshots. A Talus run has no 3D view: they are accepted, do nothing, and
the first one says so once (ParaView reads Talus's VTK output)."""

import sys

from talus.dem.step.engines import PyRunner

_told = False


def notice(what: str):
    global _told
    if not _told:
        _told = True
        print(f"talus: {what} belongs to Yade's 3D view, which a batch run does not have: it does nothing "
              "(write VTK with VTKRecorder and open it in ParaView)", file=sys.stderr)


class _GuiSettings:
    """A renderer or Gl1 functor: any setting is kept and ignored."""

    def __init__(self, *args, **settings):
        notice(type(self).__name__)
        self.__dict__.update(settings)


class SnapshotEngine(PyRunner):
    """Yade's screenshot engine: takes its place in O.engines and does nothing."""

    def __init__(self, iterPeriod: int = 1, label: str = "", **settings):
        notice("SnapshotEngine")
        super().__init__(command=lambda: None, iterPeriod=max(1, int(iterPeriod)), label=label)
        self.settings = settings


_NAMES = ["Gl1_Sphere", "Gl1_Wall", "Gl1_Facet", "Gl1_Box", "Gl1_PotentialParticle", "Gl1_PotentialBlock",
          "Gl1_NormPhys", "Gl1_CpmPhys", "Gl1_L3Geom", "Gl1_L6Geom", "Gl1_ScGeom", "Gl1_Aabb", "Gl1_Node",
          "Gl1_GridConnection", "Gl1_PFacet", "OpenGLRenderer", "GlExtra_AlphaGraph", "GlExtra_OctreeCubes",
          "GlShapeDispatcher", "GlBoundDispatcher", "GlIGeomDispatcher", "GlIPhysDispatcher", "GlStateDispatcher"]
for _name in _NAMES:
    globals()[_name] = type(_name, (_GuiSettings,), {"__doc__": "Yade's 3D view setting: accepted, does nothing."})

__all__ = [*_NAMES, "SnapshotEngine"]
