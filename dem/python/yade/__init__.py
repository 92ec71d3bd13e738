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
import sys

from talus.dem import *          # noqa: F401,F403  (the DEM core under Yade's names)
from talus.dem import O, __all__ as _dem_names
from yade import _components, _scope
from yade._gui import *          # noqa: F401,F403  (the 3D view's classes: accepted, inert)
from yade._gui import __all__ as _gui_names
from yade.wrapper import Omega

_component_names = _components.export(globals())

builtins.O = O
builtins.Omega = Omega

# Yade's modules under their names. `from talus.dem import *` above bound pack, geom, ymport and
# timing to talus.dem's modules, which `from yade import pack` would then keep: `import yade.x`
# loads the yade.x namespace module and rebinds the name to it.
import yade.utils as utils          # noqa: E402  (these need O above)
import yade.pack as pack            # noqa: E402
import yade.plot as plot            # noqa: E402
import yade.ymport as ymport        # noqa: E402
import yade.export as export        # noqa: E402
import yade.timing as timing        # noqa: E402
import yade.geom as geom            # noqa: E402
import yade.qt as qt                # noqa: E402
import yade.params as params        # noqa: E402
import yade.config as config        # noqa: E402  (Yade's yade.config and yade.math come with yade)
import yade.math as math            # noqa: E402
import yade.libVersions as libVersions  # noqa: E402
import yade.runtime as runtime      # noqa: E402  (Yade's yade.runtime too: the command-line options)

__all__ = [*_dem_names, *_gui_names, *_component_names, "O", "Omega",
           "utils", "pack", "plot", "ymport", "export", "timing", "geom", "qt", "params"]


__getattr__ = _scope.module_getattr("yade")


def yade_run_defaults() -> None:
    """Where a run started as ``yade -x`` behaves otherwise than Talus's defaults, behave as Yade
    (``talus run`` and ``yadeimport`` call it; the default engines' labels, as any, are names of
    Python's builtins).

    - A contact overlapping beyond O.maxOverlapRatio does not stop the run (Yade has no such
      check) but is reported once as a warning (Scene.overlapStops), in O and in the scenes made
      from now on.
    - An empty O gets Yade's default engines (O.reset() empties them, as in Yade).
    - The other components' own differences (their ``yade_run_defaults``)."""
    from talus.dem.core import scene
    scene.OVERLAP_STOPS = False
    O.overlapStops = False
    _components.run_defaults()
    if not O.engines and not len(O.bodies):
        O.engines = default_engines()


def launcher_options(script: str, args: list, threads: int | None = None):
    """``opts``, the options of Yade's launcher that ``yade -x`` gives a script: a batch run
    without GUI that exits after the script."""
    import argparse
    return argparse.Namespace(version=False, threads=threads, cores=None, updateScripts=None, nice=None,
                              exitAfter=True, verbosity=None, nogui=True, test=False, check=False, checkall=False,
                              performance=False, quickperformance=False, stdperformance=None, script=script,
                              args=[script, *args], impLibraries=None, mpi_mode=False)


def default_engines() -> list:
    """The engines Yade 2023.02a gives its first scene: spheres, facets and boxes with linear
    frictional contacts, the time step from the global stiffness every 10 steps, damping 0.2."""
    return [ForceResetter(),
            InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()], label="collider"),
            InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                            [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()],
                            label="interactionLoop"),
            GlobalStiffnessTimeStepper(timeStepUpdateInterval=10, label="timeStepper"),
            NewtonIntegrator(damping=0.2, label="newton")]


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
    (``os``, ``sys``, ``time``, ``math``, ``numpy``, ``random``, ``itertools``, ``warnings``,
    ``argparse``, ``doctest``, ``execfile``, ``version``, ``features``), as listed by a script under ``yade -x``."""
    import argparse
    import doctest
    import itertools
    import math
    import os
    import random
    import time
    import warnings

    import numpy
    import yade
    namespace = {name: getattr(yade, name) for name in __all__}
    namespace.update({name: getattr(pack, name) for name in pack.__all__})
    namespace.update({name: getattr(utils, name) for name in utils.__all__})
    namespace.update({name: getattr(math, name) for name in dir(math) if not name.startswith("_")})
    namespace.update(yade=yade, utils=utils, pack=pack, geom=geom, os=os, sys=sys, time=time, math=math,
                     numpy=numpy, random=random, itertools=itertools, warnings=warnings, argparse=argparse,
                     doctest=doctest, execfile=execfile)
    namespace["version"] = config.version     # Yade's launcher's global: the program's version
    namespace["features"] = config.features   # and its optional parts (checks test 'PFVFLOW' in features)
    return namespace


plot.add_script_names(script_namespace)   # addAutoData evaluates in Yade's names, as Yade's plot does
