"""The Yade names of the components other than the DEM core: found at run time through
``talus.components()``, so that ``dem/`` (which holds this package) depends on no other component
of ours, and a build without one simply lacks its names."""

from __future__ import annotations

import importlib

import talus

# Component -> its package, whose __all__ are Yade's names (FlowEngine, HydroForceEngine, ...).
_PACKAGES = {"flow": "talus.flow", "coupling": "talus.coupling", "fem": "talus.fem"}


def _enabled_packages():
    enabled = talus.components()
    return [importlib.import_module(package) for component, package in _PACKAGES.items() if enabled.get(component)]


def run_defaults() -> None:
    """Call each enabled component's ``yade_run_defaults()`` (if it has one): where its defaults
    differ from Yade's, a script run as Yade's gets Yade's (yade.yade_run_defaults)."""
    for module in _enabled_packages():
        hook = getattr(module, "yade_run_defaults", None)
        if hook is not None:
            hook()


def export(namespace: dict) -> list[str]:
    """Put every enabled component's public names into ``namespace``; returns the names."""
    names = []
    for module in _enabled_packages():
        for name in module.__all__:
            namespace[name] = getattr(module, name)
            names.append(name)
    return names

