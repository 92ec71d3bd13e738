"""``yade.runtime``: how the program was started (Yade's names). Scripts read ``opts`` for Yade's
command-line options; under ``talus run`` none of Yade's options was given, so each has the
value Yade gives it when absent (``nogui`` and ``exitAfter`` true: a batch run)."""

import argparse
import sys

argv = sys.argv
hasDisplay = False
opts = argparse.Namespace(
    version=False, threads=None, cores=None, updateScripts=None, nice=None, exitAfter=True, verbosity=None,
    nogui=True, test=False, check=False, checkall=False, performance=False, quickperformance=False,
    stdperformance=None, script=sys.argv[0] if sys.argv else "", args=list(sys.argv), impLibraries=None,
    mpi_mode=False)
