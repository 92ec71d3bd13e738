#pragma once

// The loops of ContactLawKernel, included by each law's .cpp (they need the Scene).
#include "dem/ContactLaw.h"
#include "dem/Scene.h"

namespace talus::dem
{
template <class Law>
void ContactLawKernel<Law>::computeForces(Scene& scene, std::uint8_t lawIndex)
{
  const Law& law = static_cast<const Law&>(*this);
  std::vector<Contact>& list = scene.contacts.list;
  const StepContext step{scene.bodies, scene.periodic ? &scene.cell : nullptr, scene.dt};
  const auto n = static_cast<std::int64_t>(list.size());
#pragma omp parallel for schedule(static) if (n >= parallelMinimum)
  for (std::int64_t k = 0; k < n; ++k)
  {
    Contact& c = list[static_cast<std::size_t>(k)];
    if (c.real && c.law == lawIndex)
      law.force(c, step);
  }
}

template <class Law>
std::int64_t ContactLawKernel<Law>::computeAll(Scene& scene)
{
  const Law& law = static_cast<const Law&>(*this);
  std::vector<Contact>& list = scene.contacts.list;
  const StepContext step{scene.bodies, scene.periodic ? &scene.cell : nullptr, scene.dt};
  const auto n = static_cast<std::int64_t>(list.size());
  const double ratio = scene.maxOverlapRatio;
  std::int64_t firstBad = n;
#pragma omp parallel for schedule(static) reduction(min : firstBad) if (n >= parallelMinimum)
  for (std::int64_t k = 0; k < n; ++k)
  {
    Contact& c = list[static_cast<std::size_t>(k)];
    if (!updateContactGeometry(c, step.bodies, step.cell, step.dt))
      continue;
    if (c.fresh)
    {
      c.law = 0;
      law.initialize(c, scene);
    }
    law.force(c, step);
    if (overlapsTooMuch(c, ratio))
      firstBad = std::min(firstBad, k);
  }
  return firstBad < n ? firstBad : -1;
}
} // namespace talus::dem
