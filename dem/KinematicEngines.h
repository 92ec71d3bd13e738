#pragma once

#include "dem/Engine.h"
#include "dem/types.h"

#include <vector>

namespace talus::dem
{
/// Imposes the velocity and angular velocity of the bodies `ids` every step (Yade's
/// KinematicEngine): it zeroes them, then `apply` adds the engine's motion. Place it before
/// NewtonIntegrator, which moves non-dynamic bodies with these velocities (fixed walls, facets,
/// boxes, clumps), so contacts see the boundary's true velocity at the contact point.
class KinematicEngine : public Engine
{
public:
  void run(Scene& scene) override;

  std::vector<BodyId> ids;

protected:
  /// Add this engine's velocities to the (zeroed) velocities of `ids`.
  virtual void apply(Scene& scene) = 0;
};

/// Translation at `velocity` along `translationAxis` (normalised when run, as in Yade).
class TranslationEngine : public KinematicEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "TranslationEngine"; }
  Vec3 translationAxis = Vec3::UnitX();
  double velocity = 0;

protected:
  void apply(Scene& scene) override;
};

/// Rotation at `angularVelocity` (rad/s) about `rotationAxis`; with `rotateAroundZero` the
/// bodies also orbit the axis through `zeroPoint`: their velocity is the chord they travel in
/// one step divided by dt, so they stay on the circle exactly (Yade's RotationEngine).
class RotationEngine : public KinematicEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "RotationEngine"; }
  Vec3 rotationAxis = Vec3::UnitX();
  double angularVelocity = 0;
  bool rotateAroundZero = false;
  Vec3 zeroPoint = Vec3::Zero();

protected:
  void apply(Scene& scene) override;
};

/// Harmonic oscillation x = A cos(2 pi f t + fi) per axis, imposed as its velocity
/// -A w sin(w t + fi) with w = 2 pi f (Yade's HarmonicMotionEngine).
class HarmonicMotionEngine : public KinematicEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "HarmonicMotionEngine"; }
  Vec3 A = Vec3::Zero();
  Vec3 f = Vec3::Zero();
  Vec3 fi = Vec3::Constant(M_PI / 2);

protected:
  void apply(Scene& scene) override;
};
} // namespace talus::dem
