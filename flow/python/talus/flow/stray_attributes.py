"""Assignments of attributes an engine does not have (``flow.minKdivmean = 1e-4``, a misspelt
``minKdivKmean``). Talus refuses them, naming the closest attribute. Yade 2023.02a accepts them
after construction (not as constructor keywords): the engine keeps the value as a plain Python
attribute that nothing reads, and a checkpoint drops it. A Yade script run by ``talus run`` (or
``yadeimport``) gets Yade's behaviour with a warning, printed once per engine type and name,
naming the attribute and the likely intended one: the script runs unchanged, and the value
changes nothing, exactly as in Yade."""

from __future__ import annotations

import difflib
import os
import sys
import warnings

_accepted = False           # set by accept(): a Yade script's run
_warned: set[tuple[str, str]] = set()
_PACKAGE = os.path.dirname(os.path.abspath(__file__))


def accept() -> None:
    """From now on, keep the assignments Yade keeps (yade_run_defaults calls it)."""
    global _accepted
    _accepted = True


def refuse_or_keep(engine, kind: str, name: str, value, known) -> None:
    """An assignment of ``name``, which the engine does not have: kept as a plain attribute with a
    warning naming its class in a Yade script's run once ``engine`` is constructed (its
    ``_constructed``), otherwise an AttributeError naming ``kind`` (the class whose attributes
    ``known`` are) and the closest of ``known``."""
    close = difflib.get_close_matches(name, list(known), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    if not (_accepted and engine.__dict__.get("_constructed", False)):
        raise AttributeError(f"{kind} has no attribute {name!r}{hint}")
    kind = type(engine).__name__
    if (kind, name) not in _warned:
        _warned.add((kind, name))
        level, frame = 1, sys._getframe()     # the warning points at the script's line
        while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
            frame, level = frame.f_back, level + 1
        warnings.warn(f"{kind} has no attribute {name!r}{hint}: kept as a plain Python attribute that nothing reads, "
                      "as Yade 2023.02a does (the value changes nothing, and checkpoints drop it)", RuntimeWarning,
                      stacklevel=level)
    object.__setattr__(engine, name, value)
