#include "dem/measure/Energy.h"
#include "dem/core/Clump.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/core/Scene.h"
#include "dem/core/StepLoop.h"
#include "dem/base/Threads.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>


namespace talus::dem
{
namespace
{
/// {1/2 m v^2, 1/2 w.I w} of body i; zero for a body whose energy is not counted.
std::pair<double, double> bodyKinetic(const Scene& scene, std::size_t i)
{
  const Bodies& b = scene.bodies;
  // clump members move with their clump, whose energy is the rigid body's
  if (!b.alive[i] || !b.dynamic[i] || b.clumpId[i] >= 0 || !countsBody(scene.domain.get(), i))
    return {0.0, 0.0};
  // With homoDeform the velocities carry the field of the step just made (prevVelGrad once the
  // cell has moved) at the positions it was applied to, x - v dt: the fluctuation is what is
  // left, exactly as the integrator recovers it.
  const bool homogeneous = scene.periodic && scene.cell.homoDeform;
  const Mat3& L = scene.cell.prevVelGrad;
  const Vec3 v = homogeneous ? Vec3(b.vel[i] - L * (b.pos[i] - scene.dt * b.vel[i])) : b.vel[i];
  const Vec3 omega = homogeneous ? Vec3(b.angVel[i] - spin(L)) : b.angVel[i];
  // principal moments: the angular velocity in the principal (body) frame
  const Vec3 bodyOmega = b.aspherical(i) ? Vec3(b.ori[i].conjugate() * omega) : omega;
  return {0.5 * b.mass[i] * v.squaredNorm(), 0.5 * bodyOmega.dot(b.inertia[i].cwiseProduct(bodyOmega))};
}
} // namespace

std::pair<double, double> kineticEnergyParts(const Scene& scene)
{
  std::pair<double, double> total{0.0, 0.0};
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
  {
    const auto [translational, rotational] = bodyKinetic(scene, i);
    total.first += translational;
    total.second += rotational;
  }
  return total;
}

std::vector<double> bodyKineticEnergies(const Scene& scene)
{
  std::vector<double> energies(scene.bodies.size());
  for (std::size_t i = 0; i < energies.size(); ++i)
  {
    const auto [translational, rotational] = bodyKinetic(scene, i);
    energies[i] = translational + rotational;
  }
  return energies;
}

double kineticEnergy(const Scene& scene)
{
  const auto n = static_cast<std::int64_t>(scene.bodies.size());
  const std::int64_t blocks = (n + energyBlock - 1) / energyBlock;
  std::vector<double> sums(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (n >= parallelLoopMinimum)
  for (std::int64_t blk = 0; blk < blocks; ++blk)
  {
    double sum = 0;
    for (std::int64_t k = blk * energyBlock, end = std::min(n, k + energyBlock); k < end; ++k)
    {
      const auto [translational, rotational] = bodyKinetic(scene, static_cast<std::size_t>(k));
      sum += translational + rotational;
    }
    sums[static_cast<std::size_t>(blk)] = sum;
  }
  double total = 0;
  for (double s : sums)
    total += s;
  return total;
}

double elasticPotential(const Scene& scene)
{
  double total = 0;
  for (const auto& engine : scene.engines)
    if (const auto* loop = dynamic_cast<const InteractionLoop*>(engine.get()); loop && !loop->dead)
      for (std::size_t k = 0; k < loop->laws.size(); ++k)
        total += loop->laws[k]->elasticEnergy(scene, static_cast<std::uint8_t>(k));
  return total;
}

namespace
{
/// The terms of EnergyValues: the balance's, in its order, then the kinetic parts.
constexpr std::array<double EnergyValues::*, 11> energyTerms{
    &EnergyValues::kinetic,     &EnergyValues::elastPotential, &EnergyValues::gravWork,    &EnergyValues::nonviscDamp,
    &EnergyValues::plastDissip, &EnergyValues::viscDamp,       &EnergyValues::velGradWork, &EnergyValues::kinematicWork,
    &EnergyValues::growthWork,  &EnergyValues::kinTrans,       &EnergyValues::kinRot};
constexpr std::size_t balanceTerms = 9;
} // namespace

double EnergyValues::total() const
{
  double sum = 0;
  for (std::size_t k = 0; k < balanceTerms; ++k)
    sum += this->*energyTerms[k];
  return sum;
}

double EnergyValues::flowed() const
{
  double sum = 0;
  for (std::size_t k = 0; k < balanceTerms; ++k)
    sum += std::abs(this->*energyTerms[k]);
  return sum;
}

EnergyValues energyValues(const Scene& scene)
{
  const EnergyTracker& e = scene.energy;
  const auto [translational, rotational] = kineticEnergyParts(scene);
  EnergyValues v{kineticEnergy(scene), translational, rotational, elasticPotential(scene), e.gravWork,
                 e.nonviscDamp, e.plastDissip, e.viscDamp, e.velGradWork, e.kinematicWork, e.growthWork};
  if (scene.domain) // one sum over processes of every term
  {
    std::array<double, energyTerms.size()> all{};
    for (std::size_t k = 0; k < all.size(); ++k)
      all[k] = v.*energyTerms[k];
    scene.domain->sum(all);
    for (std::size_t k = 0; k < all.size(); ++k)
      v.*energyTerms[k] = all[k];
  }
  return v;
}

namespace
{
/// The energy-growth check at the end of the steps it is due at (see Scene::maxEnergyGrowth).
void checkEnergyGrowthWhenDue(Scene& scene)
{
  if (scene.energy.enabled && scene.maxEnergyGrowth > 0 && scene.iter % energyGrowthCheckPeriod == 0)
    checkEnergyGrowth(scene);
}
[[maybe_unused]] const bool energyGrowthChecked = addStepCheck(&checkEnergyGrowthWhenDue);
} // namespace

void checkEnergyGrowth(Scene& scene)
{
  EnergyTracker& e = scene.energy;
  const EnergyValues values = energyValues(scene);
  const double total = values.total(), flowed = values.flowed();
  if (std::isnan(e.growthReference))
  {
    e.growthReference = total;
    return;
  }
  const double growth = total - e.growthReference;
  if (!(growth > scene.maxEnergyGrowth * flowed))
    return;
  // the body that gained the most: the largest kinetic energy
  const Bodies& b = scene.bodies;
  std::size_t fastest = 0;
  double most = -1;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.alive[i] && b.dynamic[i])
      if (const double k = b.mass[i] * b.vel[i].squaredNorm(); k > most)
      {
        most = k;
        fastest = i;
      }
  char message[512];
  std::snprintf(message, sizeof message,
                "step %lld: the total energy grew by %.3g (%.1f%% of the %.3g that flowed, limit %.0f%%, "
                "O.maxEnergyGrowth): the run is unstable; body %zu moves fastest (%.3g m/s). The time step %.3g "
                "is too large: P-wave estimate %.3g",
                static_cast<long long>(scene.iter), growth, 100 * growth / flowed, flowed, 100 * scene.maxEnergyGrowth,
                fastest, b.vel[fastest].norm(), scene.dt, scene.pWaveTimeStep());
  std::string text = message;
  if (const double contact = scene.contactTimeStep(); std::isfinite(contact))
    text += ", stiffest contact's critical step about " + std::to_string(contact);
  throw std::runtime_error(text);
}
} // namespace talus::dem
