"""Yade's ``Serializable.dict()`` for Talus's materials, states and shapes: every attribute by
name, in Yade's order (a class's own attributes before its base's)."""

from __future__ import annotations


class Serializable:
    """Mixin: each class lists its own Yade attributes in ``_attributes``; ``dict()`` reads them
    all. An attribute Talus does not have is left out (Yade's dict has every one)."""

    __slots__ = ()
    _attributes: tuple[str, ...] = ()

    def dict(self) -> dict:
        names = dict.fromkeys(n for cls in type(self).__mro__ for n in vars(cls).get("_attributes", ()))
        return {n: getattr(self, n) for n in names if hasattr(self, n)}
