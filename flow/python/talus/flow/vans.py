"""The 1D vertical VANS fluid model: the fluid-resolution part of Yade's HydroForceEngine.

A steady, uniform, unidirectional flow over (and through) a granular bed, resolved along the
vertical from the solid-phase depth profiles (solid fraction, particle velocity, mean drag per
particle) that a DEM average provides::

    from talus.flow import VansFluid, slope_gravity

    fluid = VansFluid(nCell=900, deltaZ=6e-3 / 30, gravity=slope_gravity(0.05),
                      ilm=2, iturbu=1, iusl=1, radiusPart=3e-3)
    fluid.phiPart = phi          # nCell values each
    fluid.vxPart = vx
    fluid.averageDrag = drag
    fluid.fluidResolution(1e-2, 1e-5)   # advance 1e-2 s with steps of 1e-5 s
    u = fluid.vxFluid                    # nCell + 1 values, at fluid.zFluid

Attribute and option names are Yade's (``HydroForceEngine``): ``nCell`` (``ndimz`` in Yade's
scripts), ``deltaZ``, ``densFluid``, ``viscoDyn``, ``gravity``, ``dpdx``, ``iturbu``, ``ilm``,
``kappa``, ``phiMax``, ``viscousSubLayer``, ``irheolf``, ``iusl``, ``uTop``,
``fluidWallFriction``, ``channelWidth``, ``fluidFrictionCoef``, ``radiusPart``; profiles
``phiPart``, ``vxPart``, ``averageDrag``, ``vxFluid``; outputs ``ReynoldStresses``,
``turbulentViscosity``, ``taufsi``. One difference: Yade 2023.02a reads the particle velocity
from ``vPart[:, 0]``; here it is ``vxPart``.

The grid: ``nCell`` cells of height ``deltaZ`` from z = 0; the fluid column is
h = (nCell - 1) deltaZ high; ``vxFluid`` lives at z = 0, at the cell centres (j + 1/2) deltaZ
(j < nCell - 1) and at z = h (``zFluid``); stresses and viscosities at z = j deltaZ (``zMesh``).
Equations, closures and validity: ``docs/flow.md``.
"""

from __future__ import annotations

import enum
import math
import warnings
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from talus import _flow

__all__ = ["VansFluid", "MixingLength", "EffectiveViscosity", "TopBoundary", "slope_gravity"]


class MixingLength(enum.IntEnum):
    """Mixing-length closure (Yade's ``ilm``)."""
    PRANDTL = 0       #: l_m = kappa z
    FREE_SURFACE = 1  #: l_m = kappa z sqrt(1 - z/h)
    LI_SAWAMOTO = 2   #: l_m = integral of kappa (phiMax - phi)/phiMax dz, damped in the bed


class EffectiveViscosity(enum.IntEnum):
    """Effective viscosity of the fluid in the mixture (Yade's ``irheolf``)."""
    FLUID = 0      #: nu
    EINSTEIN = 1   #: nu (1 + 2.5 phi)
    POWER_LAW = 2  #: nu (1 - phi)^-2.8


class TopBoundary(enum.IntEnum):
    """Boundary condition at the top of the fluid column (Yade's ``iusl``)."""
    IMPOSED_VELOCITY = 0  #: u(h) = uTop
    FREE_SURFACE = 1      #: du/dz(h) = 0


def slope_gravity(angle: float, g: float = 9.81) -> tuple[float, float, float]:
    """Gravity vector of a channel inclined by ``angle`` radians, x streamwise, z wall-normal:
    ``(g sin(angle), 0, -g cos(angle))``, as Yade's scripts build it."""
    return (g * math.sin(angle), 0.0, -g * math.cos(angle))


def _option(enum_type: type[enum.IntEnum], value: int, name: str) -> enum.IntEnum:
    try:
        return enum_type(int(value))
    except (ValueError, TypeError):
        allowed = ", ".join(f"{m.value} ({m.name.lower()})" for m in enum_type)
        raise ValueError(f"VansFluid: {name} must be one of {allowed}, got {value!r}") from None


def _cell_count(value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"VansFluid: nCell must be an integer, got {value!r}")
    return int(value)


def _flag(value: bool | int, name: str) -> bool:
    if value not in (0, 1):  # True == 1, False == 0
        raise ValueError(f"VansFluid: {name} must be 0/1 or a bool, got {value!r}")
    return bool(value)


def core_parameter(cxx_name: str, doc: str, convert=float):
    """A property stored in the C++ parameter set of the object's ``_core`` (validated there when
    set); HydroForceEngine's particle parameters are made the same way."""
    def get(self):
        return getattr(self._core.parameters(), cxx_name)

    def set(self, value):
        p = self._core.parameters()
        setattr(p, cxx_name, convert(value))
        self._core.setParameters(p)
    return property(get, set, doc=doc)


def _profile(name: str, doc: str, settable: bool = True):
    getter_name = name[0].lower() + name[1:]

    def get(self) -> np.ndarray:
        return getattr(self._core, getter_name)()

    def set(self, values: ArrayLike) -> None:
        try:
            array = np.asarray(values, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"VansFluid: {name} must be an array of numbers") from None
        if array.ndim != 1:
            raise ValueError(f"VansFluid: {name} must be one-dimensional, got shape {array.shape}")
        getattr(self._core, "set" + name[0].upper() + name[1:])(array)
    return property(get, set if settable else None, doc=doc)


_CXX_OPTIONS = {
    "ilm": ("mixingLength", MixingLength, _flow.MixingLengthModel),
    "irheolf": ("effectiveViscosity", EffectiveViscosity, _flow.EffectiveViscosityModel),
    "iusl": ("topBoundary", TopBoundary, _flow.TopBoundary),
}


class VansFluid:
    """1D vertical VANS fluid resolution (Yade's ``HydroForceEngine.fluidResolution`` and the
    attributes it reads), on a grid of ``nCell`` cells of height ``deltaZ``.

    Every parameter is a keyword with Yade 2023.02a's default; set them later as attributes as
    in Yade. Bad values raise ``ValueError`` naming the parameter.

    Args:
        nCell: number of cells (``ndimz`` in Yade's scripts; either name is accepted), >= 2.
        deltaZ: cell height [m]; the fluid column is (nCell - 1) deltaZ high.
        densFluid: fluid density [kg/m^3].
        viscoDyn: fluid dynamic viscosity [Pa s].
        gravity: gravity vector (x streamwise, z wall-normal); |gravity[0]| drives the flow.
            ``slope_gravity(angle)`` builds it for an inclined channel.
        dpdx: imposed streamwise pressure gradient [Pa/m] (negative drives the flow along +x).
        iturbu: 1 for the mixing-length eddy viscosity, 0 for laminar flow.
        ilm: mixing length, a ``MixingLength`` (0 kappa z, 1 kappa z sqrt(1-z/h), 2 Li-Sawamoto).
        kappa: von Karman constant.
        phiMax: maximum solid fraction (Li-Sawamoto closure).
        viscousSubLayer: 1 to switch the eddy viscosity off below z+ = 11.3 (u* = sqrt(|g_x| h)).
        irheolf: effective viscosity, an ``EffectiveViscosity`` (0 fluid, 1 Einstein, 2 power law).
        iusl: top boundary, a ``TopBoundary`` (0 imposed velocity ``uTop``, 1 free surface).
        uTop: top velocity [m/s] when ``iusl == 0``.
        fluidWallFriction: add the side-wall friction sink (channel width ``channelWidth``,
            factor ``fluidFrictionCoef``), in Yade 2023.02a's form.
        radiusPart: particle radius [m], turning ``averageDrag`` (per particle) into a drag per
            unit volume; must be > 0 when there is drag.
    """

    def __init__(self, *, nCell: int | None = None, deltaZ: float, ndimz: int | None = None,
                 densFluid: float = 1000.0, viscoDyn: float = 1e-3,
                 gravity: Sequence[float] = (0.0, 0.0, -9.81), dpdx: float = 0.0,
                 iturbu: int = 1, ilm: int = MixingLength.LI_SAWAMOTO, kappa: float = 0.41,
                 phiMax: float = 0.64, viscousSubLayer: int = 0,
                 irheolf: int = EffectiveViscosity.FLUID, iusl: int = TopBoundary.FREE_SURFACE,
                 uTop: float = 1.0, fluidWallFriction: bool = False, channelWidth: float = 1.0,
                 fluidFrictionCoef: float = 1.0, radiusPart: float = 0.0):
        if (nCell is None) == (ndimz is None):
            raise ValueError("VansFluid: give the number of cells as nCell or ndimz (one of them)")
        p = _flow.VansParameters()
        p.nCell = _cell_count(nCell if nCell is not None else ndimz)
        p.deltaZ = float(deltaZ)
        self._gravity = self._check_gravity(gravity)
        p.gravityX = self._gravity[0]
        p.densFluid, p.viscoDyn, p.dpdx = float(densFluid), float(viscoDyn), float(dpdx)
        p.turbulence = _flag(iturbu, "iturbu")
        p.kappa, p.phiMax, p.uTop = float(kappa), float(phiMax), float(uTop)
        p.viscousSubLayer = _flag(viscousSubLayer, "viscousSubLayer")
        p.fluidWallFriction = _flag(fluidWallFriction, "fluidWallFriction")
        p.channelWidth, p.fluidFrictionCoef = float(channelWidth), float(fluidFrictionCoef)
        p.radiusPart = float(radiusPart)
        for name, value in (("ilm", ilm), ("irheolf", irheolf), ("iusl", iusl)):
            cxx_name, py_enum, cxx_enum = _CXX_OPTIONS[name]
            setattr(p, cxx_name, cxx_enum(int(_option(py_enum, value, name))))
        self._core = _flow.VansFluid(p)

    @staticmethod
    def _check_gravity(gravity: Sequence[float]) -> tuple[float, float, float]:
        try:
            g = tuple(float(x) for x in gravity)
        except (TypeError, ValueError):
            raise ValueError(f"VansFluid: gravity must be a 3-vector, got {gravity!r}") from None
        if len(g) != 3 or not all(math.isfinite(x) for x in g):
            raise ValueError(f"VansFluid: gravity must be a finite 3-vector, got {gravity!r}")
        return g  # type: ignore[return-value]

    # -- parameters (Yade's names) -----------------------------------------------------------
    nCell = core_parameter("nCell", "Number of cells; changing it resets every profile to zeros.", _cell_count)
    ndimz = nCell
    deltaZ = core_parameter("deltaZ", "Cell height [m].")
    densFluid = core_parameter("densFluid", "Fluid density [kg/m^3].")
    viscoDyn = core_parameter("viscoDyn", "Fluid dynamic viscosity [Pa s].")
    dpdx = core_parameter("dpdx", "Imposed streamwise pressure gradient [Pa/m].")
    kappa = core_parameter("kappa", "Von Karman constant of the mixing length.")
    phiMax = core_parameter("phiMax", "Maximum solid fraction (Li-Sawamoto mixing length).")
    uTop = core_parameter("uTop", "Imposed top velocity [m/s] (iusl = 0).")
    channelWidth = core_parameter("channelWidth", "Channel width [m] for the side-wall friction.")
    fluidFrictionCoef = core_parameter("fluidFrictionCoef", "Fitting factor of the wall friction.")
    radiusPart = core_parameter("radiusPart", "Particle radius [m] for the drag per unit volume.")
    iturbu = core_parameter("turbulence", "1: mixing-length eddy viscosity, 0: laminar.",
                            lambda v: _flag(v, "iturbu"))
    viscousSubLayer = core_parameter("viscousSubLayer", "1: no eddy viscosity below z+ = 11.3.",
                                     lambda v: _flag(v, "viscousSubLayer"))
    fluidWallFriction = core_parameter("fluidWallFriction", "Side-wall friction sink term on/off.",
                                       lambda v: _flag(v, "fluidWallFriction"))

    def _get_option(self, name: str) -> enum.IntEnum:
        cxx_name, py_enum, _ = _CXX_OPTIONS[name]
        return py_enum(int(getattr(self._core.parameters(), cxx_name)))

    def _set_option(self, name: str, value: int) -> None:
        cxx_name, py_enum, cxx_enum = _CXX_OPTIONS[name]
        p = self._core.parameters()
        setattr(p, cxx_name, cxx_enum(int(_option(py_enum, value, name))))
        self._core.setParameters(p)

    ilm = property(lambda self: self._get_option("ilm"), lambda self, v: self._set_option("ilm", v),
                   doc="Mixing length closure, a MixingLength (Yade's ilm).")
    irheolf = property(lambda self: self._get_option("irheolf"),
                       lambda self, v: self._set_option("irheolf", v),
                       doc="Effective viscosity, an EffectiveViscosity (Yade's irheolf).")
    iusl = property(lambda self: self._get_option("iusl"), lambda self, v: self._set_option("iusl", v),
                    doc="Top boundary, a TopBoundary (Yade's iusl).")

    @property
    def gravity(self) -> tuple[float, float, float]:
        """Gravity vector; |gravity[0]| drives the flow (slope_gravity builds it)."""
        return self._gravity

    @gravity.setter
    def gravity(self, value: Sequence[float]) -> None:
        g = self._check_gravity(value)
        p = self._core.parameters()
        p.gravityX = g[0]
        self._core.setParameters(p)
        self._gravity = g

    @property
    def fluidHeight(self) -> float:
        """Height of the fluid column, (nCell - 1) deltaZ [m]."""
        return self._core.parameters().fluidHeight()

    @property
    def zFluid(self) -> np.ndarray:
        """Elevations of the vxFluid nodes: 0, (j + 1/2) deltaZ for j < nCell - 1, fluidHeight."""
        return np.asarray(self._core.velocityNodeElevations())

    @property
    def zMesh(self) -> np.ndarray:
        """Elevations j deltaZ of the mesh nodes (ReynoldStresses, turbulentViscosity)."""
        return np.asarray(self._core.meshNodeElevations())

    # -- profiles ------------------------------------------------------------------------------
    phiPart = _profile("phiPart", "Solid volume fraction per cell (nCell values in [0, 1)).")
    vxPart = _profile("vxPart", "Mean streamwise particle velocity per cell [m/s] (nCell values).")
    averageDrag = _profile("averageDrag", "Mean streamwise drag force per particle in each cell [N] "
                                          "(nCell values).")
    vxFluid = _profile("vxFluid", "Fluid velocity at the nCell + 1 nodes zFluid [m/s]: the result "
                                  "of the last call and the start of the next.")
    ReynoldStresses = _profile("reynoldStresses", "Reynolds shear stress rho eps nu_t du/dz at zMesh "
                                                  "[Pa] after the last call.", settable=False)
    turbulentViscosity = _profile("turbulentViscosity", "Eddy viscosity nu_t at zMesh [m^2/s] "
                                                        "(last time step).", settable=False)
    taufsi = _profile("taufsi", "Drag exchange coefficient per cell [1/s] used by the last call.",
                      settable=False)
    mixingLengthProfile = _profile("mixingLength", "Mixing length at zMesh [m] used by the last "
                                                   "call.", settable=False)

    @property
    def clippedDragCells(self) -> int:
        """Cells whose taufsi hit the cap 1/(10 dt) in the last call (0 when dt is adequate)."""
        return self._core.clippedDragCells()

    @property
    def lastStepCount(self) -> int:
        """Time steps taken by the last fluidResolution call."""
        return self._core.lastStepCount()

    @property
    def lastStepChange(self) -> float:
        """Largest change of vxFluid over the last step, relative to max |vxFluid|."""
        return self._core.lastStepChange()

    @property
    def oscillating(self) -> bool:
        """True if the last call ended flip-flopping (its last two steps changed vxFluid in
        opposite directions by more than 1e-3 relative): dt is too long for the lagged eddy
        viscosity, the profile oscillates around the solution instead of reaching it."""
        return self._core.oscillating()

    def initialization(self) -> None:
        """Reset every profile to zeros of the current size (Yade's ``initialization()``)."""
        self._core.initialization()

    def fluidResolution(self, tfin: float, dt: float) -> None:
        """Advance ``vxFluid`` over ``tfin`` seconds with steps ``dt``, the solid profiles frozen
        (Yade's ``HydroForceEngine.fluidResolution(tfin, dt)``; steps are taken while the summed
        time is below tfin, so tfin/dt or one more: ``lastStepCount`` tells). The implicit scheme
        stays bounded for any ``dt``; a ``RuntimeWarning`` says when ``dt`` was too long all the
        same: the profile flip-flops from step to step (``oscillating``), or the drag coefficient
        had to be capped at 1/(10 dt) (``clippedDragCells``).

        Raises:
            ValueError: tfin < 0, dt <= 0, a profile of the wrong length or with NaN, ...
            RuntimeError: the velocity became non-finite (vxFluid is then left unchanged).
        """
        self._core.fluidResolution(float(tfin), float(dt))
        if self._core.oscillating():
            warnings.warn(f"VansFluid.fluidResolution: the velocity profile flip-flops from step to step "
                          f"(last change {self._core.lastStepChange():.2g} of max |u|, opposite to the one "
                          f"before): dt = {dt:g} s is too long for the lagged eddy viscosity; use a smaller "
                          f"dt", RuntimeWarning, stacklevel=2)
        clipped = self._core.clippedDragCells()
        if clipped:
            warnings.warn(f"VansFluid.fluidResolution: the drag coefficient taufsi was capped at "
                          f"1/(10 dt) = {1 / (10 * dt):.3g} 1/s in {clipped} cell(s); the fluid-particle "
                          f"coupling is weakened by the time step: use a smaller dt",
                          RuntimeWarning, stacklevel=2)

    def __repr__(self) -> str:
        return (f"VansFluid(nCell={self.nCell}, deltaZ={self.deltaZ:g}, ilm={int(self.ilm)}, "
                f"iturbu={int(self.iturbu)}, iusl={int(self.iusl)})")
