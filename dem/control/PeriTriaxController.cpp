#include "dem/control/PeriTriaxController.h"

#include "dem/measure/Measurements.h"
#include "dem/core/Domain.h"
#include "dem/core/Scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
double sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }
} // namespace

void PeriTriaxController::update(const Scene& scene)
{
  for (int i = 0; i < 3; ++i)
    strain[i] = std::log(scene.cell.trsf(i, i));
  // The stiffness sums and the contact count, exact: the same bits split over processes (each
  // contact counted on one), which the cell's update needs (it must be the serial one on all).
  std::array<ExactSum, 4> sum;
  if (!dynCell)
  {
    for (const Contact& c : scene.contacts.list)
    {
      if (!countsInSums(scene, c))
        continue;
      for (int i = 0; i < 3; ++i)
        sum[static_cast<std::size_t>(i)] += std::abs(c.normal[i]) * c.kn + (1 - std::abs(c.normal[i])) * c.ks;
      sum[3] += 1;
    }
    sumExactly(scene.domain.get(), sum);
  }
  stressTensor = loveWeberStress(scene);
  stress = stressTensor.diagonal();
  const double n = sum[3].value();
  stiff = n > 0 ? Vec3(Vec3(sum[0].value(), sum[1].value(), sum[2].value()) / n) : Vec3::Zero();
}

void PeriTriaxController::run(Scene& scene)
{
  if (!scene.periodic)
    throw std::runtime_error("PeriTriaxController: the scene is not periodic (set O.periodic = True)");
  if (!(scene.dt > 0))
    throw std::runtime_error("PeriTriaxController: the time step must be positive");
  const Bodies& b = scene.bodies;
  const Vec3 size = scene.cell.hSize.colwise().norm();
  const Vec3 area(size[1] * size[2], size[0] * size[2], size[0] * size[1]);
  if (maxBodySpan[0] <= 0)
  {
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.alive[i] && b.shape[i] == ShapeKind::Sphere)
        maxBodySpan = maxBodySpan.cwiseMax(Vec3::Constant(2 * b.radius[i]));
    if (scene.domain) // the largest over the processes' spheres
    {
      Vec3 negated = -maxBodySpan;
      scene.domain->min(std::span<double>(negated.data(), 3));
      maxBodySpan = -negated;
    }
  }
  for (int a = 0; a < 3; ++a)
    if (2.1 * maxBodySpan[a] > size[a])
      throw std::runtime_error("PeriTriaxController: the cell (size " + std::to_string(size[a]) + " along axis "
                               + std::to_string(a) + ") became smaller than 2.1 times the largest sphere diameter");
  const bool doUpdate = scene.iter % std::max(globUpdate, 1) == 0;
  if (doUpdate || stiff.minCoeff() <= 0 || dynCell)
    update(scene);
  if (dynCell && std::isnan(mass))
  {
    std::array<ExactSum, 1> total; // the same bits split over processes
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.alive[i] && countsBody(scene.domain.get(), i))
        total[0] += b.mass[i];
    sumExactly(scene.domain.get(), total);
    mass = total[0].value();
  }
  const double dt = scene.dt;
  bool allOk = true;
  for (int a = 0; a < 3; ++a)
  {
    double& rate = scene.cell.velGrad(a, a);
    if (stressMask & (1 << a))
    {
      if (!dynCell)
        rate = 1 / dt * (goal[a] - stress[a]) * area[a] / (stiff[a] > 0 ? stiff[a] : 1.);
      else
      {
        if (!(mass > 0))
          throw std::runtime_error("PeriTriaxController: dynCell needs a positive cell mass, got " + std::to_string(mass));
        const double damp = 1 - growDamping * sign(rate * (goal[a] - stress[a]));
        rate += damp * dt * (goal[a] - stress[a]) / mass;
      }
    }
    else
      rate = (std::exp(goal[a] - strain[a]) - 1) / dt; // reach the goal strain in one step, within the cap
    if (!dynCell)
      rate = (1 - growDamping) * rate + .8 * prevGrow[a];
    if (std::abs(rate) > maxStrainRate[a])
      rate = sign(rate) * maxStrainRate[a];
    rate = std::max(rate, -(size[a] - 2.1 * maxBodySpan[a]) / dt);
    strain[a] += rate * dt; // predicted; recomputed exactly at the next update
    if (stressMask & (1 << a))
    {
      const double s = stress[a];
      if ((goal[a] != 0 && std::abs((s - goal[a]) / goal[a]) > relStressTol) || std::abs(s - goal[a]) > absStressTol)
        allOk = false;
    }
    else if ((goal[a] != 0 && std::abs((strain[a] - goal[a]) / goal[a]) > 1e-6) || std::abs(strain[a] - goal[a]) > 1e-6)
      allOk = false;
  }
  if (!dynCell)
    for (int a = 0; a < 3; ++a)
      if (stiff[a] > 0) // stress predicted from the stiffness between updates
        stress[a] += scene.cell.velGrad(a, a) * dt / size[a] * (stiff[a] / area[a]);
  strainRate = scene.cell.velGrad.diagonal();
  externalWork += (0.5 * (scene.cell.prevVelGrad + scene.cell.velGrad) * stressTensor).trace() * dt * scene.cell.volume();
  prevGrow = strainRate;
  if (allOk)
  {
    if (doUpdate || currUnbalanced < 0)
      currUnbalanced = unbalancedForce(scene, sceneGravity(scene));
    if (currUnbalanced < maxUnbalanced && doneHook)
      doneHook();
  }
}
} // namespace talus::dem
