"""Talus: the discrete element method coupled to fluid and continuum solvers.

Import this package, never the compiled modules (``talus._dem``, ...) directly::

    import talus
    print(talus.__version__, talus.components())

Sub-packages follow the components: ``talus.dem`` (the core), ``talus.flow``, ``talus.coupling``,
``talus.fem``; tools shared by cases and benchmarks are ``talus.results`` (JSON result records and
charts), ``talus.report`` (the validation page) and ``talus.bench`` (side-by-side benchmarks).
"""

from talus import _build_config, _dem

__version__: str = _build_config.VERSION

if _dem.version() != __version__:
    raise ImportError(
        f"talus: the compiled module talus._dem is version {_dem.version()} but the Python "
        f"package is {__version__}; rebuild (cmake --build) so both come from the same tree")


def components() -> dict[str, bool]:
    """Which components this build has, e.g. ``{"dem": True, "flow": True, ...}``."""
    return {name: on for name, (on, _note) in _build_config.COMPONENTS.items()}


def build_info() -> dict[str, dict[str, tuple[bool, str]]]:
    """Components and optional features, each ``(enabled, note)``: the note says what was found
    or why the item is off, as printed by the configure step."""
    return {"components": dict(_build_config.COMPONENTS),
            "features": dict(_build_config.FEATURES)}


__all__ = ["__version__", "components", "build_info"]
