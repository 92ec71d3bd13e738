"""The shape kinds the Python layer knows, each registered by its own module (talus.dem.geometry.shapes:
Sphere, Wall, Facet, Box, Clump; talus.dem.geometry.blocks: PotentialBlock; talus.dem.geometry.particles:
PotentialParticle) with what the rest of the package needs of it. ``O.bodies.append``, ``b.shape``
and the scene's engine setup look a kind up here by its name (the C++ shape kind) instead of
importing every shape module, so a new shape adds its module and one ``register`` call.

``talus.dem`` imports every shape module, so all kinds are registered before any scene exists.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable

if TYPE_CHECKING:
    from talus.dem.core.bodies import BodySpec
    from talus.dem.core.scene import Scene


@dataclass(frozen=True)
class ShapeKind:
    """What the package does with bodies of one shape kind.

    ``add(scene, spec, material)``: put a body made by the kind's constructor (``sphere``,
    ``potentialBlock``, ...) into the scene, return its id; None for a kind made otherwise
    (clumps: ``O.bodies.clump``).
    ``view(scene, id)``: the shape object ``b.shape`` gives for body ``id``.
    ``configure(cpp, engines)``: set the kind's contact settings in the scene's C++ side from
    its engine list (the geometry functors' options), each time ``O.engines`` is set; None for
    a kind without such settings.
    """
    name: str
    view: Callable[[Scene, int], object]
    add: Callable[[Scene, BodySpec, int], int] | None = None
    configure: Callable[[object, list], None] | None = None


_KINDS: dict[str, ShapeKind] = {}


def register(kind: ShapeKind) -> None:
    if kind.name in _KINDS:
        raise ValueError(f"shape kind {kind.name!r} is registered twice")
    _KINDS[kind.name] = kind


def shape_kind(name: str) -> ShapeKind:
    """The registered kind ``name``; a KeyError naming the known kinds otherwise."""
    try:
        return _KINDS[name]
    except KeyError:
        raise KeyError(f"no shape kind {name!r} is registered (known: {', '.join(_KINDS)})") from None


def shape_kinds() -> list[ShapeKind]:
    """Every registered kind, in the order they were registered."""
    return list(_KINDS.values())
