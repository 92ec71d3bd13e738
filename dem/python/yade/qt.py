"""``yade.qt``: Yade's 3D view and controller. Talus runs scripts in batch: every call here is
accepted and does nothing, and the first one says so once (ParaView reads Talus's VTK output)."""

import sys

_told = False


def _batch(*_args, **_kwargs):
    global _told
    if not _told:
        _told = True
        print("talus: yade.qt (3D view, controller) is not available in a batch run; the calls do nothing "
              "(write VTK with VTKRecorder and open it in ParaView)", file=sys.stderr)
    return _Inert()


class _Inert:
    """What a GUI call returns: any attribute, call or assignment is accepted and does nothing."""

    def __getattr__(self, _name):
        return _Inert()

    def __setattr__(self, _name, _value):
        pass

    def __call__(self, *_args, **_kwargs):
        return _Inert()


View = Controller = Inspector = Generator = Renderer = _batch

from yade._gui import SnapshotEngine  # noqa: E402,F401  (an engine for O.engines: inert, one notice)


def views() -> list:
    """The open 3D views: none in a batch run."""
    return []
