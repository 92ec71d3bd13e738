#pragma once

#include "dem/control/TriaxialStressController.h"

#include <string>

namespace talus::dem
{
/// Yade's ThreeDTriaxialEngine: a TriaxialStressController whose axes are each controlled
/// either in stress (stressControl_i: the walls of axis i keep goal_i) or in strain (the two
/// walls of axis i approach each other at a rate that relaxes towards strainRate_i by
/// (1 - strainRateDamping) per step; positive rates compress). With internalCompaction the
/// spheres grow as in the controller. The first step switches the walls of strain-controlled
/// axes off for the stress control (wall_*_activated) and, with updateFrictionAngle, sets the
/// friction to frictionAngleDegree.
class ThreeDTriaxialEngine : public TriaxialStressController
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "ThreeDTriaxialEngine"; }

  // parameters (Yade's names and defaults)
  Vec3 strainRate = Vec3::Zero();         ///< strainRate1..3
  Vec3 currentStrainRate = Vec3::Zero();  ///< currentStrainRate1..3
  std::array<bool, 3> stressControl{true, true, true};
  /// Yade's ThreeDTriaxialEngine.strainDamping (it hides the controller's strainDamping).
  double strainRateDamping = 0.9997;
  double frictionAngleDegree = -1;
  bool updateFrictionAngle = false;
  double UnbalancedForce = 1; ///< kept for Yade's scripts; Yade's engine does not update it
  std::string Key;
  bool firstRun = true;
};

} // namespace talus::dem
