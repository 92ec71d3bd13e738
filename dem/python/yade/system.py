"""``yade.system``: the class registry Yade's tools query (``childClasses``).

In Yade every class of its object model derives from ``Serializable``; ``childClasses(base)`` gives
the names of the classes derived from ``base``. Talus answers for the classes it implements under
Yade's names (those of Yade 2023.02a's ``yade`` module that ``import yade`` serves as classes,
the value types excepted, which are not Serializable in Yade either).
"""

from __future__ import annotations

import inspect

import yade
from yade._yade_names import NAMES

_VALUE_TYPES = {"Vector2", "Vector2i", "Vector3", "Vector3i", "Vector4", "Vector6", "Vector6i", "Matrix3", "Matrix6",
                "Quaternion", "AlignedBox2", "AlignedBox3"}


def _classes() -> dict[str, type]:
    names = set(NAMES["yade"]) - _VALUE_TYPES
    found = {}
    for name in sorted(names):
        try:
            cls = getattr(yade, name)
        except AttributeError:
            continue  # a Yade class Talus lacks
        if inspect.isclass(cls) and cls.__name__ == name:
            found[name] = cls
    return found


def childClasses(base: str) -> set[str]:
    """Names of the classes deriving (at any depth) from the class named ``base``; every class
    for ``"Serializable"``; an empty set for a name no class has, as in Yade."""
    classes = _classes()
    if base == "Serializable":
        return set(classes)
    root = classes.get(base)
    if root is None:
        return set()
    return {name for name, cls in classes.items() if cls is not root and issubclass(cls, root)}
