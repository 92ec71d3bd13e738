#include "dem/engines/CallbackEngine.h"

#include "dem/core/Scene.h"

#include <stdexcept>

namespace talus::dem
{
void CallbackEngine::run(Scene& scene)
{
  if (iterPeriod < 0 || realPeriod < 0 || virtPeriod < 0 || (iterPeriod == 0 && realPeriod == 0 && virtPeriod == 0))
    throw std::invalid_argument("PyRunner '" + label + "': set iterPeriod >= 1, virtPeriod > 0 or realPeriod > 0");
  if (nDo >= 0 && nDone >= nDo)
    return;
  const auto now = std::chrono::steady_clock::now();
  const bool first = initRun && nDone == 0;
  const bool byIter = iterPeriod > 0 && scene.iter - iterLast >= iterPeriod;
  const bool byTime = realPeriod > 0 && std::chrono::duration<double>(now - realLast_).count() >= realPeriod;
  const bool byVirt = virtPeriod > 0 && scene.time - virtLast >= virtPeriod;
  if (!first && !byIter && !byTime && !byVirt)
    return;
  iterLast = scene.iter;
  virtLast = scene.time;
  realLast_ = now;
  ++nDone;
  if (callback)
    callback();
  // A script's command may have written into the bodies after this step's ghost update: on a
  // scene split over processes the other processes' copies take it before the next contacts.
  // Not after a call by wall time, which the processes make at different steps.
  if (resumable && realPeriod == 0 && scene.domain)
    scene.domain->afterIntegration(scene);
}
} // namespace talus::dem
