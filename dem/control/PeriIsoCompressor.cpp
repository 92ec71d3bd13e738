#include "dem/control/PeriIsoCompressor.h"

#include "dem/measure/Measurements.h"
#include "dem/core/Scene.h"

#include <algorithm>
#include <cmath>
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
    double largest = 0;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.alive[i] && b.shape[i] == ShapeKind::Sphere)
        largest = std::max(largest, 2 * b.radius[i]);
    if (charLen <= 0)
    {
      if (b.size() == 0 || b.shape[0] != ShapeKind::Sphere)
        throw std::runtime_error("PeriIsoCompressor: charLen is not given and body 0 is not a sphere to take it from");
      charLen = 2 * b.radius[0];
    }
    if (maxSpan <= 0)
      maxSpan = largest;
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
    Vec3 force = Vec3::Zero();
    double stiffness = 0;
    long n = 0;
    for (const Contact& c : scene.contacts.list)
    {
      if (!c.real)
        continue;
      force += c.force.cwiseAbs();
      stiffness += c.kn / 3. + 2. * c.ks / 3.; // kn along one direction, ks along the other two
      ++n;
    }
    avgStiffness = n > 0 ? stiffness / static_cast<double>(n) : -1;
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
