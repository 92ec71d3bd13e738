#include "dem/ForceResetter.h"

#include "dem/Scene.h"

namespace talus::dem
{
void ForceResetter::run(Scene& scene)
{
  Bodies& b = scene.bodies;
  const auto n = static_cast<std::int64_t>(b.size());
#pragma omp parallel for schedule(static) if (n >= parallelMinimum)
  for (std::int64_t k = 0; k < n; ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    b.force[i] = b.extForce[i];
    b.torque[i] = b.extTorque[i];
  }
}
} // namespace talus::dem
