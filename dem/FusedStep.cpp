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
  if (!usual.collider || !usual.loop || usual.loop->laws.size() != 1 || !usual.loop->callbacks.empty() || !usual.newton)
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

void FusedStep::findBoundaryRuns(const Contacts& contacts)
{
  if (runsVersion_ == contacts.version)
    return;
  runsVersion_ = contacts.version;
  const ContactList& list = contacts.list;
  boundaryRuns_.clear();
  boundaryContacts_ = 0;
  for (std::size_t k = 0; k < list.size();)
  {
    const ContactGeometryKind kind = list[k].kind;
    const bool boundary = kind == ContactGeometryKind::WallSphere || kind == ContactGeometryKind::FacetSphere
                          || kind == ContactGeometryKind::BoxSphere;
    std::size_t end = k + 1;
    while (end < list.size() && list[end].id1 == list[k].id1)
      ++end;
    if (boundary)
    {
      if (boundaryRuns_.size() == maxBoundaryRuns)
      {
        boundaryRuns_.clear(); // too many to split each one: contiguous ranges for all
        boundaryContacts_ = 0;
        break;
      }
      boundaryRuns_.emplace_back(static_cast<std::int64_t>(k), static_cast<std::int64_t>(end));
      boundaryContacts_ += static_cast<std::int64_t>(end - k);
    }
    k = end;
  }
}

std::int64_t FusedStep::computeContacts(Scene& scene, ContactLaw& law, int thread, int threads)
{
  const auto contacts = static_cast<std::int64_t>(scene.contacts.list.size());
  std::int64_t bad = contacts;
  auto compute = [&](std::int64_t first, std::int64_t last) {
    if (first < last)
      bad = std::min(bad, law.computeAllIn(scene, first, last));
  };
  if (boundaryRuns_.empty())
  {
    const auto [first, last] = contactRanges_.range(contacts, thread, threads);
    compute(first, last);
    return bad;
  }
  // This thread's share of the other contacts, counted over the gaps between the runs.
  const auto [from, to] = contactRanges_.range(contacts - boundaryContacts_, thread, threads);
  std::int64_t gapStart = 0, counted = 0;
  auto gap = [&](std::int64_t gapEnd) {
    const std::int64_t length = gapEnd - gapStart;
    compute(gapStart + std::clamp(from - counted, std::int64_t{0}, length),
            gapStart + std::clamp(to - counted, std::int64_t{0}, length));
    counted += length;
  };
  for (const auto& [begin, end] : boundaryRuns_)
  {
    gap(begin);
    gapStart = end;
  }
  gap(contacts);
  // Its share of each wall's, facet's or box's contacts: those of the spheres it integrates (a
  // run is sorted by the sphere's id).
  const auto bodies = static_cast<std::int64_t>(scene.bodies.size());
  const auto [firstBody, lastBody] = bodyRanges_.range(bodies, thread, threads);
  const ContactList& list = scene.contacts.list;
  auto firstOf = [&](std::int64_t begin, std::int64_t end, std::int64_t body) {
    return static_cast<std::int64_t>(
        std::lower_bound(list.begin() + begin, list.begin() + end, body,
                         [](const Contact& c, std::int64_t id) { return c.id2 < id; })
        - list.begin());
  };
  for (const auto& [begin, end] : boundaryRuns_)
    compute(thread == 0 ? begin : firstOf(begin, end, firstBody), thread + 1 == threads ? end : firstOf(begin, end, lastBody));
  return bad;
}

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
  Collider::SkinCheck skin = collider.skinCheck(scene);
  const bool clumps = newton.hasClumps();
  // In an open scene the skin check depends on the positions only, so each thread checks its
  // bodies right after moving them, for the next step: the step then needs no barrier between
  // the check and the contacts, and re-detects, when it must, before its one parallel region.
  // (Not with clumps: a clump moves its members, which may be another thread's bodies.)
  const bool checkAhead = !scene.periodic && !clumps;
  const bool knownAhead = checkAhead && aheadFor_ == scene.iter;
  aheadFor_ = -1;
  // A new contact list: the check's references are new, the richer state and the boundary runs
  // follow the list.
  auto redetectNow = [&] {
    collider.rebuild(scene);
    skin = collider.skinCheck(scene); // the next step's, around the new references
  };
  auto listChanged = [&] {
    if (law.needsExtra())
      alignContactExtra(scene.contacts);
    findBoundaryRuns(scene.contacts);
  };
  const bool redetectFirst = skin.rebuild || (knownAhead && movedAhead_);
  if (redetectFirst)
    redetectNow();
  const bool checkNow = !redetectFirst && !knownAhead;

  // Each thread's flags and times, a cache line apiece (they are written during the step).
  struct alignas(64) PerThread
  {
    Collider::Displacements moved, movedAhead;
    std::int64_t badContact = -1, badBody = -1;
    double bodySeconds = 0, contactSeconds = 0;
  };
  std::array<PerThread, BalancedRanges::maxThreads> mine{};
  int used = 1;
  bool redetect = false;
  Collider::Displacements measured; // this step's check (checkNow), all threads together

  // Contacts, a barrier, then this thread's bodies: gather, integrate, and check ahead (with
  // `ahead`, the next step's check). Called by every thread of the team (it holds a barrier). A
  // contact overlapping too much stops the step before any body moves, as the engines do.
  auto contactsThenBodies = [&](int thread, int threads, bool working, const Collider::SkinCheck& ahead) {
    PerThread& my = mine[static_cast<std::size_t>(working ? thread : 0)];
    const auto contacts = static_cast<std::int64_t>(scene.contacts.list.size());
    if (working)
    {
      const double start = now();
      const std::int64_t bad = computeContacts(scene, law, thread, threads);
      my.badContact = bad < contacts ? bad : -1;
      my.contactSeconds = now() - start;
    }
#pragma omp barrier
    for (int t = 0; t < threads; ++t)
      if (mine[static_cast<std::size_t>(t)].badContact >= 0)
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
      my.badBody = bad;
      if (checkAhead)
        my.movedAhead = collider.displacementsIn(scene, ahead, first, last);
      my.bodySeconds += now() - start;
    }
  };

  listChanged();
#pragma omp parallel
  {
    const int thread = threadNumber(), threads = teamSize();
    const bool working = thread < threads;
    if (working)
    {
      PerThread& my = mine[static_cast<std::size_t>(thread)];
      const auto [first, last] = bodyRanges_.range(bodies, thread, threads);
      const double start = now();
      ForceResetter::resetIn(scene.bodies, first, last);
      if (checkNow)
        my.moved = collider.displacementsIn(scene, skin, first, last);
      my.bodySeconds = now() - start;
    }
    bool anyMoved = false;
    Collider::SkinCheck ahead = skin;
    Collider::Displacements all;
    if (checkNow)
    {
#pragma omp barrier
      for (int t = 0; t < threads; ++t)
        all.add(mine[static_cast<std::size_t>(t)].moved);
      anyMoved = Collider::mustRebuild(skin, all);
      ahead.common = Collider::commonOf(all); // what the collider keeps after this check
    }
    if (!anyMoved)
      contactsThenBodies(thread, threads, working, ahead);
    if (thread == 0)
    {
      used = threads;
      redetect = anyMoved;
      measured = all;
    }
  }
  if (checkNow && !redetect)
    collider.noteDisplacements(measured);
  if (redetect)
  {
    redetectNow();
    listChanged();
#pragma omp parallel
    {
      const int thread = threadNumber(), threads = teamSize();
      contactsThenBodies(thread, threads, thread < threads, skin);
    }
  }
  law.stepDone();
  for (int t = 0; t < used; ++t)
  {
    bodyRanges_.record(t, mine[static_cast<std::size_t>(t)].bodySeconds);
    contactRanges_.record(t, mine[static_cast<std::size_t>(t)].contactSeconds);
  }
  bodyRanges_.rebalance(used);
  contactRanges_.rebalance(used);
  ++steps;

  std::int64_t badContactIndex = -1, badBodyIndex = -1;
  Collider::Displacements movedAhead;
  for (int t = 0; t < used; ++t)
  {
    const PerThread& their = mine[static_cast<std::size_t>(t)];
    if (their.badContact >= 0 && (badContactIndex < 0 || their.badContact < badContactIndex))
      badContactIndex = their.badContact;
    if (their.badBody >= 0 && (badBodyIndex < 0 || their.badBody < badBodyIndex))
      badBodyIndex = their.badBody;
    movedAhead.add(their.movedAhead);
  }
  if (badContactIndex >= 0)
    InteractionLoop::overlapFound(scene, scene.contacts.list[static_cast<std::size_t>(badContactIndex)]);
  newton.finish(scene, badBodyIndex);
  if (checkAhead)
  {
    movedAhead_ = Collider::mustRebuild(skin, movedAhead);
    collider.noteDisplacements(movedAhead);
    aheadFor_ = scene.iter + 1;
  }
  return true;
}
} // namespace talus::dem
