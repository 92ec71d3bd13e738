"""Yade's scripting interface, served by Talus.

A script written for Yade imports what it always imported::

    from yade import pack, plot, utils, ymport, export, timing, qt
    from yade.utils import *

and gets Talus's implementation under Yade's names: the package holds namespaces only, the
behaviour lives in ``talus.dem`` (and ``talus.flow``, ``talus.fem``, ``talus.coupling`` when this
build has them). ``talus run script.py`` gives a script the namespace ``yade -x`` gives (see
:func:`script_namespace`).

Importing ``yade`` puts ``O`` and ``Omega`` in Python's builtins, as Yade does, so that modules a
script imports see them too.

This package never shadows a real Yade: Yade's own launcher puts its modules ahead of
``PYTHONPATH``, so ``yade -x`` keeps running Yade with Talus's package on the path.
"""

from __future__ import annotations

import builtins
import math
import sys

from talus.dem import *          # noqa: F401,F403  (the DEM core under Yade's names)
from talus.dem import O, __all__ as _dem_names
from yade import _components
from yade._gui import *          # noqa: F401,F403  (the 3D view's classes: accepted, inert)
from yade._gui import __all__ as _gui_names
from yade.wrapper import Omega

_component_names = _components.export(globals())

builtins.O = O
builtins.Omega = Omega

from yade import utils, pack, plot, ymport, export, timing, geom, qt, params  # noqa: E402  (need O above)

__all__ = [*_dem_names, *_gui_names, *_component_names, "O", "Omega",
           "utils", "pack", "plot", "ymport", "export", "timing", "geom", "qt", "params"]


def execfile(path, globals=None, locals=None):
    """Python 2's execfile, which Yade's launcher gives scripts: run the file in ``globals``
    (default: the caller's)."""
    if globals is None:
        globals = sys._getframe(1).f_globals
    with open(path, encoding="utf-8") as source:
        code = compile(source.read(), path, "exec")
    exec(code, globals, locals if locals is not None else globals)


def script_namespace() -> dict:
    """The globals ``yade -x script.py`` runs a script with: every class and function of
    ``yade``, ``from yade.utils import *``, ``from yade.pack import *``, ``from math import *``,
    the modules ``yade``, ``utils``, ``pack``, ``geom``, and what Yade's launcher itself imports
    (``os``, ``sys``, ``time``, ``execfile``)."""
    import os
    import time
    import yade
    namespace = {name: getattr(yade, name) for name in __all__}
    namespace.update({name: getattr(pack, name) for name in pack.__all__})
    namespace.update({name: getattr(utils, name) for name in utils.__all__})
    namespace.update({name: getattr(math, name) for name in dir(math) if not name.startswith("_")})
    namespace.update(yade=yade, utils=utils, pack=pack, geom=geom, os=os, sys=sys, time=time, execfile=execfile)
    return namespace
