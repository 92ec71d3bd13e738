#pragma once

#include "flow/VansParameters.h"

#include <cstddef>
#include <span>
#include <vector>

namespace talus::flow
{
/// The 1D vertical volume-averaged (VANS) fluid model of Yade's HydroForceEngine: the streamwise
/// fluid velocity profile u(z, t) of a steady, uniform, unidirectional flow over (and through) a
/// granular bed described by its solid-phase depth profiles.
///
/// Equation solved (Maurin et al. 2015; Revil-Baudard & Chauchat 2013), eps = 1 - phi:
///
///     eps du/dt = eps d/dz[ nu_eff d(eps u + phi v_p)/dz ] + d/dz[ eps nu_t du/dz ]
///                 + eps |g_x| - eps dpdx / rho + taufsi (v_p - u) - eps (2/W) (f/8) u^2,
///
/// with nu_t = l_m^2 |du/dz| (MixingLengthModel), taufsi = n <f_D> / (rho |u - v_p|) the drag per
/// unit volume and per unit relative velocity (n = phi / V_p particles per unit volume, capped at
/// 1/(10 dt) as in Yade), and the last term the optional side-wall friction (friction factor f,
/// channel width W). taufsi, phi and v_p are frozen during a call (they come from the DEM average
/// of the last coupling), the eddy viscosity and the wall friction factor are lagged by one
/// step, the rest is implicit (backward Euler in time, finite volumes on the staggered grid of
/// VansParameters), so the velocity stays bounded for any time step. The lag limits accuracy:
/// with dt much longer than the turbulent time scale the profile flip-flops around the solution
/// from step to step, which oscillating() reports. The wall-friction term is split
/// half implicit as Yade 2023.02a writes it, u^2 of the old step times u of the new one, which is
/// only consistent for u of order 1 m/s; it is kept for side-by-side comparisons with Yade.
///
/// Use: set the parameters, the solid profiles (phiPart, vxPart, averageDrag, nCell values each)
/// and possibly an initial vxFluid (nCell + 1 values, zero by default), then call
/// fluidResolution(tfin, dt); read vxFluid, reynoldStresses, turbulentViscosity, taufsi.
class VansFluid
{
public:
  /// @param parameters the model's parameters (copied); profiles start as zeros
  /// @throws std::invalid_argument naming the offending parameter (see VansParameters::validate)
  explicit VansFluid(const VansParameters& parameters);

  /// The current parameters.
  [[nodiscard]] const VansParameters& parameters() const noexcept { return m_parameters; }
  /// Replace the parameters. Changing nCell resets every profile to zeros of the new size.
  /// @param parameters the new parameters (copied)
  /// @throws std::invalid_argument naming the offending parameter; nothing is changed then
  void setParameters(const VansParameters& parameters);

  /// Reset every profile (inputs and outputs) to zeros of the current size, as Yade's
  /// HydroForceEngine.initialization() does.
  void initialization();

  /// Solid volume fraction per cell.
  /// @param phiPart nCell values, each in [0, 1)
  /// @throws std::invalid_argument on another count or a value out of range
  void setPhiPart(std::span<const double> phiPart);
  /// Mean streamwise particle velocity per cell.
  /// @param vxPart nCell values [m/s]
  /// @throws std::invalid_argument on another count or a value not finite
  void setVxPart(std::span<const double> vxPart);
  /// Mean streamwise drag force per particle in each cell; with radiusPart it gives the momentum
  /// exchange with the fluid. Negative values are dropped (taufsi >= 0).
  /// @param averageDrag nCell values [N]
  /// @throws std::invalid_argument on another count or a value not finite
  void setAverageDrag(std::span<const double> averageDrag);
  /// Fluid velocity at the velocity nodes: the initial state of the next call.
  /// @param vxFluid nCell + 1 values [m/s]
  /// @throws std::invalid_argument on another count or a value not finite
  void setVxFluid(std::span<const double> vxFluid);

  /// The solid profiles last set (views into this object, valid until the next set or nCell change).
  [[nodiscard]] std::span<const double> phiPart() const noexcept { return m_phiPart; }
  [[nodiscard]] std::span<const double> vxPart() const noexcept { return m_vxPart; }
  [[nodiscard]] std::span<const double> averageDrag() const noexcept { return m_averageDrag; }
  /// Fluid velocity at the velocity nodes (nCell + 1 values), see velocityNodeElevations().
  [[nodiscard]] std::span<const double> vxFluid() const noexcept { return m_vxFluid; }
  /// Reynolds shear stress rho eps nu_t du/dz at the mesh nodes z_j = j deltaZ [Pa] (nCell values),
  /// with nu_t of the last time step and du/dz of the final profile.
  [[nodiscard]] std::span<const double> reynoldStresses() const noexcept { return m_reynoldStresses; }
  /// Eddy viscosity nu_t of the last time step at the mesh nodes [m^2/s] (nCell values).
  [[nodiscard]] std::span<const double> turbulentViscosity() const noexcept { return m_turbulentViscosity; }
  /// Drag exchange coefficient taufsi [1/s] per cell used by the last call (nCell values;
  /// taufsi[0] = 0 as in Yade, the bottom cell is under the wall node).
  [[nodiscard]] std::span<const double> taufsi() const noexcept { return m_taufsi; }
  /// Mixing length used by the last call at the mesh nodes [m] (nCell values).
  [[nodiscard]] std::span<const double> mixingLength() const noexcept { return m_mixingLength; }
  /// Number of cells whose taufsi reached the cap 1/(10 dt) in the last call: the drag was then
  /// weakened by the time step (Yade caps silently; a non-zero count means dt is too large for
  /// the coupling).
  [[nodiscard]] std::size_t clippedDragCells() const noexcept { return m_clippedDragCells; }
  /// Number of time steps taken by the last call.
  [[nodiscard]] std::size_t lastStepCount() const noexcept { return m_lastStepCount; }
  /// Largest change of the velocity over the last step, relative to the largest velocity.
  [[nodiscard]] double lastStepChange() const noexcept { return m_lastStepChange; }
  /// True if the last call ended flip-flopping: its last two steps changed the velocity in
  /// opposite directions by more than oscillationThreshold (relative). This is how the lagged
  /// eddy viscosity fails when dt is much longer than the turbulent time scale: bounded, but
  /// oscillating around the solution instead of converging to it. Use a smaller dt.
  [[nodiscard]] bool oscillating() const noexcept { return m_oscillating; }

  /// Relative step-to-step change above which an alternating change counts as oscillation.
  static constexpr double oscillationThreshold = 1e-3;

  /// Elevations of the nCell + 1 velocity nodes: 0, (j + 1/2) deltaZ for j = 0 .. nCell - 2, h.
  [[nodiscard]] std::vector<double> velocityNodeElevations() const;
  /// Elevations of the nCell mesh nodes j deltaZ, where stresses and viscosities live.
  [[nodiscard]] std::vector<double> meshNodeElevations() const;

  /// Advance the fluid velocity over tfin with steps dt, the solid profiles frozen, exactly as
  /// Yade's HydroForceEngine.fluidResolution(tfin, dt): steps are taken while the accumulated
  /// time (0, dt, 2 dt, ... summed in floating point) is below tfin.
  /// @param tfin the time to advance [s], >= 0
  /// @param dt the fluid time step [s], > 0
  /// @throws std::invalid_argument if tfin < 0 or dt <= 0 (or either is not finite), if dt is too
  ///         small to advance the summed time in floating point, if a profile
  ///         does not have the size nCell (nCell + 1 for vxFluid), holds a non-finite value, or
  ///         phiPart is outside [0, 1), or radiusPart is zero while some cell carries drag
  /// @throws std::runtime_error if the velocity becomes non-finite; vxFluid is then left as it was
  void fluidResolution(double tfin, double dt);

private:
  VansParameters m_parameters;
  std::vector<double> m_phiPart, m_vxPart, m_averageDrag, m_vxFluid;
  std::vector<double> m_reynoldStresses, m_turbulentViscosity, m_taufsi, m_mixingLength;
  std::size_t m_clippedDragCells = 0;
  std::size_t m_lastStepCount = 0;
  double m_lastStepChange = 0;
  bool m_oscillating = false;
};
} // namespace talus::flow
