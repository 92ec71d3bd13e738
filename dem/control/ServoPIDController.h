#pragma once

#include "dem/impose/KinematicEngines.h"

#include <cstdint>

namespace talus::dem
{
/// A translation whose speed a PID controller sets so that the force on the bodies along
/// `axis` reaches `target` (Yade's ServoPIDController): every `iterPeriod` steps the error
/// e = |F . axis-components| - target of the summed force F on `ids` gives the speed
/// kP e + kI sum(e) + kD (e - e_previous), capped at |maxVelocity|; in between the speed stays.
class ServoPIDController : public TranslationEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "ServoPIDController"; }
  Vec3 axis = Vec3::Zero();
  double target = 0, maxVelocity = 0, kP = 0, kI = 0, kD = 0;
  std::int64_t iterPeriod = 100;
  // controller state, as Yade's read-only attributes
  std::int64_t iterPrevStart = -1;
  double errorCur = 0, errorPrev = 0, iTerm = 0, curVel = 0;
  Vec3 current = Vec3::Zero(); ///< the force components along axis at the last update

  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
};
} // namespace talus::dem
