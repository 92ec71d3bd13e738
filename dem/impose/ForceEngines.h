#pragma once

#include "dem/core/Engine.h"
#include "dem/base/types.h"

#include <string>
#include <vector>

namespace talus::dem
{
/// Adds `force` to the bodies `ids` every step (Yade's ForceEngine). Place it between
/// ForceResetter and NewtonIntegrator.
class ForceEngine : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "ForceEngine"; }

  std::vector<BodyId> ids;
  Vec3 force = Vec3::Zero();

protected:
  /// Add `f` to the force of every body of `ids`.
  /// @throws std::out_of_range naming the engine and the id of a body that does not exist
  void addToBodies(Scene& scene, const Vec3& f) const;
};

/// ForceEngine whose magnitude is read from the table (`times`, `magnitudes`) at the current
/// time (linear between readings; `wrap`: the table repeats), along `direction` (normalised
/// when run, as Yade does): Yade's InterpolatingDirectedForceEngine. `force` holds the force of
/// the last step.
class InterpolatingDirectedForceEngine : public ForceEngine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "InterpolatingDirectedForceEngine"; }

  std::vector<double> times, magnitudes;
  Vec3 direction = Vec3::UnitX();
  bool wrap = false;
};

/// A harmonic force A_k sin(2 pi f_k t + fi_k) per axis k on the bodies `ids` (Yade's
/// HarmonicForceEngine).
class HarmonicForceEngine : public ForceEngine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "HarmonicForceEngine"; }

  Vec3 A = Vec3::Zero();
  Vec3 f = Vec3::Zero();
  Vec3 fi = Vec3::Zero();
};

/// A homogeneous gravity field as an engine (Yade's GravityEngine, which Yade calls deprecated in
/// favour of NewtonIntegrator.gravity): adds gravity x mass to every body but clumps (whose
/// members get theirs). With energy tracking it books gravWork as Yade does, -m g.v dt with the
/// velocity the body has when the engine runs.
class GravityEngine : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "GravityEngine"; }

  Vec3 gravity = Vec3::Zero();
  bool warnOnce = true; ///< print Yade's deprecation notice at the first run
  int mask = 0;         ///< nonzero: only the bodies whose group mask shares a bit with it (Yade's)
};

/// Gravity that follows a laptop's tilt (Yade's HdapsGravityEngine): reads the accelerometer's
/// sysfs files `hdapsDir`/calibrate (once, unless `calibrated`) and `hdapsDir`/position (at most
/// every `msecUpdate` ms; a component that moved more than `updateThreshold` from the last
/// reading is followed), and turns `zeroGravity` by half the readings in degrees about -y and -x
/// into `gravity`, applied as GravityEngine applies it. As in Yade, a missing or unreadable file
/// stops the run with an error naming it.
class HdapsGravityEngine : public GravityEngine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "HdapsGravityEngine"; }

  std::string hdapsDir = "/sys/devices/platform/hdaps";
  double msecUpdate = 50;
  int updateThreshold = 4;
  Eigen::Vector2i calibrate = Eigen::Vector2i::Zero();
  bool calibrated = false;
  Vec3 zeroGravity = Vec3(0, 0, -1);
  Eigen::Vector2i accel = Eigen::Vector2i::Zero(); ///< the reading followed, less the calibration

private:
  double lastReading_ = -1e300; ///< wall-clock seconds of the last reading
};
} // namespace talus::dem
