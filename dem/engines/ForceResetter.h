#pragma once

#include "dem/core/Engine.h"
#include "dem/base/Threads.h"

namespace talus::dem
{
struct Bodies;

/// Starts a step: every body's force and torque become its persistent external force and
/// torque (zero unless a coupling or the user set them), ready for contacts to add to.
class ForceResetter : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "ForceResetter"; }
  /// The reset, per body.
  [[nodiscard]] Stages stages() const override { return Stages{}.with(StagePoint::Reset, Grain::PerBody); }
  /// run()'s work on the bodies [first, last) (for the step scheduler's parallel regions).
  /// @param first first body id of the share
  /// @param last one past the last body id (at most bodies.size())
  static void resetIn(Bodies& bodies, std::int64_t first, std::int64_t last);

private:
  BalancedRanges ranges_; ///< bodies per thread
};
} // namespace talus::dem
