#pragma once

#include "dem/core/Engine.h"
#include "dem/base/types.h"

#include <cstdint>
#include <limits>

namespace talus::dem
{
class Scene;

/// Yade's GlobalStiffnessTimeStepper: sets the time step to a fraction of the smallest
/// eigen-period of the bodies' oscillations on their contacts (seed 3.5, "stability").
///
/// Per dynamic body, the diagonal of its translational stiffness sum over contacts of
/// (kn - ks) n_i^2 + ks and of its rotational stiffness ks r^2 (1 - n_i^2); its critical step
/// is sqrt(2) sqrt(min(m / max_i K_i, min_i I_i / R_i)). The scene's step becomes
/// timestepSafetyCoefficient times the smallest, capped at maxDt and at 1.05 times the previous
/// one. Contacts with no normal force are skipped; before any contact the step is `defaultDt`
/// (timestepSafetyCoefficient x P-wave estimate if negative).
///
/// With `viscEl` (Yade's option for dashpot contacts), the contacts' dashpots cn, cs are summed
/// the same way into a translational and a rotational viscosity per body, and the body's step is
/// also at most 2 timestepSafetyCoefficient min(m / max_i C_i, min_i I_i / Cr_i): the explicit
/// scheme's limit for a dashpot (not a square root: m / C is a time).
class GlobalStiffnessTimeStepper : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "GlobalStiffnessTimeStepper"; }

  /// The step that the current contacts allow (timestepSafetyCoefficient included), +inf if no
  /// body has a loaded contact. Reads the contacts as they are; changes nothing. Split over
  /// processes, the smallest over them (collective).
  /// @return the time step (s)
  [[nodiscard]] double stiffnessTimeStep(const Scene& scene) const;

  bool active = true;
  bool viscEl = false;
  double timestepSafetyCoefficient = 0.8;
  double defaultDt = -1;
  double maxDt = std::numeric_limits<double>::max();
  std::int64_t timeStepUpdateInterval = 1;
  double previousDt = std::numeric_limits<double>::max(); ///< last step set
  bool computedOnce = false;
};

/// Yade's RayleighWaveTimeStep: min over spheres of pi r / (0.1631 nu + 0.876605) sqrt(rho / G),
/// G = E / (2 (1 + nu)), rho from the sphere's mass. +inf without spheres.
/// @return the time step (s), no safety factor applied
double rayleighWaveTimeStep(const Scene& scene);
} // namespace talus::dem
