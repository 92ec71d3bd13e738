"""Which scenes there are: the default scene ``O``, which Yade's helpers act on when given none
(``utils.sphere``'s default material, ``unbalancedForce()``, ``VTKRecorder`` called by hand), and
every live ``Scene``.

This module imports nothing of the DEM, so that any module can ask for ``O`` without importing
the package ``talus.dem`` (which imports every module): ``talus.dem`` makes ``O`` and hands it
over with :func:`set_default_scene`; each ``Scene`` enters itself with :func:`add_scene`.
"""

from __future__ import annotations

import weakref
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene

_default: Scene | None = None
_live: weakref.WeakSet = weakref.WeakSet()


def default_scene() -> Scene:
    """``O``, the default scene."""
    if _default is None:
        raise RuntimeError("the default scene O is made when talus.dem is imported: import talus.dem first")
    return _default


def set_default_scene(scene: Scene) -> None:
    global _default
    _default = scene


def add_scene(scene: Scene) -> None:
    """Count ``scene`` among the live scenes (while it is referenced elsewhere)."""
    _live.add(scene)


def live_scenes() -> list[Scene]:
    """Every scene still referenced, the default one first."""
    others = [s for s in list(_live) if s is not _default]
    return [default_scene(), *others]
