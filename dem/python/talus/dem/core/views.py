"""The per-body arrays a scene hands out (``positions()``, ``velocities()``, ``forces()``, ...: the
particle exchange interface in Python). They are views of the scene's storage, valid until adding
bodies moves it; the scene keeps weak references to them to warn when that happens."""

from __future__ import annotations

import warnings
import weakref


class ArrayViews:
    """The live views a scene handed out."""

    def __init__(self):
        self._refs: list[weakref.ref] = []

    def track(self, array):
        """Remember ``array`` (a view just handed out) and return it."""
        self._refs = [r for r in self._refs if r() is not None]
        self._refs.append(weakref.ref(array))
        return array

    def before_adding(self, cpp, adding: int = 1) -> None:
        """Before adding ``adding`` bodies to the scene ``cpp``: warn, once for these views, if
        one is still alive and the arrays' storage must move (it would point at freed memory)."""
        if any(r() is not None for r in self._refs) and cpp.bodySpareCapacity() < adding:
            self._refs = []
            warnings.warn("adding bodies moves the per-body arrays: arrays taken before from positions(), "
                          "velocities(), forces(), persistent_forces(), radii(), ... no longer follow the bodies "
                          "(do not use them; take them again after adding)", RuntimeWarning, stacklevel=4)

    def forget(self) -> None:
        """The bodies are gone (O.bodies.clear): the views no longer follow anything."""
        self._refs = []
