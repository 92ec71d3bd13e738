#include "dem/Energy.h"
#include "dem/InteractionLoop.h"
#include "dem/Scene.h"
#include "dem/Threads.h"


namespace talus::dem
{
double kineticEnergy(const Scene& scene)
{
  const Bodies& b = scene.bodies;
  const bool homogeneous = scene.periodic && scene.cell.homoDeform;
  const auto n = static_cast<std::int64_t>(b.size());
  const std::int64_t blocks = (n + energyBlock - 1) / energyBlock;
  std::vector<double> sums(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (n >= parallelLoopMinimum)
  for (std::int64_t blk = 0; blk < blocks; ++blk)
  {
    double sum = 0;
    for (std::int64_t k = blk * energyBlock, end = std::min(n, k + energyBlock); k < end; ++k)
    {
      const auto i = static_cast<std::size_t>(k);
      if (!b.alive[i] || !b.dynamic[i])
        continue;
      const Vec3 v = homogeneous ? Vec3(b.vel[i] - scene.cell.velGrad * b.pos[i]) : b.vel[i];
      sum += 0.5 * b.mass[i] * v.squaredNorm() + 0.5 * b.angVel[i].dot(b.inertia[i].cwiseProduct(b.angVel[i]));
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
} // namespace talus::dem
