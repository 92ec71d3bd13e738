"""The Yade names of the components other than the DEM core: found at run time through
``talus.components()``, so that ``dem/`` (which holds this package) depends on no other component
of ours, and a build without one simply lacks its names."""

from __future__ import annotations

import importlib

import talus

# Component -> its package, whose __all__ are Yade's names (FlowEngine, HydroForceEngine, ...).
_PACKAGES = {"flow": "talus.flow", "coupling": "talus.coupling", "fem": "talus.fem"}


def export(namespace: dict) -> list[str]:
    """Put every enabled component's public names into ``namespace``; returns the names."""
    names = []
    enabled = talus.components()
    for component, package in _PACKAGES.items():
        if not enabled.get(component):
            continue
        module = importlib.import_module(package)
        for name in module.__all__:
            namespace[name] = getattr(module, name)
            names.append(name)
    return names

