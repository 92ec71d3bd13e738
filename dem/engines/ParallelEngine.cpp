#include "dem/engines/ParallelEngine.h"

namespace talus::dem
{
void ParallelEngine::run(Scene& scene)
{
  for (const auto& group : slaves)
    for (const auto& engine : group)
      if (!engine->dead)
        engine->run(scene);
}
} // namespace talus::dem
