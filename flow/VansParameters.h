#pragma once

namespace talus::flow
{
/// Mixing-length closure of the eddy viscosity, with Yade's option number (HydroForceEngine.ilm).
enum class MixingLengthModel
{
  Prandtl = 0,      ///< l_m = kappa z (classical Prandtl)
  FreeSurface = 1,  ///< l_m = kappa z sqrt(1 - z/h) (parabolic eddy viscosity of free-surface flows)
  LiSawamoto = 2,   ///< l_m = integral of kappa (phiMax - phi)/phiMax dz (Li & Sawamoto 1995)
};

/// Effective viscosity of the fluid in the mixture (HydroForceEngine.irheolf).
enum class EffectiveViscosityModel
{
  Fluid = 0,     ///< nu_eff = nu (pure fluid)
  Einstein = 1,  ///< nu_eff = nu (1 + 2.5 phi)
  PowerLaw = 2,  ///< nu_eff = nu (1 - phi)^-2.8 (bottom node keeps Einstein's form, as in Yade)
};

/// Boundary condition at the top of the fluid column (HydroForceEngine.iusl).
enum class TopBoundary
{
  ImposedVelocity = 0,  ///< Dirichlet: u(h) = uTop (a lid, or the centre line of a channel)
  FreeSurface = 1,      ///< Neumann: du/dz(h) = 0
};

/// Parameters of the 1D vertical VANS fluid model (Yade's HydroForceEngine, fluid part).
///
/// Names follow HydroForceEngine where it has one; the defaults are Yade 2023.02a's, except
/// nCell and deltaZ, which have no sensible default.
///
/// The grid: nCell solid-phase cells of height deltaZ from z = 0; the fluid column spans
/// z in [0, h] with h = (nCell - 1) deltaZ. The velocity is stored at nCell + 1 nodes:
/// z = 0 (no-slip wall), the cell centres (j + 1/2) deltaZ for j = 0 .. nCell - 2, and z = h.
struct VansParameters
{
  /// Number of cells (Yade's nCell, "ndimz" in its scripts); >= 1, and >= 2 to resolve the
  /// fluid (one cell has no fluid column: the forces on particles only need the grid).
  int nCell = 0;
  double deltaZ = 0;           ///< cell height [m]; > 0
  double densFluid = 1000.0;   ///< fluid density [kg/m^3]; > 0
  double viscoDyn = 1e-3;      ///< fluid dynamic viscosity [Pa s]; >= 0
  /// Streamwise component of gravity [m/s^2]; only its magnitude drives the flow (Yade uses
  /// |gravity[0]|). For a slope of angle alpha: g sin(alpha).
  double gravityX = 0.0;
  double dpdx = 0.0;           ///< imposed streamwise pressure gradient [Pa/m]
  bool turbulence = true;      ///< Yade's iturbu: eddy viscosity from a mixing length, or none
  MixingLengthModel mixingLength = MixingLengthModel::LiSawamoto;  ///< Yade's ilm
  double kappa = 0.41;         ///< von Karman constant; >= 0
  double phiMax = 0.64;        ///< maximum solid fraction (Li-Sawamoto closure); in (0, 1]
  /// Yade's viscousSubLayer: no eddy viscosity where z u*/nu < 11.3, with u* = sqrt(|gx| h).
  bool viscousSubLayer = false;
  EffectiveViscosityModel effectiveViscosity = EffectiveViscosityModel::Fluid;  ///< Yade's irheolf
  TopBoundary topBoundary = TopBoundary::FreeSurface;  ///< Yade's iusl
  double uTop = 1.0;           ///< top velocity [m/s] for TopBoundary::ImposedVelocity
  bool fluidWallFriction = false;  ///< sink term for the friction on the side walls
  double channelWidth = 1.0;       ///< channel width [m] for the wall friction; > 0
  double fluidFrictionCoef = 1.0;  ///< fitting factor on the wall friction factor; >= 0
  /// Particle radius [m] turning the mean drag per particle into a drag per unit volume;
  /// must be > 0 when any cell carries drag.
  double radiusPart = 0.0;

  /// @throws std::invalid_argument naming the first parameter that is out of range or not finite
  void validate() const;

  /// Height of the fluid column, (nCell - 1) deltaZ.
  [[nodiscard]] double fluidHeight() const { return (nCell - 1) * deltaZ; }
};
} // namespace talus::flow
