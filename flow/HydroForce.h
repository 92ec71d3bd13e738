#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace talus::flow
{
/// Parameters of the particle side of Yade's HydroForceEngine (forces and averaging). Names and
/// defaults are Yade 2023.02a's.
struct HydroForceParameters
{
  int nCell = 0;              ///< number of layers of the 1D grid [zRef, zRef + nCell deltaZ); >= 1
  double deltaZ = 0;          ///< layer height [m]; > 0
  double zRef = 0;            ///< elevation of the bottom of the grid [m]
  double densFluid = 1000.0;  ///< fluid density [kg/m^3]; > 0
  double viscoDyn = 1e-3;     ///< fluid dynamic viscosity [Pa s]; >= 0
  double expoRZ = 3.1;        ///< Richardson-Zaki exponent of the hindrance (1 - phi)^-expoRZ; >= 0
  bool lift = false;          ///< add the lift from the velocity difference across the particle
  double Cl = 0.2;            ///< lift coefficient
  /// Steady flow: the streamwise pressure gradient balances the fluid weight, so buoyancy has
  /// no streamwise part (Yade's steadyFlow, true by default).
  bool steadyFlow = true;
  std::array<double, 3> gravity{0.0, 0.0, -9.81};  ///< gravity vector [m/s^2]
  /// Volume of a layer [m^3] turning solid volumes into fractions (Yade's vCell); > 0 to average.
  double vCell = 0;
  /// Period of space along z [m] in a periodic cell (0: not periodic along z); elevations are
  /// wrapped into [zRef, zRef + periodZ) before they are located in the grid.
  double periodZ = 0;
  /// Particles in `ids` centred outside the grid (below zRef, or above zRef + nCell deltaZ): an
  /// error (false) or no fluid force (true, Yade's behaviour).
  bool ignoreOutside = false;
  // Turbulent velocity fluctuations (discrete random walk, Yade's turbulentFluctuationZDep).
  bool velFluct = false;          ///< apply the fluctuations in action()
  double bedElevation = 0;        ///< above zRef; particles below get no fluctuation [m]
  bool unCorrelatedFluctuations = false;  ///< x and z fluctuations independent (default correlated)
  double kappa = 0.41;            ///< von Karman constant of the eddy time scale

  /// @throws std::invalid_argument naming the first parameter out of range or not finite
  void validate() const;
};

/// The particle arrays a coupling reads, indexed by body id (the particle exchange interface:
/// O.positions(), O.velocities(), O.radii() in Python, ParticleExchange in C++).
struct ParticleArrays
{
  std::span<const double> positions;   ///< 3 values per body
  std::span<const double> velocities;  ///< 3 values per body
  std::span<const double> radii;       ///< 1 value per body
};

/// Result of averageProfile: per layer of the grid.
struct SolidProfile
{
  std::vector<double> phiPart;      ///< solid volume fraction
  std::vector<double> vxPart, vyPart, vzPart;  ///< solid-volume weighted mean particle velocity [m/s]
  std::vector<double> averageDrag;  ///< solid-volume weighted mean streamwise drag per particle [N]
};

/// Hydrodynamic forces on spheres from a 1D vertical streamwise fluid velocity profile, and the
/// solid-phase averaging that feeds the fluid resolution (Yade's HydroForceEngine.action and
/// averageProfile; seed chapter 15.2-15.3).
///
/// A particle at elevation z lies in layer p = floor((z - zRef)/deltaZ), 0 <= p < nCell; the
/// fluid velocity it sees is vxFluid[p + 1] (the velocity node at the centre of layer p, as in
/// VansFluid; for the top layer, the surface node), the solid fraction phiPart[p]. Forces:
/// - drag f_D = 1/2 rho pi r^2 (0.44 |u_r| + 24.4 nu / (2 r)) (1 - phi)^-expoRZ u_r, with
///   u_r = (vxFluid + u'_x, u'_y, u'_z) - v (Dallavalle's drag coefficient 0.44 + 24.4/Re_p
///   with Yade's constants, Richardson-Zaki hindrance);
/// - buoyancy -rho V g, without its streamwise part if steadyFlow;
/// - lift (optional) 1/2 rho pi r^2 Cl (u_top^2 - u_bottom^2) e_z, u_top and u_bottom the
///   relative streamwise velocities one radius (in whole layers) above and below.
class HydroForce
{
public:
  /// @param parameters the model's parameters (copied); the profiles start as zeros (nCell + 1
  ///        velocities, nCell fractions and stresses)
  /// @throws std::invalid_argument naming the offending parameter
  explicit HydroForce(const HydroForceParameters& parameters);

  /// The current parameters.
  [[nodiscard]] const HydroForceParameters& parameters() const noexcept { return m_parameters; }
  /// Replace the parameters. Changing nCell resets the profiles to zeros.
  /// @param parameters the new parameters (copied)
  /// @throws std::invalid_argument naming the offending parameter; nothing is changed then
  void setParameters(const HydroForceParameters& parameters);

  /// Fluid velocity at the nCell + 1 velocity nodes (VansFluid's layout).
  /// @param vxFluid streamwise velocities [m/s], nCell + 1 values
  /// @throws std::invalid_argument on another count or a value not finite
  void setVxFluid(std::span<const double> vxFluid);
  /// Solid fraction per layer used by the hindrance.
  /// @param phiPart nCell values in [0, 1)
  /// @throws std::invalid_argument on another count or a value out of range
  void setPhiPart(std::span<const double> phiPart);
  /// Reynolds shear stress per mesh node, scaling the fluctuations.
  /// @param stresses nCell values [Pa]
  /// @throws std::invalid_argument on another count or a value not finite
  void setReynoldStresses(std::span<const double> stresses);
  /// The profiles last set (views into this object, valid until the next set or nCell change).
  [[nodiscard]] std::span<const double> vxFluid() const noexcept { return m_vxFluid; }
  [[nodiscard]] std::span<const double> phiPart() const noexcept { return m_phiPart; }
  [[nodiscard]] std::span<const double> reynoldStresses() const noexcept { return m_reynoldStresses; }

  /// Add the fluid force of each particle in `ids` to `forces` (3 values per body). If velFluct,
  /// first advance the fluctuations' random walk by `dt` (their eddy lives count down).
  /// @param particles the scene's particle arrays, by body id
  /// @param ids the bodies that feel the fluid
  /// @param forces 3 values per body of the arrays, added to
  /// @param dt the time since the last call [s]
  /// @throws std::invalid_argument if `forces` has not 3 values per body, for an id that is not
  ///         a body of the arrays or has no positive radius, or (unless ignoreOutside) a particle
  ///         outside the grid; nothing is added then
  void action(const ParticleArrays& particles, std::span<const std::int64_t> ids, std::span<double> forces,
              double dt);

  /// The fluid force action() would add to particle `id`.
  /// @param particles the scene's particle arrays, by body id
  /// @param id the body
  /// @return the force [N], zero outside the grid
  /// @throws std::invalid_argument if id is not a body of the arrays or has no positive radius
  [[nodiscard]] std::array<double, 3> force(const ParticleArrays& particles, std::int64_t id) const;

  /// Solid fraction, mean velocity and mean streamwise drag per layer over the spheres `ids`,
  /// each sphere split between the layers it crosses with the exact volume of each slice
  /// (V = pi r^2 (b - a) - pi (b^3 - a^3)/3 between heights a < b from its centre).
  /// @param particles the scene's particle arrays, by body id
  /// @param ids the spheres averaged over
  /// @return the profiles, nCell values each
  /// @throws std::invalid_argument if vCell <= 0, or an id is not a body of the arrays
  [[nodiscard]] SolidProfile averageProfile(const ParticleArrays& particles, std::span<const std::int64_t> ids) const;

  /// Draw a new fluctuation for every particle of `ids` now (Yade's turbulentFluctuation), and
  /// restart its eddy life. Deterministic for a given seed and call sequence.
  /// @param particles the scene's particle arrays, by body id
  /// @param ids the bodies given a new fluctuation
  /// @throws std::invalid_argument if an id is not a body of the arrays or has no positive radius
  void turbulentFluctuation(const ParticleArrays& particles, std::span<const std::int64_t> ids);
  /// Current fluctuation (u'_x, u'_y, u'_z) of each body, 3 values per body (zero if none).
  [[nodiscard]] std::span<const double> fluctuations() const noexcept { return m_fluct; }
  /// Remaining eddy life of each body's fluctuation [s].
  [[nodiscard]] std::span<const double> fluctuationLife() const noexcept { return m_life; }
  /// Restart the random number generator (std::mt19937_64, seeded 0 at construction).
  /// @param value the seed
  void seed(std::uint64_t value) { m_random.seed(value); }

  /// Volume of the part of a sphere of radius r between heights a and b from its centre.
  /// @param r the radius [m]
  /// @param a, b the heights from the centre (clipped to [-r, r]; nothing if b <= a)
  /// @return the volume [m^3]
  [[nodiscard]] static double sliceVolume(double r, double a, double b);

private:
  /// Elevation above zRef, wrapped into the period along z if any.
  [[nodiscard]] double elevation(double z) const;
  [[nodiscard]] std::array<double, 3> dragForce(double radius, int layer, const double* vel, std::size_t id) const;
  /// Force on a particle known to be in `layer` of the grid.
  [[nodiscard]] std::array<double, 3> forceInLayer(const ParticleArrays& particles, std::size_t id, int layer) const;
  void updateHindrance();
  void checkId(const ParticleArrays& particles, std::int64_t id, const char* what) const;
  void drawFluctuation(std::size_t id, double height);
  void resizeFluctuations(std::size_t bodies);

  HydroForceParameters m_parameters;
  std::vector<double> m_vxFluid, m_phiPart, m_reynoldStresses;
  std::vector<double> m_hindrance;  ///< (1 - phiPart)^-expoRZ per layer, cached
  std::vector<int> m_layers;        ///< scratch: layer of each id in action()
  std::vector<double> m_fluct, m_life;
  std::mt19937_64 m_random{0};
  std::normal_distribution<double> m_normal{0.0, 1.0};
};
} // namespace talus::flow
