"""The bodies' heat: Yade's ThermalState fields ``temp``, ``Cp``, ``k`` and ``alpha``, one value per
body in the DEM core (NaN where not given), which every component reads and changes through the
scene's arrays (``scene.temperatures()``, ...: the particle exchange interface). A heat model
(ThermalEngine) gives its defaults to the bodies whose fields are NaN at its steps; before that,
reading a field gives the default of the scene's engine that declares one (``_heatDefaults()``)."""

from __future__ import annotations

import math

import numpy as np

ABSOLUTE_ZERO = -273.15   # °C: Yade's scripts use °C or K, so no temperature may go below it

# Yade's name of each field -> the scene's array (talus._dem Scene method).
FIELDS = {"temp": "temperature", "Cp": "heatCapacity", "k": "conductivity", "alpha": "thermalExpansion"}


def below_absolute_zero(name: str, value: float) -> ValueError | None:
    """The error for a temperature below absolute zero, or None."""
    if value < ABSOLUTE_ZERO:
        return ValueError(f"{name} = {value} is below absolute zero (-273.15 °C, 0 K)")
    return None


def check(field: str, value) -> float:
    """``value`` as body field ``field`` (temp, Cp, k, alpha), or the error naming ``state.<field>``:
    a finite number, a temperature above absolute zero, Cp > 0, k and alpha >= 0."""
    name = f"state.{field}"
    if isinstance(value, (str, bytes, bool)):
        raise TypeError(f"{name} must be a number, got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    error = below_absolute_zero(name, number) if field == "temp" else None
    if field == "Cp" and number <= 0:
        error = ValueError(f"{name} must be > 0 (J/(kg K)), got {number}")
    if field in ("k", "alpha") and number < 0:
        error = ValueError(f"{name} must be >= 0, got {number}")
    if error is not None:
        raise error
    return number


def _defaults(scene) -> dict:
    for engine in scene.engines:
        if hasattr(engine, "_heatDefaults"):
            return engine._heatDefaults()
    return {}


def value_of(scene, id: int, field: str) -> float:
    """Body ``id``'s ``field``: its value, else the default of the scene's heat engine.
    @raises AttributeError when neither exists (as Yade's State without heat)"""
    value = float(getattr(scene._cpp, FIELDS[field])()[id])
    if math.isnan(value):
        value = _defaults(scene).get(field, value)
    if math.isnan(value):
        raise AttributeError(f"body {id} has no state.{field}: no value was given (set b.state.{field}) and no engine "
                             "of the scene gives one (a ThermalEngine gives particleT0, particleCp, particleK, "
                             "particleAlpha)")
    return value


def assign(scene, id: int, field: str, value) -> None:
    """Set body ``id``'s ``field`` (checked: see check)."""
    getattr(scene._cpp, FIELDS[field])()[id] = check(field, value)


def sphere_arrays(scene, ids) -> dict:
    """``temp``, ``k`` and ``Cp`` of the spheres ``ids`` for the sphere file (VTKRecorder's
    'thermal'), the heat engine's defaults where not given; a field no sphere has is left out.
    @raises ValueError when no sphere has a temperature and no engine gives one"""
    defaults = _defaults(scene)
    arrays = {}
    for field in ("temp", "k", "Cp"):
        values = np.array(getattr(scene._cpp, FIELDS[field])()[ids], dtype=float)
        values[np.isnan(values)] = defaults.get(field, np.nan)
        if not np.isnan(values).all():
            arrays[field] = values
    if len(ids) and "temp" not in arrays:
        raise ValueError("VTKRecorder: the 'thermal' recorder writes the spheres' temperatures, and none has one "
                         "(set b.state.temp, or add a ThermalEngine to O.engines)")
    return arrays
