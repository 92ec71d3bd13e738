#pragma once

#include "dem/core/EnergyTracker.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace talus::dem
{
class Scene;

/// Split over processes (Scene::domain), kineticEnergy, kineticEnergyParts and elasticPotential
/// are this process's share: the bodies and contacts it counts (Domain::countsBody,
/// countsContact), each body and contact counted by one process; energyValues adds the shares.

/// Sum of 1/2 m v^2 + 1/2 w.I w over dynamic bodies (clumps as one body, aspherical bodies in
/// their principal frame; fluctuating velocities in a homogeneously deforming periodic cell).
/// @return the energy (J)
double kineticEnergy(const Scene& scene);
/// The two parts of kineticEnergy, summed body by body in id order: {translational, rotational}
/// (Yade's kinTrans and kinRot, which NewtonIntegrator's kinSplit books instead of kinetic).
/// @return {translational, rotational} (J)
std::pair<double, double> kineticEnergyParts(const Scene& scene);
/// Each body's part of kineticEnergy (0 for those it does not count: erased, not dynamic, clump
/// members), indexed by id.
/// @return one energy (J) per body id
std::vector<double> bodyKineticEnergies(const Scene& scene);
/// Elastic energy stored in the contacts of the scene's InteractionLoop(s), as each law defines
/// it (1/2 Fn^2/kn + 1/2 Fs^2/ks for linear springs, 2/5 Fn u for Hertz, moments as springs).
/// @return the energy (J)
double elasticPotential(const Scene& scene);

/// O.energy's values, the whole scene's: the state energies computed now and the accumulated
/// terms of the tracker (EnergyTracker).
struct EnergyValues
{
  double kinetic = 0, kinTrans = 0, kinRot = 0, elastPotential = 0, gravWork = 0, nonviscDamp = 0, plastDissip = 0,
         viscDamp = 0, velGradWork = 0, kinematicWork = 0, growthWork = 0;
  /// Every term but the kinetic parts (kinTrans + kinRot is kinetic): what the balance adds up.
  /// @return the sum (J)
  [[nodiscard]] double total() const;
  /// The sum of the terms' magnitudes (the energy that flowed).
  /// @return the sum (J)
  [[nodiscard]] double flowed() const;
};
/// The scene's energies. Split over processes, each term is the sum of the processes' shares
/// (their own bodies, each contact once), in one reduction: every process must call it. The
/// shares are added in another order than the serial run's sums: the values equal the serial
/// run's within round-off, not bit for bit.
/// @return the energies (J)
EnergyValues energyValues(const Scene& scene);

/// Steps between two checks of energy growth (kinetic and elastic energies cost a pass over
/// bodies and contacts).
inline constexpr std::int64_t energyGrowthCheckPeriod = 100;

/// The instability check on energy (Scene::maxEnergyGrowth): the total of a tracked scene is
/// conserved up to the dissipation's discretisation error, so a total grown beyond its first
/// checked value by more than maxEnergyGrowth of the energy that flowed (the sum of the terms'
/// magnitudes) means the step is unstable.
/// @param scene the tracked scene; the first call records the total it compares with
/// @throws std::runtime_error on such growth, naming the body with the largest kinetic energy,
///         the step and the stable step estimates
void checkEnergyGrowth(Scene& scene);
} // namespace talus::dem
