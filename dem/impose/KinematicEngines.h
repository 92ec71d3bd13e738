#pragma once

#include "dem/core/Engine.h"
#include "dem/base/types.h"

#include <memory>
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

  /// Add this engine's velocities to the (zeroed) velocities of `bodies` (its own ids, or those
  /// of a CombinedKinematicEngine it is part of).
  /// @param bodies the rows moved (Scene::rowsActedOn of the ids; velocities in m/s and rad/s added, not set)
  virtual void apply(Scene& scene, const std::vector<BodyId>& bodies) = 0;
};

/// Several kinematic engines moving the same bodies (Yade's CombinedKinematicEngine, made by
/// `engine + engine` in Python): the velocities are zeroed once, then each engine of `comb`
/// that is not dead adds its motion to `ids`, in order.
class CombinedKinematicEngine : public KinematicEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "CombinedKinematicEngine"; }
  std::vector<std::shared_ptr<KinematicEngine>> comb;
  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
};

/// Translation at `velocity` along `translationAxis` (normalised when run, as in Yade).
class TranslationEngine : public KinematicEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "TranslationEngine"; }
  Vec3 translationAxis = Vec3::UnitX();
  double velocity = 0;

  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
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

  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
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

  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
};
/// A screw motion (Yade's HelixEngine): the rotation of RotationEngine about the axis through
/// `zeroPoint` (always orbiting it) plus `linearVelocity` along the axis; `angleTurned` adds up
/// the angle.
class HelixEngine : public RotationEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "HelixEngine"; }
  double linearVelocity = 0;
  double angleTurned = 0;
  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
};

/// HelixEngine whose angular velocity is read from the table (`times`, `angularVelocities`)
/// at the current time (linear between readings; `wrap`: the table repeats), with
/// linearVelocity = slope x angularVelocity (Yade's InterpolatingHelixEngine).
class InterpolatingHelixEngine : public HelixEngine
{
public:
  [[nodiscard]] std::string typeName() const override { return "InterpolatingHelixEngine"; }
  std::vector<double> times, angularVelocities;
  bool wrap = false;
  double slope = 0;
  void apply(Scene& scene, const std::vector<BodyId>& bodies) override;
};
} // namespace talus::dem
