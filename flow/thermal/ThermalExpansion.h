#pragma once
// Thermal expansion of the particles and of the pore fluid (the thermo-mechanical part of Yade's
// ThermalEngine: thermoMech, solidThermoMech, fluidThermoMech; Caulk, Scholtès, Krzaczek &
// Chareyre 2020, CMAME): spheres grow with their temperature, and the pores' fluid volume
// changes by the fluid's expansion and the spheres' growth, which the pore flow turns into a
// pressure change (drained through the network, stored by a compressible fluid).
#include "dem/interface/Exchange.h"
#include "flow/pore/PoreFlow.h"
#include "flow/thermal/ParticleConduction.h"
#include "flow/thermal/PoreHeat.h"

#include <array>
#include <vector>

namespace talus::flow::thermal
{
/// Which expansions act, and the fluid's coefficients (Yade's names in ThermalEngine).
struct ExpansionParameters
{
  /// Radii follow the temperature: dr = alpha r dT (thermoMech, with a per-body alpha > 0).
  bool particles = true;
  /// The spheres' growth takes volume from the pores they bound (solidThermoMech).
  bool solidVolume = true;
  /// The pore fluid expands: a pore's fluid volume V grows by V fluidBeta dT (fluidThermoMech).
  bool fluid = true;
  double fluidBeta = 2e-4;    ///< volumetric expansion coefficient of the fluid, 1/K
  /// > 0: the fluid volume of a pore is porosityFactor x its volume instead of its void volume
  double porosityFactor = 0;
};

/// Expansion since the temperatures were last marked, applied after each thermal run:
///
///     r_i  +=  alpha_i r_i (T_i - T_i,mark)                         free spheres (not held by a boundary)
///     dV_p/dt = -( V_p fluidBeta (T_p - T_p,mark) + sum_v Omega_v / 3 (r_v^3 - r_v,old^3) ) / span
///
/// with Omega_v the solid angle of sphere v's corner of pore p (the share of the sphere's volume
/// change that goes into that pore). dV_p/dt is handed to the pore flow as an extra volume rate
/// for the solves until the next thermal run (`span` seconds later): an undrained pore of a
/// fluid of bulk modulus K_f then gains  K_f fluidBeta dT  of pressure, a drained one loses it
/// through the network. Every pore counts, those touching a boundary too (Yade skips them).
class ThermalExpansion
{
public:
  /// @param particles the spheres' temperatures; it must outlive this object
  /// @param exchange the scene's particle exchange, through which radii grow (copied; the scene
  ///        must outlive this object)
  ThermalExpansion(ParticleConduction& particles, dem::ParticleExchange exchange)
      : particles_(particles), exchange_(exchange)
  {
  }

  ExpansionParameters params;
  /// Linear expansion coefficient of new spheres (Yade's particleAlpha), 1/K.
  double defaultAlpha = 1.16e-5;
  /// Per body covered: the temperature the radius corresponds to (NaN: not marked yet). The
  /// linear expansion coefficients are the DEM's per-body field (state.alpha), read through the
  /// particle exchange interface.
  std::vector<double> sphereMark;

  /// Cover the bodies added since the last call (defaultAlpha to those whose coefficient is NaN,
  /// not given), and mark those not marked yet at their current temperature.
  void resize();
  /// Take the current temperatures (spheres, and pores of `fluid` if given) as the reference.
  /// @param fluid the pore temperatures, or null (spheres only)
  void mark(const PoreHeat* fluid);
  /// Expand by the change since the mark over a thermal run of `span` s (> 0), then mark again.
  /// `flow`: the pore flow receiving the volume rates (null: spheres only); `fluid`: its pore
  /// temperatures (null: no fluid expansion).
  /// @param span the thermal run's duration (s), > 0: the volume rates are changes over it
  /// @param fluid the pore temperatures, or null
  /// @param flow the pore flow given the rates (setExtraVolumeRates), or null
  /// @throws std::invalid_argument if a sphere would reach a non-positive radius
  void apply(double span, const PoreHeat* fluid, pore::PoreFlow* flow);

  /// The volume rates handed to the flow at the last apply (one per pore; empty: none).
  [[nodiscard]] const std::vector<double>& lastVolumeRates() const { return rates_; }

private:
  /// Omega_v / (4 pi) of each corner of each pore of the current network (0 for a boundary).
  void computeFractions(const pore::PoreNetwork& net);

  ParticleConduction& particles_;
  dem::ParticleExchange exchange_;
  std::vector<double> poreMark_;              ///< pore temperatures at the mark
  const void* markedMesh_ = nullptr;          ///< the network poreMark_ belongs to
  const void* fractionMesh_ = nullptr;        ///< the network fractions_ belong to
  std::vector<std::array<double, 4>> fractions_;
  std::vector<double> rates_;
};
} // namespace talus::flow::thermal
