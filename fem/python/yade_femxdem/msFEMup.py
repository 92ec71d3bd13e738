"""Drop-in for Yade's FEMxDEM msFEMup (u-p hydromechanical coupling, fixed-stress split): not yet
on Talus. The module imports (so a script fails at MultiScale(...) with this explanation, not
at the import)."""
import _compat  # noqa: F401
from simDEM import *  # noqa: F401,F403

__all__ = ["MultiScale"]


class MultiScale:
    def __init__(self, *args, **kwargs):
        raise NotImplementedError("msFEMup.MultiScale (u-p coupling: pore pressure, getCurrentPore, getCurrentFlux, "
                                  "getEquivalentPorosity, solve(globalIter, solidIter)) is not implemented on Talus "
                                  "yet; msFEM2D and msFEM3D are (docs/fem.md)")
