"""Drop-in for Yade's FEMxDEM msFEM3D, on Talus's Gauss-point RVEs (see msFEM2D.py)."""
import _compat  # noqa: F401
from talus.fem.msfem import MultiScale  # noqa: F401
from simDEM import *  # noqa: F401,F403

__all__ = ["MultiScale"]
