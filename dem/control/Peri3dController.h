#pragma once

#include "dem/core/Engine.h"
#include "dem/base/types.h"

#include <array>
#include <functional>
#include <vector>

namespace talus::dem
{
class Scene;

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Vec6i = Eigen::Matrix<int, 6, 1>;

/// Yade's Peri3dController: drives all six components (Voigt order xx, yy, zz, yz, zx, xy) of
/// the periodic cell's strain, each to a prescribed strain or, if its bit of stressMask is set,
/// to a prescribed Love-Weber stress, along a piecewise linear path in `progress` (0 to 1 over
/// nSteps steps). Place it after the NewtonIntegrator, as Yade's examples do.
///
/// Strain components get the path's rate directly. A stress component's strain rate is
/// corrected every step by +-mod times the largest strain rate, against the sign of the
/// linearly extrapolated gap between the stress and the ideal (path) stress; on the first step
/// of a "stress-based" run it is estimated from an isotropic compliance (youngEstimation,
/// poissonEstimation). All rates are scaled down together to maxStrainRate, and progress then
/// advances by less than 1/nSteps. The strain increment is applied to the unrotated stretch of
/// the cell's polar decomposition, so that a rotated cell keeps its rotation. When progress
/// reaches 1 or a strain exceeds maxStrain, doneHook is called (every step from then on), or,
/// without one, the engine dies and the run pauses.
class Peri3dController : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "Peri3dController"; }

  // parameters
  Vec6 goal = Vec6::Zero();
  int stressMask = 0;
  int nSteps = 1000;
  double maxStrainRate = 1e3;
  double maxStrain = 1e6;
  double mod = .1;
  double youngEstimation = 1e20;
  double poissonEstimation = .25;
  /// (progress, value) points of xx, yy, zz, yz, zx, xy; normalised in place on the first step
  /// (progress by the last point's, values by goal / last value unless the last value is 0).
  std::array<std::vector<Eigen::Vector2d>, 6> paths;
  std::function<void()> doneHook;

  // state and read-outs (strain: the sum of the prescribed rates times dt, engineering shears)
  double progress = 0;
  Vec6 stress = Vec6::Zero(), strain = Vec6::Zero(), strainRate = Vec6::Zero(), stressRate = Vec6::Zero();
  Vec6 stressIdeal = Vec6::Zero(), stressGoal = Vec6::Zero(), strainGoal = Vec6::Zero();
  Vec6i ps = Vec6i::Zero(), pe = Vec6i::Zero(), pathSizes = Vec6i::Zero(), pathsCounter = Vec6i::Zero();
  int lenPs = 0, lenPe = 0;

  /// Every path the single point (1, 1): each component goes linearly to its goal (Yade's default).
  Peri3dController();

private:
  bool start();
  void pathRates(double dt);
  void predictStressRates(bool firstStressBasedStep, const Vec6& stressOld, double dt);
};
} // namespace talus::dem
