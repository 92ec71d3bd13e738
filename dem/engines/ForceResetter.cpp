#include "dem/engines/ForceResetter.h"
#include "dem/core/Scene.h"

#include "dem/base/Threads.h"

namespace talus::dem
{
void ForceResetter::resetIn(Bodies& b, std::int64_t first, std::int64_t last)
{
  for (auto i = static_cast<std::size_t>(first); i < static_cast<std::size_t>(last); ++i)
  {
    b.force[i] = b.extForce[i];
    b.torque[i] = b.extTorque[i];
  }
}

void ForceResetter::run(Scene& scene)
{
  Bodies& b = scene.bodies;
  balancedFor(ranges_, static_cast<std::int64_t>(b.size()),
              [&](std::int64_t first, std::int64_t last) { resetIn(b, first, last); });
}
} // namespace talus::dem
