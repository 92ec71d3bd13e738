"""Yade's footing.py imports ``msFEM`` (a module Yade 2023.02a does not ship: its FIXME asks which
of msFEM2D, msFEM3D, msFEMup it should be); Talus's MultiScale serves 2D and 3D domains alike."""
import _compat  # noqa: F401
from talus.fem.msfem import MultiScale  # noqa: F401
from simDEM import *  # noqa: F401,F403

__all__ = ["MultiScale"]
