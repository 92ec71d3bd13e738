#include "dem/CallbackEngine.h"

#include "dem/Scene.h"

#include <stdexcept>

namespace talus::dem
{
void CallbackEngine::run(Scene& scene)
{
  if (iterPeriod < 1)
    throw std::invalid_argument("PyRunner '" + label + "': iterPeriod must be at least 1");
  const bool first = initRun && nDone == 0;
  if (!first && scene.iter - iterLast < iterPeriod)
    return;
  iterLast = scene.iter;
  ++nDone;
  if (callback)
    callback();
}
} // namespace talus::dem
