#include "dem/control/PeriIsoCompressor.h"

#include "dem/measure/Measurements.h"
#include "dem/core/Domain.h"
#include "dem/core/Scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::dem
{
namespace
{
double sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }
} // namespace

void PeriIsoCompressor::run(Scene& scene)
{
  if (!scene.periodic)
    throw std::runtime_error("PeriIsoCompressor: the scene is not periodic (set O.periodic = True)");
  if (!(scene.dt > 0))
    throw std::runtime_error("PeriIsoCompressor: the time step must be positive");
  if (state >= stresses.size())
    return;
  const Bodies& b = scene.bodies;
  if (charLen <= 0 || maxSpan <= 0)
  {
    // The largest sphere and body 0's diameter over the processes (+inf: body 0 is no sphere
    // here; split over processes, it is a sphere of another process, or no sphere anywhere).
    std::array<double, 2> smallest{0, std::numeric_limits<double>::infinity()};
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.alive[i] && b.shape[i] == ShapeKind::Sphere)
        smallest[0] = std::min(smallest[0], -2 * b.radius[i]);
    const std::int64_t first = scene.domain ? scene.domain->rowOf(0) : 0;
    if (first >= 0 && static_cast<std::size_t>(first) < b.size())
    {
      const auto row = static_cast<std::size_t>(first);
      if (b.alive[row] && b.shape[row] == ShapeKind::Sphere)
        smallest[1] = 2 * b.radius[row];
    }
    if (scene.domain)
      scene.domain->min(smallest);
    if (charLen <= 0)
    {
      if (std::isinf(smallest[1]))
        throw std::runtime_error("PeriIsoCompressor: charLen is not given and body 0 is not a sphere to take it from");
      charLen = smallest[1];
    }
    if (maxSpan <= 0)
      maxSpan = -smallest[0];
  }
  if (maxDisplPerStep < 0)
    maxDisplPerStep = 1e-2 * charLen;
  const Vec3 size = scene.cell.hSize.colwise().norm();
  const Vec3 area(size[1] * size[2], size[0] * size[2], size[0] * size[1]);
  const double minSize = size.minCoeff(), maxSize = size.maxCoeff();
  if (minSize < 2.1 * maxSpan)
    throw std::runtime_error("PeriIsoCompressor: the cell became smaller than 2.1 times the largest sphere");
  if (scene.iter % std::max(globalUpdateInt, 1) == 0 || avgStiffness < 0 || (sigma.array() < 0).any())
  {
    const auto [force, stiffness] = totalForceInVolume(scene); // Yade's measure; exact over processes
    avgStiffness = stiffness;
    sigma = -force.cwiseQuotient(area);
  }
  const double goal = stresses[state];
  const double K = avgStiffness > 0 ? avgStiffness : 1.;
  Vec3 grow = Vec3::Zero();
  bool reached = true;
  if (keepProportions)
  {
    const double meanSigma = sigma.mean(), meanArea = area.mean(), meanSize = size.mean();
    double meanGrow = 1e-4 * (goal - meanSigma) * meanArea / K;
    const double maxToMean = maxSize / meanSize;
    if (std::abs(maxToMean * meanGrow) > maxDisplPerStep)
      meanGrow = sign(meanGrow) * maxDisplPerStep / maxToMean;
    if (meanGrow < -(minSize - 2.1 * maxSpan) / maxToMean)
      throw std::runtime_error("PeriIsoCompressor: the cell cannot shrink further (2.1 times the largest sphere) "
                               "although the stress asks for it: stiffer particles, a larger sample or a lower stress");
    if (avgStiffness > 0)
      sigma += Vec3::Constant(meanGrow * avgStiffness);
    reached = std::abs((sigma.mean() - goal) / goal) <= 5e-3;
    grow = meanGrow / meanSize * size;
  }
  else
    for (int a = 0; a < 3; ++a)
    {
      grow[a] = 1e-4 * (goal - sigma[a]) * area[a] / K;
      if (std::abs(grow[a]) > maxDisplPerStep)
        grow[a] = sign(grow[a]) * maxDisplPerStep;
      grow[a] = std::max(grow[a], -(size[a] - 2.1 * maxSpan));
      if (avgStiffness > 0)
        sigma[a] += grow[a] * avgStiffness;
      reached = reached && std::abs((sigma[a] - goal) / goal) <= 5e-3;
    }
  for (int a = 0; a < 3; ++a)
    scene.cell.velGrad(a, a) = grow[a] / (scene.dt * size[a]);
  if (!reached)
    return;
  if (scene.iter % std::max(globalUpdateInt, 1) == 0)
    currUnbalanced = unbalancedForce(scene, sceneGravity(scene));
  if (currUnbalanced >= 0 && currUnbalanced < maxUnbalanced)
  {
    ++state;
    if (state == stresses.size() && doneHook)
      doneHook();
  }
}
} // namespace talus::dem
