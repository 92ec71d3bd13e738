#include "dem/FusedStep.h"

#include "dem/Collider.h"
#include "dem/ForceResetter.h"
#include "dem/InteractionLoop.h"
#include "dem/NewtonIntegrator.h"
#include "dem/Scene.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>

namespace talus::dem
{
namespace
{
/// The scene's live engines if they are exactly the usual four, else nulls.
struct UsualEngines
{
  Collider* collider = nullptr;
  InteractionLoop* loop = nullptr;
  NewtonIntegrator* newton = nullptr;
};

UsualEngines usualEngines(const Scene& scene)
{
  std::array<Engine*, 4> live{};
  std::size_t count = 0;
  for (const auto& engine : scene.engines)
  {
    if (engine->dead)
      continue;
    if (count == live.size())
      return {};
    live[count++] = engine.get();
  }
  if (count != live.size() || !dynamic_cast<ForceResetter*>(live[0]))
    return {};
  UsualEngines usual{dynamic_cast<Collider*>(live[1]), dynamic_cast<InteractionLoop*>(live[2]),
                     dynamic_cast<NewtonIntegrator*>(live[3])};
  if (!usual.collider || !usual.loop || usual.loop->laws.size() != 1 || !usual.newton)
    return {};
  return usual;
}

int threadNumber()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

int teamSize()
{
#ifdef _OPENMP
  return std::min(omp_get_num_threads(), BalancedRanges::maxThreads);
#else
  return 1;
#endif
}

double now()
{
#ifdef _OPENMP
  return omp_get_wtime();
#else
  return 0;
#endif
}
} // namespace

bool FusedStep::run(Scene& scene)
{
  if (scene.timingEnabled || scene.energy.enabled)
    return false;
  const auto bodies = static_cast<std::int64_t>(scene.bodies.size());
  if (bodies < parallelLoopMinimum)
    return false;
  const UsualEngines usual = usualEngines(scene);
  if (!usual.collider)
    return false;
  Collider& collider = *usual.collider;
  InteractionLoop& loop = *usual.loop;
  NewtonIntegrator& newton = *usual.newton;
  ContactLaw& law = *loop.laws[0];
  loop.prepare(scene);
  newton.prepare(scene);
  const Collider::SkinCheck skin = collider.skinCheck(scene);
  const bool clumps = newton.hasClumps();

  constexpr int most = BalancedRanges::maxThreads;
  std::array<bool, most> moved{};
  std::array<std::int64_t, most> badContact{}, badBody{};
  std::array<double, most> bodySeconds{}, contactSeconds{};
  badContact.fill(-1);
  badBody.fill(-1);
  int used = 1;
  bool redetect = skin.rebuild;

  // Contacts, a barrier, then this thread's bodies: gather and integrate. Called by every thread
  // of the team (it holds a barrier). A contact overlapping too much stops the step before any
  // body moves, as the engines do.
  auto contactsThenBodies = [&](int thread, int threads, bool working) {
    const auto contacts = static_cast<std::int64_t>(scene.contacts.list.size());
    if (working)
    {
      const auto [first, last] = contactRanges_.range(contacts, thread, threads);
      const double start = now();
      const std::int64_t bad = law.computeAllIn(scene, first, last);
      badContact[static_cast<std::size_t>(thread)] = bad < contacts ? bad : -1;
      contactSeconds[static_cast<std::size_t>(thread)] = now() - start;
    }
#pragma omp barrier
    for (int t = 0; t < threads; ++t)
      if (badContact[static_cast<std::size_t>(t)] >= 0)
        return;
    const auto [first, last] = working ? bodyRanges_.range(bodies, thread, threads) : std::pair<std::int64_t, std::int64_t>{0, 0};
    const double start = now();
    loop.gatherIn(scene, first, last);
    if (clumps)
    {
      // A clump reads its members' forces and moves them, whichever thread gathered them.
#pragma omp barrier
    }
    const std::int64_t bad = newton.integrateIn(scene, first, last);
    if (working)
    {
      badBody[static_cast<std::size_t>(thread)] = bad;
      bodySeconds[static_cast<std::size_t>(thread)] += now() - start;
    }
  };

  if (law.needsExtra())
    alignContactExtra(scene.contacts);
#pragma omp parallel
  {
    const int thread = threadNumber(), threads = teamSize();
    const bool working = thread < threads;
    if (working)
    {
      const auto [first, last] = bodyRanges_.range(bodies, thread, threads);
      const double start = now();
      ForceResetter::resetIn(scene.bodies, first, last);
      if (!skin.rebuild)
        moved[static_cast<std::size_t>(thread)] = collider.movedIn(scene, skin, first, last);
      bodySeconds[static_cast<std::size_t>(thread)] = now() - start;
    }
#pragma omp barrier
    bool anyMoved = skin.rebuild;
    for (int t = 0; t < threads; ++t)
      anyMoved = anyMoved || moved[static_cast<std::size_t>(t)];
    if (!anyMoved)
      contactsThenBodies(thread, threads, working);
    if (thread == 0)
    {
      used = threads;
      redetect = anyMoved;
    }
  }
  if (redetect)
  {
    collider.rebuild(scene);
    if (law.needsExtra())
      alignContactExtra(scene.contacts);
#pragma omp parallel
    {
      const int thread = threadNumber(), threads = teamSize();
      contactsThenBodies(thread, threads, thread < threads);
    }
  }
  law.stepDone();
  for (int t = 0; t < used; ++t)
  {
    bodyRanges_.record(t, bodySeconds[static_cast<std::size_t>(t)]);
    contactRanges_.record(t, contactSeconds[static_cast<std::size_t>(t)]);
  }
  bodyRanges_.rebalance(used);
  contactRanges_.rebalance(used);
  ++steps;

  std::int64_t badContactIndex = -1, badBodyIndex = -1;
  for (int t = 0; t < used; ++t)
  {
    const std::int64_t c = badContact[static_cast<std::size_t>(t)], b = badBody[static_cast<std::size_t>(t)];
    if (c >= 0 && (badContactIndex < 0 || c < badContactIndex))
      badContactIndex = c;
    if (b >= 0 && (badBodyIndex < 0 || b < badBodyIndex))
      badBodyIndex = b;
  }
  if (badContactIndex >= 0)
    throw std::runtime_error(InteractionLoop::overlapReport(scene, scene.contacts.list[static_cast<std::size_t>(badContactIndex)]));
  newton.finish(scene, badBodyIndex);
  return true;
}
} // namespace talus::dem
