#pragma once
// Heat conduction between spheres in contact, with one temperature per particle (the
// conduction part of Yade's ThermalEngine; Caulk, Scholtès, Krzaczek & Chareyre 2020, CMAME).
#include "dem/interface/Exchange.h"
#include "flow/thermal/HeatModel.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace talus::flow::thermal
{
/// Number of boundaries of a packing, numbered as Yade's wallIds: xmin, xmax, ymin, ymax, zmin, zmax.
inline constexpr int kBoundaries = 6;

/// How the conductance of a contact is computed (Yade's useKernMethod; the default otherwise).
enum class ContactConductance : std::uint8_t
{
  /// G = 2 (k1 + k2) r1 r2 / d, d = r1 + r2 - overlap: Yade's default, an area of the order of
  /// the smaller cross-section whatever the overlap.
  Radii,
  /// G = 2 (k1 + k2) rc^2 / d with rc the radius of the circle where the two spheres intersect
  /// (Kern and Bland's formula): the overlap decides the area.
  Kern,
};

/// Temperatures of the spheres of a scene, advanced by explicit heat conduction through their
/// contacts:
///
///     C_i dT_i/dt = sum_j G_ij (T_j - T_i),   C_i = m_i Cp_i
///
/// over the real sphere-sphere contacts of the scene (read through the particle exchange
/// interface). m_i is the body's mass, or rho V_i when `particleDensity` > 0 (Yade's override,
/// for scenes with scaled densities). Particles of a temperature boundary keep their
/// temperature; the heat they receive is summed per boundary.
///
/// The temperatures, conductivities and heat capacities are the DEM's per-body fields, read and
/// written through the particle exchange interface (other components see and change the same
/// values); this model gives its defaults to the bodies whose fields are NaN (not given) when it
/// first covers them. Bodies that are not live spheres are left out of every sum.
class ParticleConduction : public HeatModel
{
public:
  /// @param exchange the scene's particle exchange (copied; the scene must outlive this model)
  explicit ParticleConduction(dem::ParticleExchange exchange) : exchange_(exchange) {}

  /// Values new spheres start with (Yade's particleT0, particleK, particleCp).
  double initialTemperature = 0, defaultConductivity = 3.0, defaultHeatCapacity = 750.0;
  /// > 0: the density of the heat capacity instead of the body's mass (Yade's particleDensity).
  double particleDensity = 0;
  ContactConductance conductance = ContactConductance::Radii;

  /// Per body id (the DEM's fields): temperature (K or °C, as the user's values), conductivity
  /// (W/(m K)) and specific heat capacity (J/(kg K)).
  [[nodiscard]] std::span<double> temperatures() { return exchange_.temperatures(); }
  [[nodiscard]] std::span<const double> temperatures() const { return exchange_.temperatures(); }
  [[nodiscard]] std::span<const double> conductivities() const { return exchange_.conductivities(); }
  [[nodiscard]] std::span<const double> heatCapacities() const { return exchange_.heatCapacities(); }
  /// Per body covered: the boundary whose temperature it keeps, -1 for none.
  std::vector<std::int8_t> boundary;

  /// Cover the bodies added since the last call: give them a boundary entry, and the defaults
  /// above to those of their fields that are NaN (not given); the others keep their values.
  void resize();
  /// Hold `ids` at `value` as particles of boundary `k` (0..5).
  /// @param k the boundary, 0..5 (Yade's wall order: xmin, xmax, ymin, ymax, zmin, zmax)
  /// @param ids the spheres held
  /// @param value their temperature (the user's unit)
  /// @throws std::invalid_argument for a boundary outside 0..5 or an id that is not a live sphere
  void imposeTemperature(int k, const std::vector<dem::BodyId>& ids, double value);
  /// Heat `rates` (W, positive into the particle) into spheres `ids` through boundary `k`, at
  /// every step (a flux boundary; Talus's addition to Yade's insulated non-temperature sides).
  /// Replaces the earlier flux of that boundary; boundaryFlux reports the sum of the rates.
  /// @param k the boundary, 0..5
  /// @param ids live spheres (one held at a temperature takes none)
  /// @param rates one per id (W), finite
  /// @throws std::invalid_argument for a boundary outside 0..5, an id that is not a live sphere,
  ///         sizes that differ or a non-finite rate
  void imposeHeatFlux(int k, const std::vector<dem::BodyId>& ids, const std::vector<double>& rates);
  /// The spheres and rates of boundary k's flux (empty: none).
  [[nodiscard]] const std::vector<std::pair<dem::BodyId, double>>& heatFlux(int k) const
  {
    return heatFlux_.at(static_cast<std::size_t>(k));
  }
  /// Release every particle held by a boundary and remove every flux.
  void clearBoundaries();

  /// Heat rates and conductance sums of the current contacts and temperatures (the first half
  /// of a step; also gives stableTimeStep).
  void computeRates() override;
  /// Add an exchange with something else than a sphere (the pore fluid) to sphere `id`'s rate
  /// of the last computeRates: `rate` W into it through conductance `g` (W/K). Call
  /// computeStableStep after the last one.
  /// @param id a live sphere
  /// @param rate the heat rate into it (W)
  /// @param g the conductance of the exchange (W/K), added to its sum for the stable step
  void addExchange(dem::BodyId id, double rate, double g);
  /// stableTimeStep and limitingBody from the conductance sums (computeRates calls it).
  /// @throws std::invalid_argument naming a conducting sphere without heat capacity (no mass
  ///         and no particleDensity, or particleCp 0)
  void computeStableStep();
  /// Advance the temperatures by `dt` (s) with the rates of the last computeRates (explicit
  /// Euler); the heat rate into each boundary during it is kept (boundaryFlux).
  void applyRates(double dt) override;
  /// computeRates then applyRates(dt).
  /// @param dt the step (s)
  /// @throws std::invalid_argument as computeStableStep
  void advance(double dt)
  {
    computeRates();
    applyRates(dt);
  }
  /// The largest stable step of the explicit scheme at the last computeRates: min over free
  /// spheres of C_i / sum_j G_ij; below it each new temperature is a weighted mean of old ones
  /// (no overshoot, no growth). +inf without contacts.
  [[nodiscard]] double stableTimeStep() const override { return stableStep_; }
  [[nodiscard]] std::string limitingPart() const override { return "sphere " + std::to_string(limitingBody_); }
  /// The body whose step limits stableTimeStep (-1: none).
  [[nodiscard]] dem::BodyId limitingBody() const { return limitingBody_; }

  /// Heat rate (W) from the packing into each boundary's particles during the last step
  /// (Yade's thermalBndFlux: positive when the packing is hotter than the boundary); for a
  /// flux boundary, the heat rate it gives to the packing.
  [[nodiscard]] const std::array<double, kBoundaries>& boundaryFlux() const { return boundaryFlux_; }
  /// Heat (J) received by each boundary since the start (Talus: the energy balance).
  [[nodiscard]] const std::array<double, kBoundaries>& boundaryHeat() const { return boundaryHeat_; }
  /// @return the same sums, writable (Python's setBoundaryHeat sets them back)
  std::array<double, kBoundaries>& boundaryHeat() { return boundaryHeat_; }

  /// Heat capacity C_i (J/K) of sphere `id`.
  /// @param id a body id with an entry (after resize())
  /// @return m_i Cp_i, or rho V_i Cp_i with particleDensity > 0
  [[nodiscard]] double heatCapacityOf(dem::BodyId id) const;
  /// Conductance (W/K) of a real sphere-sphere contact (see ContactConductance).
  /// @return the conductance (W/K), from the two spheres' conductivities and the contact's size
  [[nodiscard]] double contactConductance(const dem::Contact& c) const;

private:
  /// Whether contact `c` conducts: real, between two live spheres.
  [[nodiscard]] bool conducts(const dem::Contact& c) const;

  dem::ParticleExchange exchange_;
  std::vector<double> rate_;        ///< heat rate into each body (W)
  std::vector<double> conductance_; ///< sum of the conductances of each body's contacts (W/K)
  double stableStep_ = 0;
  std::array<double, kBoundaries> boundaryFlux_{};
  std::array<double, kBoundaries> boundaryHeat_{};
  std::array<std::vector<std::pair<dem::BodyId, double>>, kBoundaries> heatFlux_{};
  dem::BodyId limitingBody_ = -1;
};
} // namespace talus::flow::thermal
