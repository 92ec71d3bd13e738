#pragma once

// The loops of ContactLawKernel, included by each law's .cpp (they need the Scene).
#include "dem/laws/ContactLaw.h"
#include "dem/contact/FacetGeometryBatch.h"
#include "dem/contact/SphereCandidatesApart.h"
#include "dem/contact/SphereGeometryBatch.h"
#include "dem/core/Scene.h"
#include "dem/base/Threads.h"

#include <algorithm>
#include <bit>

namespace talus::dem
{
namespace detail
{
/// The step's context for a law (with Contacts::extra aligned if the law uses it).
template <class Law>
StepContext stepContext(Scene& scene)
{
  ContactExtra* extra = nullptr;
  if constexpr (Law::usesExtra)
  {
    alignContactExtra(scene.contacts);
    extra = scene.contacts.extra.data();
  }
  return StepContext{scene.bodies, scene.materials, scene.periodic ? &scene.cell : nullptr, scene.dt, extra,
                     scene.maxOverlapRatio};
}

/// Add per-block contact energies to the scene's tracker, in block order.
inline void addContactEnergy(Scene& scene, const std::vector<ContactEnergy>& blocks)
{
  ContactEnergy total;
  for (const ContactEnergy& e : blocks)
    total += e;
  scene.energy.plastDissip += total.plastDissip;
  scene.energy.viscDamp += total.viscDamp;
}
} // namespace detail

template <class Law>
void ContactLawKernel<Law>::prepare(Scene& scene)
{
  realMix_.follow(scene.contacts);
}

template <class Law>
void ContactLawKernel<Law>::computeForces(Scene& scene, std::uint8_t lawIndex)
{
  if (scene.energy.enabled)
    loopForces<true>(scene, lawIndex);
  else
    loopForces<false>(scene, lawIndex);
}

template <class Law>
template <bool Track>
void ContactLawKernel<Law>::loopForces(Scene& scene, std::uint8_t lawIndex)
{
  const Law& law = static_cast<const Law&>(*this);
  ContactList& list = scene.contacts.list;
  const StepContext step = detail::stepContext<Law>(scene);
  const auto n = static_cast<std::int64_t>(list.size());
  // Tracking energy: contacts in fixed blocks, each block's energies summed in order.
  // Split over processes, a contact across two of them is computed by both and its energy
  // counted by one (Domain::countsContact).
  const Domain* domain = Track ? scene.domain.get() : nullptr;
  auto one = [&](std::int64_t k, ContactEnergy& e) {
    Contact& c = list[static_cast<std::size_t>(k)];
    ContactEnergy uncounted;
    if (c.real && c.law == lawIndex)
      law.template force<Track>(c, static_cast<std::size_t>(k), step,
                                countsContact(domain, static_cast<std::size_t>(c.id1), static_cast<std::size_t>(c.id2)) ? e : uncounted);
  };
  if constexpr (Track)
  {
    // Contacts in fixed blocks, each block's energies summed in order.
    const std::int64_t blocks = (n + energyBlock - 1) / energyBlock;
    std::vector<ContactEnergy> energy(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(static) if (n >= parallelLoopMinimum)
    for (std::int64_t blk = 0; blk < blocks; ++blk)
      for (std::int64_t k = blk * energyBlock, end = std::min(n, k + energyBlock); k < end; ++k)
        one(k, energy[static_cast<std::size_t>(blk)]);
    detail::addContactEnergy(scene, energy);
  }
  else
  {
    ContactEnergy unused;
#pragma omp parallel for schedule(static) firstprivate(unused) if (n >= parallelLoopMinimum)
    for (std::int64_t k = 0; k < n; ++k)
      one(k, unused);
  }
  stepDone();
}

template <class Law>
std::int64_t ContactLawKernel<Law>::computeAll(Scene& scene)
{
  return scene.energy.enabled ? loopAll<true>(scene) : loopAll<false>(scene);
}

template <class Law>
template <bool Track, bool RealMixed>
std::int64_t ContactLawKernel<Law>::firstBadIn(Scene& scene, const StepContext& step, std::int64_t first,
                                               std::int64_t last, ContactEnergy& energy) const
{
  const Law& law = static_cast<const Law&>(*this);
  ContactList& list = scene.contacts.list;
  const auto n = static_cast<std::int64_t>(list.size());
  const double ratio = scene.maxOverlapRatio;
  constexpr std::int64_t extraPrefetchDistance = 8; // contacts ahead: a few hundred nanoseconds of work
  constexpr std::int64_t recordPrefetchDistance = 32; // contacts ahead (8 KB of records)
  std::int64_t bad = n;
  // Split over processes, a contact across two of them is computed by both and its energy
  // counted by one (Domain::countsContact).
  const Domain* domain = Track ? scene.domain.get() : nullptr;
  ContactEnergy uncounted;
  // A contact's forces, its geometry of this step made.
  auto forces = [&](Contact& c, std::int64_t k) {
    law.template force<Track>(c, static_cast<std::size_t>(k), step,
                              countsContact(domain, static_cast<std::size_t>(c.id1), static_cast<std::size_t>(c.id2)) ? energy : uncounted);
    if (overlapsTooMuch(c, ratio, step.bodies))
      bad = std::min(bad, k);
  };
  const bool turnMoments = law.carriesMoments();
  auto geometryAndForces = [&](Contact& c, std::int64_t k) [[gnu::always_inline]] {
    ContactExtra* x = Law::usesExtra ? step.extra + k : nullptr;
    // Sphere pairs take the inline geometry. A law whose state the geometry does not read
    // (Hertz-Mindlin's stiffnesses) gives it none: no test of bonds and moments, and no read of
    // the state's cache lines for them.
    ContactExtra* geometryState = Law::geometryUsesExtra ? x : nullptr;
    if (!(c.kind == ContactGeometryKind::SphereSphere
              ? contactGeometry<true>(c, step.bodies, step.cell, step.dt, geometryState, turnMoments)
              : updateContactGeometry(c, step.bodies, step.cell, step.dt, geometryState, turnMoments)))
      return;
    if (c.fresh)
    {
      c.law = 0;
      law.initialize(c, x, scene);
    }
    forces(c, k);
  };
  // Sphere pairs that were in contact go four at a time through the lanes of
  // sphereGeometryBatch where the processor has them (the same bits as contactGeometry), or of
  // the law's own lanes for the geometry and the forces, the others one by one; in a periodic
  // cell, those across its boundary too (their image's shift taken as contactGeometry takes it).
  // Without energy to sum in order, the order is free: a contact writes only its own record.
  const bool batched = !Track && !Law::geometryUsesExtra && sphereBatchAvailable();
  Contact* batch[sphereBatchWidth];
  std::int64_t batchIndex[sphereBatchWidth];
  int waiting = 0;
  // The lines of a state record to prefetch: a law whose geometry reads the state (bonds,
  // moments) reads all of them, the others (Hertz-Mindlin's stiffnesses) its first.
  constexpr std::size_t extraPrefetchBytes = Law::geometryUsesExtra ? sizeof(ContactExtra) : 1;
  // Facet-sphere pairs likewise, four at a time through facetGeometryBatch: the real ones that
  // still touch get their geometry there, the others that do not touch are done, the rest
  // (beginning or ending) go one by one.
  Contact* facets[sphereBatchWidth];
  std::int64_t facetIndex[sphereBatchWidth];
  int facetsWaiting = 0;
  // Sphere pairs that are candidates only, not across a periodic boundary: four at a time
  // through spheresApart, which dismisses those whose spheres stay apart (most of them); the
  // others, beginning a contact, go one by one.
  Contact* candidates[sphereBatchWidth];
  std::int64_t candidateIndex[sphereBatchWidth];
  int candidatesWaiting = 0;
  auto testCandidates = [&]() [[gnu::always_inline]] {
    for (unsigned near = ~spheresApart(candidates, step.bodies) & ((1U << sphereBatchWidth) - 1); near != 0;
         near &= near - 1)
    {
      const int i = std::countr_zero(near);
      geometryAndForces(*candidates[i], candidateIndex[i]);
    }
    candidatesWaiting = 0;
  };
  auto runLanes = [&]() [[gnu::always_inline]] {
    SphereLanes done;
    if constexpr (requires { law.sphereLanes(batch, batchIndex, step); })
      done = law.sphereLanes(batch, batchIndex, step);
    else
      done.geometry = sphereGeometryBatch(batch, step.bodies, step.dt, step.cell);
    // The lanes' forces are made; those overlapping too little to fail the check are done.
    for (unsigned deep = done.deep; deep != 0; deep &= deep - 1)
    {
      const int i = std::countr_zero(deep);
      if (overlapsTooMuch(*batch[i], ratio, step.bodies))
        bad = std::min(bad, batchIndex[i]);
    }
    if (done.forces != (1U << sphereBatchWidth) - 1)
    {
      for (int i = 0; i < sphereBatchWidth; ++i)
        if (!(done.geometry & (1U << i)))
          geometryAndForces(*batch[i], batchIndex[i]);
        else if (!(done.forces & (1U << i)))
          forces(*batch[i], batchIndex[i]);
    }
    waiting = 0;
  };
  for (std::int64_t k = first; k < last; ++k)
  {
    Contact& c = list[static_cast<std::size_t>(k)];
    // A candidate that stays apart reads only its record's first line (ids, kind, real) and
    // is dismissed in a few nanoseconds: the loop outruns the hardware prefetchers and waits on
    // that line without the hint.
    if (k + recordPrefetchDistance < last)
      __builtin_prefetch(&list[static_cast<std::size_t>(k + recordPrefetchDistance)]);
    // The state's records are wider than the contacts' and read only for the contacts that
    // touch: the hardware prefetchers do not see that pattern, and without the hint the force
    // waits on the state's lines.
    if constexpr (Law::usesExtra)
      if (k + extraPrefetchDistance < last)
        for (std::size_t byte = 0; byte < extraPrefetchBytes; byte += 64)
          __builtin_prefetch(reinterpret_cast<const char*>(step.extra + k + extraPrefetchDistance) + byte);
    if (batched && c.kind == ContactGeometryKind::FacetSphere
        && (step.cell == nullptr || c.cellDist == Eigen::Vector3i::Zero()))
    {
      facets[facetsWaiting] = &c;
      facetIndex[facetsWaiting] = k;
      if (++facetsWaiting < sphereBatchWidth)
        continue;
      const FacetLanes done = facetGeometryBatch(facets, step.bodies, step.dt);
      for (int i = 0; i < sphereBatchWidth; ++i)
        if (done.geometry & (1U << i))
          forces(*facets[i], facetIndex[i]);
        else if (!(done.apart & (1U << i)))
          geometryAndForces(*facets[i], facetIndex[i]);
      facetsWaiting = 0;
      continue;
    }
    if constexpr (RealMixed)
    {
      if (!(batched && c.kind == ContactGeometryKind::SphereSphere))
      {
        geometryAndForces(c, k);
        continue;
      }
      // Both queues take the record and only its own counts it: no branch on `real`, which
      // the predictor misses often in a list of contacts and candidates mixed (RealMix).
      const bool real = c.real;
      const bool inside = step.cell == nullptr || c.cellDist == Eigen::Vector3i::Zero();
      batch[waiting] = &c;
      batchIndex[waiting] = k;
      candidates[candidatesWaiting] = &c;
      candidateIndex[candidatesWaiting] = k;
      waiting += static_cast<int>(real);
      candidatesWaiting += static_cast<int>(inside && !real);
      if (!inside && !real)
        geometryAndForces(c, k); // a candidate across the periodic boundary
      if (candidatesWaiting == sphereBatchWidth)
        testCandidates();
      if (waiting < sphereBatchWidth)
        continue;
    }
    else
    {
      if (batched && !c.real && c.kind == ContactGeometryKind::SphereSphere
          && (step.cell == nullptr || c.cellDist == Eigen::Vector3i::Zero()))
      {
        candidates[candidatesWaiting] = &c;
        candidateIndex[candidatesWaiting] = k;
        if (++candidatesWaiting == sphereBatchWidth)
          testCandidates();
        continue;
      }
      if (!(batched && c.real && c.kind == ContactGeometryKind::SphereSphere))
      {
        geometryAndForces(c, k);
        continue;
      }
      batch[waiting] = &c;
      batchIndex[waiting] = k;
      if (++waiting < sphereBatchWidth)
        continue;
    }
    runLanes();
  }
  for (int i = 0; i < waiting; ++i)
    geometryAndForces(*batch[i], batchIndex[i]);
  for (int i = 0; i < facetsWaiting; ++i)
    geometryAndForces(*facets[i], facetIndex[i]);
  for (int i = 0; i < candidatesWaiting; ++i)
    geometryAndForces(*candidates[i], candidateIndex[i]);
  return bad;
}

template <class Law>
template <bool Track>
std::int64_t ContactLawKernel<Law>::loopAll(Scene& scene)
{
  const StepContext step = detail::stepContext<Law>(scene);
  const auto n = static_cast<std::int64_t>(scene.contacts.list.size());
  std::int64_t firstBad = n;
  if constexpr (Track)
  {
    // Contacts in fixed blocks, each block's energies summed in order.
    const std::int64_t blocks = (n + energyBlock - 1) / energyBlock;
    std::vector<ContactEnergy> energy(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(static) reduction(min : firstBad) if (n >= parallelLoopMinimum)
    for (std::int64_t blk = 0; blk < blocks; ++blk)
      firstBad = std::min(firstBad, firstBadIn<true>(scene, step, blk * energyBlock, std::min(n, (blk + 1) * energyBlock),
                                                     energy[static_cast<std::size_t>(blk)]));
    detail::addContactEnergy(scene, energy);
  }
  else
  {
    const bool mixed = realMix_.mixed();
    auto firstIn = [&](std::int64_t first, std::int64_t last) {
      ContactEnergy unused;
      return mixed ? firstBadIn<false, true>(scene, step, first, last, unused)
                   : firstBadIn<false>(scene, step, first, last, unused);
    };
    firstBad = balancedFor(ranges_, n, n, firstIn, [](std::int64_t a, std::int64_t c) { return std::min(a, c); });
  }
  stepDone();
  return firstBad < n ? firstBad : -1;
}

template <class Law>
std::int64_t ContactLawKernel<Law>::computeAllIn(Scene& scene, std::int64_t first, std::int64_t last,
                                                 ContactEnergy* energyBlocks)
{
  const StepContext step = detail::stepContext<Law>(scene);
  if (!energyBlocks)
  {
    ContactEnergy unused;
    return realMix_.mixed() ? firstBadIn<false, true>(scene, step, first, last, unused)
                            : firstBadIn<false>(scene, step, first, last, unused);
  }
  std::int64_t bad = static_cast<std::int64_t>(scene.contacts.list.size());
  for (std::int64_t start = first; start < last; start += energyBlock)
    bad = std::min(bad, firstBadIn<true>(scene, step, start, std::min(last, start + energyBlock),
                                         energyBlocks[start / energyBlock]));
  return bad;
}

template <class Law>
double ContactLawKernel<Law>::elasticEnergy(const Scene& scene, std::uint8_t lawIndex) const
{
  const Law& law = static_cast<const Law&>(*this);
  const ContactList& list = scene.contacts.list;
  const ContactExtra* extra = Law::usesExtra ? scene.contacts.extraState() : nullptr;
  double sum = 0;
  for (std::size_t k = 0; k < list.size(); ++k)
    if (list[k].real && list[k].law == lawIndex
        && countsContact(scene.domain.get(), static_cast<std::size_t>(list[k].id1), static_cast<std::size_t>(list[k].id2)))
      sum += law.elastic(list[k], extra ? extra + k : nullptr);
  return sum;
}

template <class Law>
double ContactLawKernel<Law>::grownElasticEnergy(const Scene& scene, std::uint8_t lawIndex,
                                                 const std::vector<double>& grownBy) const
{
  const Law& law = static_cast<const Law&>(*this);
  const ContactList& list = scene.contacts.list;
  const ContactExtra* extra = Law::usesExtra ? scene.contacts.extraState() : nullptr;
  double sum = 0;
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    const Contact& c = list[k];
    if (!c.real || !c.fresh || c.law != lawIndex
        || !countsContact(scene.domain.get(), static_cast<std::size_t>(c.id1), static_cast<std::size_t>(c.id2)))
      continue;
    const double growth = grownBy[static_cast<std::size_t>(c.id1)] + grownBy[static_cast<std::size_t>(c.id2)];
    if (growth <= 0)
      continue;
    Contact ungrown = c; // as it would be without the growth
    ungrown.penetration = std::max(c.penetration - growth, 0.0);
    const ContactExtra* x = extra ? extra + k : nullptr;
    sum += law.elastic(c, x) - law.elastic(ungrown, x);
  }
  return sum;
}
} // namespace talus::dem
