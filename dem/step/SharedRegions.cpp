#include "dem/step/SharedRegions.h"

#include "dem/core/Scene.h"
#include "dem/laws/ContactLawKernel.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"

#include <algorithm>
#include <optional>

namespace talus::dem
{
namespace
{
#ifdef _OPENMP
int threadNumber() { return omp_get_thread_num(); }
/// Threads of the running region, no more than the team's slots.
int teamSize() { return std::min(omp_get_num_threads(), BalancedRanges::maxThreads); }
/// Threads a region asks for: no more than the team's slots.
int teamLimit() { return std::min(omp_get_max_threads(), BalancedRanges::maxThreads); }
double now() { return omp_get_wtime(); }
#else
int threadNumber() { return 0; }
int teamSize() { return 1; }
int teamLimit() { return 1; }
double now() { return 0; }
#endif

/// The team's barrier; none for a thread alone, which runs outside any parallel region
/// (SharedRegions::region) or inside another's (a Gauss point's RVE), whose team it must not
/// wait for.
void teamBarrier(int threads)
{
  if (threads > 1)
  {
#pragma omp barrier
  }
}

std::size_t at(StagePoint point) { return static_cast<std::size_t>(point); }
/// How many blocks of energyBlock hold `items` contacts or bodies.
std::size_t energyBlocks(std::int64_t items) { return static_cast<std::size_t>((items + energyBlock - 1) / energyBlock); }
} // namespace

std::int64_t SharedRegions::Team::first(std::int64_t Member::*field) const
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

void SharedRegions::Team::lap(Member& m, StagePoint point) const
{
  if (!timing)
    return;
  const double t = now();
  m.stage[at(point)] += t - m.mark;
  m.mark = t;
}

void SharedRegions::serialLap(StagePoint point, double start)
{
  if (team_.timing)
    stageSeconds[at(point)] += now() - start;
}

template <class Body>
void SharedRegions::region(Scene& scene, const Body& body)
{
  // As the engines' own loops: threads when the bodies or the contacts are many enough.
  const bool parallel = static_cast<std::int64_t>(scene.ownedBodies()) >= parallelLoopMinimum
                        || static_cast<std::int64_t>(scene.contacts.list.size()) >= parallelLoopMinimum;
  ++regions;
  if (!parallel || teamLimit() == 1)
  {
    // One thread runs the body outside any parallel region, without its barriers (teamBarrier):
    // libgomp makes a futex system call at every barrier and at a region's end even for a team
    // of one, three a step of a 400-sphere RVE (docs/dem.md, Speed).
    if (team_.timing)
      team_.members[0].mark = now();
    body(0, 1);
    team_.used = 1;
    return;
  }
#pragma omp parallel num_threads(teamLimit())
  {
    const int thread = threadNumber(), threads = teamSize();
    if (team_.timing)
      team_.members[static_cast<std::size_t>(thread)].mark = now();
    body(thread, threads);
    if (thread == 0)
      team_.used = threads;
  }
}

void SharedRegions::begin(const Scene& scene)
{
  // Only the members this step's regions may use: clearing all the slots (16 KiB) was a
  // per-step cost of its own in a scene of a few hundred spheres.
  for (int t = 0; t < teamLimit(); ++t)
    team_.members[static_cast<std::size_t>(t)] = Team::Member{};
  team_.used = 1;
  team_.timing = scene.timingEnabled;
  stageSeconds.fill(0);
  regions = barriers = 0;
}

void SharedRegions::reset(Scene& scene)
{
  const auto owned = static_cast<std::int64_t>(scene.ownedBodies());
  region(scene, [&](int thread, int threads) {
    Team::Member& my = team_.members[static_cast<std::size_t>(thread)];
    const auto [first, last] = bodyRanges_.range(owned, thread, threads);
    const double start = now();
    ForceResetter::resetIn(scene.bodies, first, last);
    my.bodySeconds += now() - start;
    team_.lap(my, StagePoint::Reset);
  });
}

void SharedRegions::forces(Scene& scene, const Engines& engines, Flow flow)
{
  const bool integrate = flow.integrate;
  const double start = now();
  engines.loop.prepare(scene);
  if (integrate)
    prepareIntegration(scene, engines.newton);
  ContactLaw* law = flow.contactsInRegion ? engines.loop.laws[0].get() : nullptr;
  // Contacts in the region and no reduction over processes: the skin check's verdict is known
  // inside the region, which goes on to the contacts unless it calls for a re-detection.
  const bool oneRegion = law && !scene.domain;
  Skin skin;
  skin.check = engines.collider.skinCheck(scene);
  // In an open scene the skin check depends on the positions only, so each thread may check
  // its bodies right after moving them, for the next step. Not with clumps (a clump moves its
  // members, which may be another thread's bodies), nor with other engines (they may move
  // bodies between this check and the next step).
  skin.checkAhead = integrate && flow.alone && oneRegion && !scene.periodic && !engines.newton.hasClumps();
  const bool knownAhead = skin.checkAhead && aheadFor_ == scene.iter;
  aheadFor_ = -1;
  const bool redetectFirst = oneRegion && (skin.check.rebuild || (knownAhead && movedAhead_));
  serialLap(StagePoint::SkinCheck, start);
  skin.checkNow = !redetectFirst && !knownAhead && !skin.check.rebuild;
  if (redetectFirst)
    redetect(scene, engines.collider, law, skin);
  else
    listChanged(scene, law);
  resetAndCheck(scene, engines, law, flow, skin, oneRegion);
  if (!oneRegion)
  {
    settleSkin(scene, engines, law, skin);
    if (integrate && scene.domain)
      prepareIntegration(scene, engines.newton); // the rows change when bodies migrate
  }
  else if (skin.moved)
    redetect(scene, engines.collider, law, skin);
  if (!oneRegion || skin.moved)
    region(scene, [&](int thread, int threads) {
      contactsThenBodies(scene, engines, law, flow, skin, skin.check, thread, threads);
    });
  contactsDone(scene, engines, law);
  if (integrate)
    integrationDone(scene, engines, skin);
}

void SharedRegions::resetAndCheck(Scene& scene, const Engines& engines, ContactLaw* law, Flow flow, Skin& skin,
                                  bool rest)
{
  const auto owned = static_cast<std::int64_t>(scene.ownedBodies());
  region(scene, [&](int thread, int threads) {
    Team::Member& my = team_.members[static_cast<std::size_t>(thread)];
    const auto [first, last] = bodyRanges_.range(owned, thread, threads);
    const double start = now();
    if (flow.reset && !gathersAhead(scene, law, flow))
    {
      ForceResetter::resetIn(scene.bodies, first, last);
      team_.lap(my, StagePoint::Reset);
    }
    if (skin.checkNow)
      my.moved = engines.collider.displacementsIn(scene, skin.check, first, last);
    my.bodySeconds += now() - start;
    if (!rest)
    {
      team_.lap(my, StagePoint::SkinCheck);
      return;
    }
    bool moved = false;
    Collider::SkinCheck ahead = skin.check;
    Collider::Displacements all;
    if (skin.checkNow)
    {
      teamBarrier(threads);
      if (thread == 0)
        ++barriers;
      for (int t = 0; t < threads; ++t)
        all.add(team_.members[static_cast<std::size_t>(t)].moved);
      moved = Collider::mustRebuild(skin.check, all);
      ahead.common = Collider::commonOf(all); // what the collider keeps after this check
    }
    team_.lap(my, StagePoint::SkinCheck);
    if (!moved)
      contactsThenBodies(scene, engines, law, flow, skin, ahead, thread, threads);
    if (thread == 0)
    {
      skin.moved = moved;
      skin.measured = all;
    }
  });
  if (rest && skin.checkNow && !skin.moved)
    engines.collider.noteDisplacements(skin.measured);
}

void SharedRegions::settleSkin(Scene& scene, const Engines& engines, ContactLaw* law, Skin& skin)
{
  const double start = now();
  if (skin.checkNow)
  {
    for (int t = 0; t < team_.used; ++t)
      skin.measured.add(team_.members[static_cast<std::size_t>(t)].moved);
    skin.moved = Collider::mustRebuild(skin.check, skin.measured);
  }
  // Split over processes, all decide from everyone's displacements and re-detect together,
  // after the bodies that left this process's region moved to their new owners.
  if (scene.domain)
    skin.moved = Collider::acrossProcesses(*scene.domain, skin.check.rebuild, skin.measured)
                 || Collider::mustRebuild(skin.check, skin.measured);
  const bool redetecting = skin.check.rebuild || skin.moved;
  if (!redetecting)
    engines.collider.noteDisplacements(skin.measured);
  serialLap(StagePoint::SkinCheck, start);
  if (redetecting && scene.domain)
  {
    const double migration = now();
    scene.domain->beforeDetection(scene);
    serialLap(StagePoint::Detection, migration);
  }
  if (redetecting)
    redetect(scene, engines.collider, law, skin);
  if (!law)
  {
    const double contacts = now();
    engines.loop.computeContacts(scene);
    serialLap(StagePoint::Contacts, contacts);
  }
}

bool SharedRegions::gathersAhead(const Scene& scene, const ContactLaw* law, Flow flow)
{
  // The reset then goes into the gather (nothing else writes the forces between them in the
  // region, and a step stopped by an overlap resets its bodies as the engines leave them).
  // Energy tracking computes the contacts in blocks in list order, which the gather does not
  // follow; split over processes, the bodies migrate between the reset and the contacts.
  return law && flow.reset && !scene.energy.enabled && !scene.domain;
}

void SharedRegions::contactsThenBodies(Scene& scene, const Engines& engines, ContactLaw* law, Flow flow,
                                       const Skin& skin, const Collider::SkinCheck& ahead, int thread, int threads)
{
  const bool integrate = flow.integrate;
  Team::Member& my = team_.members[static_cast<std::size_t>(thread)];
  const auto owned = static_cast<std::int64_t>(scene.ownedBodies());
  // Tracking energy, the integration sums the bodies' terms in whole blocks.
  BodyEnergy* bodyEnergy = integrate && scene.energy.enabled ? bodyEnergy_.data() : nullptr;
  const auto share = bodyRanges_.range(owned, thread, threads);
  const auto [first, last] = bodyEnergy ? blockAligned(share, owned) : share;
  std::optional<GatherAhead::Thread> gathering;
  if (gathersAhead(scene, law, flow))
    gathering.emplace(gatherAhead_, scene, engines.loop, thread, first, last, true);
  if (law)
  {
    const double start = now();
    const auto contacts = static_cast<std::int64_t>(scene.contacts.list.size());
    ContactEnergy* energy = scene.energy.enabled ? contactEnergy_.data() : nullptr;
    const std::int64_t bad = contactShares_.compute(scene, *law, thread, threads, {first, last}, energy,
                                                    gathering ? &*gathering : nullptr);
    my.badContact = bad < contacts ? bad : -1;
    const double early = gathering ? gathering->seconds() : 0;
    my.contactSeconds = now() - start - early;
    my.bodySeconds += early;
    teamBarrier(threads);
    if (thread == 0)
        ++barriers;
    team_.lap(my, StagePoint::Contacts);
    if (team_.timing)
    {
      my.stage[at(StagePoint::Contacts)] -= early;
      my.stage[at(StagePoint::Gather)] += early;
    }
    // A contact overlapping too much stops the step before any body moves, as the engines do,
    // unless the scene only counts such overlaps.
    if (scene.overlapStops)
      for (int t = 0; t < threads; ++t)
        if (team_.members[static_cast<std::size_t>(t)].badContact >= 0)
        {
          if (gathering)
            ForceResetter::resetIn(scene.bodies, first, last);
          return;
        }
  }
  const double start = now();
  if (gathering)
    gathering->finish();
  else
    engines.loop.gatherIn(scene, first, last);
  team_.lap(my, StagePoint::Gather);
  if (integrate)
  {
    if (engines.newton.hasClumps())
    {
      // A clump reads its members' forces and moves them, whichever thread gathered them.
      teamBarrier(threads);
      if (thread == 0)
        ++barriers;
    }
    my.badBody = engines.newton.integrateIn(scene, first, last, bodyEnergy);
    if (skin.checkAhead)
      my.movedAhead = engines.collider.displacementsIn(scene, ahead, first, last);
    team_.lap(my, StagePoint::Integration);
  }
  my.bodySeconds += now() - start;
}

void SharedRegions::listChanged(Scene& scene, ContactLaw* law)
{
  if (!law)
    return;
  if (law->needsExtra())
    alignContactExtra(scene.contacts);
  contactShares_.update(scene.contacts);
  gatherAhead_.update(scene.contacts, contactShares_);
  if (scene.energy.enabled)
    contactEnergy_.assign(energyBlocks(static_cast<std::int64_t>(scene.contacts.list.size())), ContactEnergy{});
}

void SharedRegions::redetect(Scene& scene, Collider& collider, ContactLaw* law, Skin& skin)
{
  const double start = now();
  collider.timingDeltas.start(scene.timingEnabled); // the re-detection labels its own stages
  collider.rebuild(scene);
  skin.check = collider.skinCheck(scene); // the next step's, around the new references
  serialLap(StagePoint::Detection, start);
  listChanged(scene, law);
}

void SharedRegions::contactsDone(Scene& scene, const Engines& engines, ContactLaw* law)
{
  if (!law)
    return; // computeContacts did it all
  law->stepDone();
  if (scene.energy.enabled)
  {
    detail::addContactEnergy(scene, contactEnergy_);
    if (!scene.energy.grownBy.empty())
      addGrownContactsEnergy(scene, engines.loop);
  }
  if (const std::int64_t bad = team_.first(&Team::Member::badContact); bad >= 0)
    InteractionLoop::overlapFound(scene, scene.contacts.list[static_cast<std::size_t>(bad)]);
}

void SharedRegions::integrationDone(Scene& scene, const Engines& engines, const Skin& skin)
{
  const double start = now();
  bodyEnergyDone(scene);
  engines.newton.finish(scene, team_.first(&Team::Member::badBody));
  if (skin.checkAhead)
  {
    Collider::Displacements movedAhead;
    for (int t = 0; t < team_.used; ++t)
      movedAhead.add(team_.members[static_cast<std::size_t>(t)].movedAhead);
    movedAhead_ = Collider::mustRebuild(skin.check, movedAhead);
    engines.collider.noteDisplacements(movedAhead);
    aheadFor_ = scene.iter + 1;
  }
  if (scene.domain)
    scene.domain->afterIntegration(scene);
  serialLap(StagePoint::Integration, start);
}

void SharedRegions::integrate(Scene& scene, NewtonIntegrator& newton)
{
  const double start = now();
  prepareIntegration(scene, newton);
  const auto owned = static_cast<std::int64_t>(scene.ownedBodies());
  const bool tracking = scene.energy.enabled;
  serialLap(StagePoint::Integration, start);
  region(scene, [&](int thread, int threads) {
    Team::Member& my = team_.members[static_cast<std::size_t>(thread)];
    const auto share = bodyRanges_.range(owned, thread, threads);
    const auto [first, last] = tracking ? blockAligned(share, owned) : share;
    const double begin = now();
    my.badBody = newton.integrateIn(scene, first, last, tracking ? bodyEnergy_.data() : nullptr);
    my.bodySeconds += now() - begin;
    team_.lap(my, StagePoint::Integration);
  });
  const double end = now();
  bodyEnergyDone(scene);
  newton.finish(scene, team_.first(&Team::Member::badBody));
  if (scene.domain)
    scene.domain->afterIntegration(scene);
  serialLap(StagePoint::Integration, end);
}

void SharedRegions::prepareIntegration(Scene& scene, NewtonIntegrator& newton)
{
  newton.prepare(scene);
  if (scene.energy.enabled)
    bodyEnergy_.assign(energyBlocks(static_cast<std::int64_t>(scene.ownedBodies())), {});
}

void SharedRegions::bodyEnergyDone(Scene& scene)
{
  if (!scene.energy.enabled)
    return;
  addPeriodicImageWork(scene);
  NewtonIntegrator::addEnergy(scene, bodyEnergy_);
}

void SharedRegions::stepDone()
{
  for (int t = 0; t < team_.used; ++t)
  {
    const Team::Member& m = team_.members[static_cast<std::size_t>(t)];
    bodyRanges_.record(t, m.bodySeconds);
    contactShares_.ranges.record(t, m.contactSeconds);
  }
  bodyRanges_.rebalance(team_.used);
  contactShares_.ranges.rebalance(team_.used);
  if (!team_.timing)
    return;
  for (std::size_t p = 0; p < stagePoints; ++p)
  {
    double longest = 0;
    for (int t = 0; t < team_.used; ++t)
      longest = std::max(longest, team_.members[static_cast<std::size_t>(t)].stage[p]);
    stageSeconds[p] += longest;
  }
}
} // namespace talus::dem
