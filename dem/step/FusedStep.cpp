#include "dem/step/FusedStep.h"

#include "dem/contact/Collider.h"
#include "dem/laws/ContactLawKernel.h"
#include "dem/core/EnergyTracker.h"
#include "dem/step/ForceResetter.h"
#include "dem/step/InteractionLoop.h"
#include "dem/step/NewtonIntegrator.h"
#include "dem/core/Scene.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <utility>

namespace talus::dem
{
namespace
{
/// Where the usual engines sit among the scene's live engines: ForceResetter, a collider and an
/// InteractionLoop with one law and no callbacks, one after the other, then NewtonIntegrator;
/// any other engines before them (prefix), between the loop and the integrator (middle) or
/// after it (suffix), each kind once.
struct UsualEngines
{
  std::size_t resetterIndex = 0, loopIndex = 0, newtonIndex = 0; ///< in scene.engines
  Collider* collider = nullptr;
  InteractionLoop* loop = nullptr;
  NewtonIntegrator* newton = nullptr;
  int prefix = 0, middle = 0, suffix = 0; ///< live engines of each group
};

std::optional<UsualEngines> usualEngines(const Scene& scene)
{
  enum class Next { Resetter, Collider, Loop, Newton, Done } next = Next::Resetter;
  UsualEngines usual;
  for (std::size_t k = 0; k < scene.engines.size(); ++k)
  {
    Engine* engine = scene.engines[k].get();
    if (engine->dead)
      continue;
    if (dynamic_cast<ForceResetter*>(engine))
    {
      if (next != Next::Resetter)
        return std::nullopt;
      usual.resetterIndex = k;
      next = Next::Collider;
    }
    else if (next == Next::Collider)
    {
      if (!(usual.collider = dynamic_cast<Collider*>(engine)))
        return std::nullopt;
      next = Next::Loop;
    }
    else if (next == Next::Loop)
    {
      usual.loop = dynamic_cast<InteractionLoop*>(engine);
      if (!usual.loop || usual.loop->laws.size() != 1 || !usual.loop->callbacks.empty())
        return std::nullopt;
      usual.loopIndex = k;
      next = Next::Newton;
    }
    else if (dynamic_cast<Collider*>(engine) || dynamic_cast<InteractionLoop*>(engine))
      return std::nullopt;
    else if (auto* newton = dynamic_cast<NewtonIntegrator*>(engine))
    {
      if (next != Next::Newton)
        return std::nullopt;
      usual.newton = newton;
      usual.newtonIndex = k;
      next = Next::Done;
    }
    else
      ++(next == Next::Resetter ? usual.prefix : next == Next::Newton ? usual.middle : usual.suffix);
  }
  if (next != Next::Done)
    return std::nullopt;
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

/// A thread's share [first, last) of n items with its ends moved to multiples of energyBlock
/// (n stays n): the shares of the threads still tile the items, and each block of energy sums
/// lies in one of them.
std::pair<std::int64_t, std::int64_t> blockAligned(std::pair<std::int64_t, std::int64_t> share, std::int64_t n)
{
  auto align = [n](std::int64_t x) { return x >= n ? n : std::min(n, (x + energyBlock / 2) / energyBlock * energyBlock); };
  return {align(share.first), align(share.second)};
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
  ContactEnergy* energy = scene.energy.enabled ? contactEnergy_.data() : nullptr;
  auto compute = [&](std::int64_t first, std::int64_t last) {
    if (first < last)
      bad = std::min(bad, law.computeAllIn(scene, first, last, energy));
  };
  if (energy)
  {
    const auto [first, last] = blockAligned(contactRanges_.range(contacts, thread, threads), contacts);
    compute(first, last);
    return bad;
  }
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

/// Each thread's flags and times of one step, a cache line apiece (they are written during it).
struct FusedStep::Team
{
  struct alignas(64) Member
  {
    Collider::Displacements moved, movedAhead;
    std::int64_t badContact = -1, badBody = -1;
    double bodySeconds = 0, contactSeconds = 0;
  };
  std::array<Member, BalancedRanges::maxThreads> members{};
  int used = 1; ///< threads that worked

  /// The smallest index the threads report through `field`, -1 if none.
  [[nodiscard]] std::int64_t first(std::int64_t Member::*field) const
  {
    std::int64_t found = -1;
    for (int t = 0; t < used; ++t)
    {
      const std::int64_t theirs = members[static_cast<std::size_t>(t)].*field;
      if (theirs >= 0 && (found < 0 || theirs < found))
        found = theirs;
    }
    return found;
  }
};

bool FusedStep::run(Scene& scene, const EngineRunner& runEngineUntimed)
{
  auto runEngine = [&](std::size_t k) {
    const auto start = std::chrono::steady_clock::now();
    runEngineUntimed(k);
    otherEnginesSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // Split over processes: the engines' path, which calls the domain (Collider, NewtonIntegrator).
  if (scene.domain || scene.timingEnabled || static_cast<std::int64_t>(scene.bodies.size()) < parallelLoopMinimum)
    return false;
  std::optional<UsualEngines> usual = usualEngines(scene);
  if (!usual)
    return false;
  if (usual->prefix > 0)
  {
    const std::size_t resetter = usual->resetterIndex;
    for (std::size_t k = 0; k < resetter; ++k)
      runEngine(k);
    // They may have changed what the rest of the step can be (engines, bodies, timing).
    usual = usualEngines(scene);
    if (!usual || scene.timingEnabled || static_cast<std::int64_t>(scene.bodies.size()) < parallelLoopMinimum)
    {
      for (std::size_t k = resetter; k < scene.engines.size(); ++k)
        runEngine(k);
      return true;
    }
  }
  Team team;
  if (usual->middle == 0 && !scene.energy.enabled)
    forces(scene, *usual->collider, *usual->loop, usual->newton, team,
           usual->prefix == 0 && usual->suffix == 0);
  else
  {
    // The engines between the loop and the integrator (force engines, couplings) see every
    // contact's force gathered, as in the engines' order: the integration waits for them, and
    // with energy tracked for the work of the imposed motions, which needs the forces too.
    forces(scene, *usual->collider, *usual->loop, nullptr, team, false);
    for (std::size_t k = usual->loopIndex + 1; k < usual->newtonIndex; ++k)
      runEngine(k);
    integrate(scene, *usual->newton, team);
  }
  for (int t = 0; t < team.used; ++t)
  {
    bodyRanges_.record(t, team.members[static_cast<std::size_t>(t)].bodySeconds);
    contactRanges_.record(t, team.members[static_cast<std::size_t>(t)].contactSeconds);
  }
  bodyRanges_.rebalance(team.used);
  contactRanges_.rebalance(team.used);
  ++steps;
  for (std::size_t k = usual->newtonIndex + 1; k < scene.engines.size(); ++k)
    runEngine(k);
  return true;
}

void FusedStep::forces(Scene& scene, Collider& collider, InteractionLoop& loop, NewtonIntegrator* newton, Team& team,
                       bool alone)
{
  ContactLaw& law = *loop.laws[0];
  const auto bodies = static_cast<std::int64_t>(scene.bodies.size());
  loop.prepare(scene);
  if (newton)
    newton->prepare(scene);
  Collider::SkinCheck skin = collider.skinCheck(scene);
  const bool clumps = newton && newton->hasClumps();
  // In an open scene the skin check depends on the positions only, so each thread checks its
  // bodies right after moving them, for the next step: the step then needs no barrier between
  // the check and the contacts, and re-detects, when it must, before its one parallel region.
  // (Not with clumps: a clump moves its members, which may be another thread's bodies; not
  // with other engines, which may move bodies between this check and the next step.)
  const bool checkAhead = newton && alone && !scene.periodic && !clumps;
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
    if (scene.energy.enabled)
      contactEnergy_.assign(static_cast<std::size_t>((scene.contacts.list.size() + energyBlock - 1) / energyBlock),
                            ContactEnergy{});
  };
  const bool redetectFirst = skin.rebuild || (knownAhead && movedAhead_);
  if (redetectFirst)
    redetectNow();
  const bool checkNow = !redetectFirst && !knownAhead;
  bool redetect = false;
  Collider::Displacements measured; // this step's check (checkNow), all threads together

  // Contacts, a barrier, then this thread's bodies: gather, and with an integrator integrate
  // and check ahead (with `ahead`, the next step's check). Called by every thread of the team (it
  // holds a barrier). A contact overlapping too much stops the step before any body moves, as
  // the engines do, unless the scene only counts such overlaps.
  auto contactsThenBodies = [&](int thread, int threads, bool working, const Collider::SkinCheck& ahead) {
    Team::Member& my = team.members[static_cast<std::size_t>(working ? thread : 0)];
    const auto contacts = static_cast<std::int64_t>(scene.contacts.list.size());
    if (working)
    {
      const double start = now();
      const std::int64_t bad = computeContacts(scene, law, thread, threads);
      my.badContact = bad < contacts ? bad : -1;
      my.contactSeconds = now() - start;
    }
#pragma omp barrier
    if (scene.overlapStops)
      for (int t = 0; t < threads; ++t)
        if (team.members[static_cast<std::size_t>(t)].badContact >= 0)
          return;
    const auto [first, last] = working ? bodyRanges_.range(bodies, thread, threads) : std::pair<std::int64_t, std::int64_t>{0, 0};
    const double start = now();
    loop.gatherIn(scene, first, last);
    if (newton)
    {
      if (clumps)
      {
        // A clump reads its members' forces and moves them, whichever thread gathered them.
#pragma omp barrier
      }
      const std::int64_t bad = newton->integrateIn(scene, first, last, nullptr);
      if (working)
      {
        my.badBody = bad;
        if (checkAhead)
          my.movedAhead = collider.displacementsIn(scene, ahead, first, last);
      }
    }
    if (working)
      my.bodySeconds += now() - start;
  };

  listChanged();
#pragma omp parallel
  {
    const int thread = threadNumber(), threads = teamSize();
    const bool working = thread < threads;
    if (working)
    {
      Team::Member& my = team.members[static_cast<std::size_t>(thread)];
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
        all.add(team.members[static_cast<std::size_t>(t)].moved);
      anyMoved = Collider::mustRebuild(skin, all);
      ahead.common = Collider::commonOf(all); // what the collider keeps after this check
    }
    if (!anyMoved)
      contactsThenBodies(thread, threads, working, ahead);
    if (thread == 0)
    {
      team.used = threads;
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
  if (scene.energy.enabled)
  {
    detail::addContactEnergy(scene, contactEnergy_);
    if (!scene.energy.grownBy.empty())
      addGrownContactsEnergy(scene, loop);
  }
  if (const std::int64_t bad = team.first(&Team::Member::badContact); bad >= 0)
    InteractionLoop::overlapFound(scene, scene.contacts.list[static_cast<std::size_t>(bad)]);
  if (!newton)
    return;
  newton->finish(scene, team.first(&Team::Member::badBody));
  if (checkAhead)
  {
    Collider::Displacements movedAhead;
    for (int t = 0; t < team.used; ++t)
      movedAhead.add(team.members[static_cast<std::size_t>(t)].movedAhead);
    movedAhead_ = Collider::mustRebuild(skin, movedAhead);
    collider.noteDisplacements(movedAhead);
    aheadFor_ = scene.iter + 1;
  }
}

void FusedStep::integrate(Scene& scene, NewtonIntegrator& newton, Team& team)
{
  newton.prepare(scene);
  const auto bodies = static_cast<std::int64_t>(scene.bodies.size());
  const bool tracking = scene.energy.enabled;
  if (tracking)
  {
    addImposedMotionWork(scene);
    bodyEnergy_.assign(static_cast<std::size_t>((bodies + energyBlock - 1) / energyBlock), {});
  }
#pragma omp parallel
  {
    const int thread = threadNumber(), threads = teamSize();
    std::pair<std::int64_t, std::int64_t> share{0, 0};
    if (thread < threads)
      share = tracking ? blockAligned(bodyRanges_.range(bodies, thread, threads), bodies)
                       : bodyRanges_.range(bodies, thread, threads);
    const auto [first, last] = share;
    const double start = now();
    const std::int64_t bad = newton.integrateIn(scene, first, last, tracking ? bodyEnergy_.data() : nullptr);
    if (thread < threads)
    {
      Team::Member& my = team.members[static_cast<std::size_t>(thread)];
      my.badBody = bad;
      my.bodySeconds += now() - start;
    }
  }
  if (tracking)
    NewtonIntegrator::addEnergy(scene, bodyEnergy_);
  newton.finish(scene, team.first(&Team::Member::badBody));
}
} // namespace talus::dem
