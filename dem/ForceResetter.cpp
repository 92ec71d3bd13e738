#include "dem/ForceResetter.h"
#include "dem/Scene.h"

#include "dem/Threads.h"

namespace talus::dem
{
void ForceResetter::run(Scene& scene)
{
  Bodies& b = scene.bodies;
  const auto n = static_cast<std::int64_t>(b.size());
  balancedFor(ranges_, n, [&](std::int64_t first, std::int64_t last) {
    for (auto i = static_cast<std::size_t>(first); i < static_cast<std::size_t>(last); ++i)
    {
      b.force[i] = b.extForce[i];
      b.torque[i] = b.extTorque[i];
    }
  });
}
} // namespace talus::dem
