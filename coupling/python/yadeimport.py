"""``from yadeimport import *``, the first line of Yade's OpenFOAM examples
(examples/openfoam/*/scriptYade.py), which import Yade into a plain Python process through a
link ``yadeimport.py -> yade-exec``: the names that link gives, Talus's implementation behind
them. With Talus's package on the path (``PYTHONPATH=<build>/python``) the scripts run under
``/usr/bin/python3`` (or ``mpiexec -n 1 /usr/bin/python3 scriptYade.py``) unchanged.

It is the namespace ``yade -x`` (``talus run``) gives a script: Yade's classes and functions
(``FoamCoupling`` and ``initMPI`` among them), ``utils``, ``pack``, ``math``'s names, the module
``yade`` itself, ``os``, ``sys`` and ``time``; ``O`` and ``Omega`` are in builtins."""

import yade as _yade

globals().update(_yade.script_namespace())
_yade.yade_run_defaults()
