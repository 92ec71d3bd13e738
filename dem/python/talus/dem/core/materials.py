"""Materials, named and parametrised as in Yade (FrictMat, ViscElMat, CohFrictMat)."""

from __future__ import annotations

import warnings

from talus import _dem
from talus.dem.base.serializable import Serializable

# Yade's ElastMat attributes (and their defaults), which FrictMat, ViscElMat and CohFrictMat have.
_ELASTIC = ("young", "poisson")
_FRICTIONAL = ("frictionAngle", *_ELASTIC)


class Material(Serializable):
    """Base of the material classes: a thin typed wrapper of the C++ material record."""

    _kind = _dem.MaterialKind.Frict
    _attributes = ("id", "label", "density")

    def __init__(self, **params):
        params.setdefault("young", 1e9)      # Yade's ElastMat defaults
        params.setdefault("poisson", 0.25)
        self._scene = None
        self._cpp = _dem.Material()
        self._cpp.kind = self._kind
        for name, value in params.items():
            if not hasattr(self._cpp, name) or name == "kind":
                raise TypeError(f"{type(self).__name__} has no parameter {name!r}")
            setattr(self._cpp, name, value)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return getattr(self._cpp, name)

    def __setattr__(self, name, value):
        if name.startswith("_"):
            object.__setattr__(self, name, value)
            return
        old = getattr(self._cpp, name)
        setattr(self._cpp, name, value)
        if self._scene is not None:   # a material in use must stay valid
            try:
                self._cpp.validate()
            except ValueError:
                setattr(self._cpp, name, old)
                raise

    @property
    def id(self) -> int:
        """Index in the scene's ``O.materials`` (Yade's), -1 before it is appended."""
        if self._scene is None:
            return -1
        return next(i for i, m in enumerate(self._scene.materials) if m is self)

    def _bind(self, scene, cpp):
        """Edit the scene's copy of this material from now on."""
        self._scene = scene
        self._cpp = cpp

    def __repr__(self):
        return f"{type(self).__name__}(label={self._cpp.label!r}, density={self._cpp.density})"


class FrictMat(Material):
    """Elastic-frictional material: ``young`` (Pa), ``poisson`` (shear/normal stiffness ratio),
    ``frictionAngle`` (radians), ``density``; defaults 1e9, 0.25, 0.5, 1000 as in Yade."""

    _kind = _dem.MaterialKind.Frict
    _attributes = _FRICTIONAL


class ElastMat(Material):
    """Yade's purely elastic material: ``young``, ``poisson``, ``density`` (the base of FrictMat).
    Talus stores it as a FrictMat without friction (frictionAngle 0, not settable); Yade itself has
    no FrictPhys functor for it, Talus's linear law treats it as frictionless."""

    _kind = _dem.MaterialKind.Frict
    _attributes = _ELASTIC

    def __init__(self, **params):
        if "frictionAngle" in params:
            raise TypeError("ElastMat has no parameter 'frictionAngle' (FrictMat has)")
        super().__init__(frictionAngle=0.0, **params)

    def __setattr__(self, name, value):
        if name == "frictionAngle":
            raise AttributeError("ElastMat has no attribute 'frictionAngle' (FrictMat has)")
        super().__setattr__(name, value)


class ViscElMat(Material):
    """Linear visco-elastic material: contact duration ``tc`` with restitution coefficients
    ``en``, ``et``, or directly ``kn``, ``cn``, ``ks``, ``cs``; plus ``frictionAngle``,
    ``density``. ``young`` and ``poisson`` (defaults 1e9 and 0.25, as Yade's) only matter
    against FrictMat bodies and in the time-step estimate."""

    _kind = _dem.MaterialKind.ViscEl
    _attributes = ("tc", "en", "et", "kn", "cn", "ks", "cs", "mR", "lubrication", "viscoDyn", "roughnessScale",
                   "mRtype", *_FRICTIONAL)


class CohFrictMat(Material):
    """FrictMat with cohesive bonds and rolling/twisting resistance (Yade's CohFrictMat):
    ``normalCohesion``, ``shearCohesion`` (Pa; times the smaller radius squared: the bond's
    strengths), ``isCohesive``, ``fragile`` (a bond breaks for good), ``momentRotationLaw``,
    ``alphaKr``, ``alphaKtw`` (rolling/twisting stiffness relative to ks r1 r2), ``etaRoll``,
    ``etaTwist`` (plastic moments per unit normal force relative to the radius; negative: none).
    Defaults are Yade's."""

    _kind = _dem.MaterialKind.CohFrict
    _attributes = ("isCohesive", "alphaKr", "alphaKtw", "etaRoll", "etaTwist", "normalCohesion", "shearCohesion",
                   "fragile", "momentRotationLaw", *_FRICTIONAL)

    def __init__(self, **params):
        super().__init__(**params)
        for name in ("normalCohesion", "shearCohesion"):
            if name in params:
                _warn_if_negative_cohesion(name, getattr(self._cpp, name))

    def __setattr__(self, name, value):
        super().__setattr__(name, value)
        if name in ("normalCohesion", "shearCohesion"):
            _warn_if_negative_cohesion(name, getattr(self._cpp, name))


def _warn_if_negative_cohesion(name: str, value: float) -> None:
    # Yade's default, -1, stands for "no cohesion"; another negative value is likely meant as
    # "unbreakable" (Yade's documentation says "purely elastic"), which neither Yade's law nor
    # Talus's does: the strength is that negative number times r^2.
    if value < 0 and value != -1:
        effect = ("the bond breaks unless compressed by more than |normalCohesion| r^2"
                  if name == "normalCohesion" else "the friction limit is lowered by |shearCohesion| r^2")
        warnings.warn(f"CohFrictMat.{name} = {value:g} < 0: {effect} (as in Yade); the meaningful range is >= 0 "
                      "(0: no cohesion)", UserWarning, stacklevel=3)


def default_material() -> FrictMat:
    """Yade's defaultMaterial: FrictMat(density=1e3, young=1e7, poisson=.3, frictionAngle=.5)."""
    return FrictMat(density=1e3, young=1e7, poisson=0.3, frictionAngle=0.5, label="defaultMat")

__all__ = ["Material", "ElastMat", "FrictMat", "ViscElMat", "CohFrictMat", "default_material"]
