#pragma once

#include "dem/Engine.h"
#include "dem/types.h"

#include <cstdint>
#include <vector>

namespace talus::dem
{
/// Leap-frog integration of Newton's and Euler's equations (Yade's NewtonIntegrator).
///
/// For each dynamic body: a = F/m + g, then Cundall's non-viscous damping on each component,
/// a_i <- a_i (1 - damping sign(a_i (v_i + a_i dt/2))) (gravity is damped too, as in Yade);
/// v += a dt; x += v dt. Rotation of spheres: the same with torque / inertia, and the
/// orientation turned by the rotation vector omega dt. Blocked DOFs keep their velocity.
/// Non-dynamic bodies move with their imposed velocities.
class NewtonIntegrator : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "NewtonIntegrator"; }

  Vec3 gravity = Vec3::Zero();
  double damping = 0.2; ///< Yade's default

private:
  // 1/m and 1/I of every body (0 where blocked or not dynamic), refreshed when bodies change,
  // so the step multiplies instead of dividing.
  void refreshInverses(const Scene& scene);
  /// The step for every body; Track: accumulate gravity's work and the damping's dissipation.
  /// @return the first body with a non-finite force or torque, or -1
  template <bool Track>
  std::int64_t integrate(Scene& scene) const;
  std::vector<Vec3> invMass_, invInertia_;
  std::int64_t seenBodiesVersion_ = -1, seenPropertiesVersion_ = -1;
};
} // namespace talus::dem
