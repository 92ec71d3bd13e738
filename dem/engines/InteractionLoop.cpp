#include "dem/engines/InteractionLoop.h"
#include "dem/contact/ContactGeometry.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/GatherVectors.h"

#include "dem/core/Scene.h"
#include "dem/base/Threads.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace talus::dem
{
void InteractionLoop::assignLaw(Contact& c, ContactExtra* x, const Scene& scene) const
{
  const Material& m1 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id1)])];
  const Material& m2 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id2)])];
  int best = 0;
  for (std::size_t k = 0; k < laws.size(); ++k)
  {
    const int score = laws[k]->handlesGeometry(c.kind) ? laws[k]->handles(m1, m2) : 0;
    if (score > best)
    {
      best = score;
      c.law = static_cast<std::uint8_t>(k);
    }
  }
  if (best == 0)
    throw std::runtime_error("no contact law of the InteractionLoop handles the contact of bodies "
                             + std::to_string(c.id1) + " and " + std::to_string(c.id2) + " (materials '" + m1.label
                             + "', '" + m2.label + "', shapes " + shapeName(scene.bodies.shape[static_cast<std::size_t>(c.id1)])
                             + " and " + shapeName(scene.bodies.shape[static_cast<std::size_t>(c.id2)]) + ")");
  laws[c.law]->initialize(c, laws[c.law]->needsExtra() ? x : nullptr, scene);
}

void InteractionLoop::checkMaterials(const Scene& scene)
{
  if (checkedMaterials_ == scene.materials.size())
    return;
  const auto& m = scene.materials;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = i; j < m.size(); ++j)
      if (laws[0]->handles(m[i], m[j]) == 0)
        throw std::runtime_error("the contact law " + laws[0]->typeName() + " cannot handle materials '" + m[i].label
                                 + "' and '" + m[j].label + "'; add a law for them to the InteractionLoop");
  checkedMaterials_ = m.size();
}

void InteractionLoop::checkShapes(const Scene& scene)
{
  if (checkedBodiesVersion_ == scene.bodiesVersion)
    return;
  const Bodies& b = scene.bodies;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    // The contact the body's shape makes with its own kind (walls, facets, boxes and clumps
    // touch only the others).
    const ShapeKind shape = b.shape[i];
    const ContactGeometryKind own = shape == ShapeKind::PotentialBlock      ? ContactGeometryKind::BlockBlock
                                    : shape == ShapeKind::PotentialParticle ? ContactGeometryKind::ParticleParticle
                                                                            : ContactGeometryKind::SphereSphere;
    const bool touchesItsKind = shape == ShapeKind::Sphere || shape == ShapeKind::PotentialBlock
                                || shape == ShapeKind::PotentialParticle;
    if (b.alive[i] && touchesItsKind && !laws[0]->handlesGeometry(own))
      throw std::runtime_error("the contact law " + laws[0]->typeName() + " cannot handle the contacts of body "
                               + std::to_string(i) + " (" + shapeName(shape)
                               + "); add a law for them to the InteractionLoop");
  }
  checkedBodiesVersion_ = scene.bodiesVersion;
}

std::string InteractionLoop::overlapReport(const Scene& scene, const Contact& c)
{
  const double rmin = std::min(c.refR1, c.refR2);
  char text[512];
  std::snprintf(text, sizeof text,
                "step %lld: bodies %d and %d overlap by %.3g, %.0f%% of the smaller radius (limit %.0f%%, "
                "O.maxOverlapRatio): the time step %.3g is too large for this contact (its own critical step is "
                "about %.3g; P-wave estimate %.3g) or the packing was created overlapping",
                static_cast<long long>(scene.iter), c.id1, c.id2, c.penetration, 100 * c.penetration / rmin,
                100 * scene.maxOverlapRatio, scene.dt, scene.contactTimeStep(), scene.pWaveTimeStep());
  return text;
}

void InteractionLoop::overlapFound(Scene& scene, const Contact& c)
{
  if (scene.overlapStops)
    throw std::runtime_error(overlapReport(scene, c));
  if (scene.overlapSteps++ == 0)
    scene.firstOverlap = overlapReport(scene, c);
}

void InteractionLoop::prepare(Scene& scene)
{
  if (laws.empty())
    throw std::runtime_error("InteractionLoop has no contact law");
  if (laws.size() > 255)
    throw std::runtime_error("InteractionLoop supports at most 255 contact laws");
  for (const auto& law : laws)
    law->prepare(scene);
  if (laws.size() == 1)
  {
    checkMaterials(scene);
    checkShapes(scene);
  }
}

Stages InteractionLoop::stages() const
{
  const Grain contacts = laws.size() == 1 && callbacks.empty() ? Grain::PerContact : Grain::Serial;
  return Stages{}.with(StagePoint::Contacts, contacts).with(StagePoint::Gather, Grain::PerBody);
}

void InteractionLoop::run(Scene& scene)
{
  prepare(scene);
  timingDeltas.start(scene.timingEnabled);
  computeContacts(scene);
  timingDeltas.checkpoint("geometry, physics, law");
  sumForcesPerBody(scene);
  timingDeltas.checkpoint("forces per body");
}

void InteractionLoop::computeContacts(Scene& scene)
{
  for (const auto& callback : callbacks)
    callback->stepInit();
  std::int64_t bad = -1;
  if (laws.size() == 1)
    bad = laws[0]->computeAll(scene); // the usual case: geometry, physics and forces in one pass
  else
  {
    computeWithSeveralLaws(scene);
    const auto& list = scene.contacts.list;
    for (std::size_t k = 0; k < list.size() && bad < 0; ++k)
      if (list[k].real && overlapsTooMuch(list[k], scene.maxOverlapRatio, scene.bodies))
        bad = static_cast<std::int64_t>(k);
  }
  if (scene.energy.enabled && !scene.energy.grownBy.empty())
    addGrownContactsEnergy(scene, *this);
  if (bad >= 0)
    overlapFound(scene, scene.contacts.list[static_cast<std::size_t>(bad)]);
  for (const auto& callback : callbacks)
    for (const Contact& c : scene.contacts.list)
      if (c.real)
        callback->go(c);
}

void InteractionLoop::computeWithSeveralLaws(Scene& scene) const
{
  ContactList& list = scene.contacts.list;
  const Bodies& bodies = scene.bodies;
  const auto n = static_cast<std::int64_t>(list.size());
  if (std::any_of(laws.begin(), laws.end(), [](const auto& law) { return law->needsExtra(); }))
    alignContactExtra(scene.contacts);
  ContactExtra* extra = scene.contacts.extraState();

  // 1. Geometry of every candidate pair; new contacts get their law and physics.
  bool failed = false;
  std::string failure;
#pragma omp parallel for if (n >= parallelLoopMinimum) schedule(static)
  for (std::int64_t k = 0; k < n; ++k)
  {
    Contact& c = list[static_cast<std::size_t>(k)];
    ContactExtra* x = extra ? extra + k : nullptr;
    if (updateContactGeometry(c, bodies, scene.periodic ? &scene.cell : nullptr, scene.dt, x) && c.fresh)
    {
      try
      {
        assignLaw(c, x, scene);
      }
      catch (const std::exception& e)
      {
#pragma omp critical(talus_interaction_loop_error)
        if (!failed)
        {
          failed = true;
          failure = e.what();
        }
      }
    }
  }
  if (failed)
    throw std::runtime_error(failure);

  // 2. Forces, law by law.
  for (std::size_t k = 0; k < laws.size(); ++k)
    laws[k]->computeForces(scene, static_cast<std::uint8_t>(k));
}

namespace
{
/// The force-and-torque gather of bodies [first, last) for one kind of scene: `Periodic` takes
/// body 2's lever arm from its periodic image (Cell::shift of the contact's cellDist, the
/// shift the geometry used this step: the cell does not change inside the InteractionLoop);
/// otherwise no record is read beyond its first cache line (Contact's layout note). `Reset` sets
/// the sums on the permanent forces (the same bits as a reset followed by the gather's addition).
/// `vectors`: gatherVectors may take the bodies (not with energy tracking, which takes every
/// contact and body in scalar code, the tests' reference).
template <bool Periodic, bool Reset>
void gatherRange(Scene& scene, const ContactExtra* extra, std::int64_t first, std::int64_t last, bool vectors)
{
  const ContactList& list = scene.contacts.list;
  Bodies& b = scene.bodies;
  const Contacts& contacts = scene.contacts;
  const Cell& cell = scene.cell;
  const auto entryCount = static_cast<std::int64_t>(contacts.entries.size());
  constexpr std::int64_t prefetchDistance = 16; // entries ahead: a few hundred nanoseconds of work
  // A body's components in one AVX2 vector where the processor has it (the same bits: the
  // same operations component by component, in this loop's order).
  if (vectors && extra == nullptr && gatherVectorsAvailable())
  {
    gatherVectors(contacts, b, Periodic ? &cell : nullptr, first, last, Reset);
    return;
  }
  for (std::int64_t id = first; id < last; ++id)
  {
    const auto i = static_cast<std::size_t>(id);
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (std::int64_t e = contacts.start[i]; e < contacts.start[i + 1]; ++e)
    {
      const std::int64_t entry = contacts.entries[static_cast<std::size_t>(e)];
      const Contact& c = list[static_cast<std::size_t>(entry >> 1)];
      // The records come in a few interleaved runs (a body's contacts with its lower and higher
      // neighbours), one cache line each: the hardware prefetchers miss that pattern, and
      // without this hint the one-line layout made the gather slower than the old
      // three-lines-per-record one; with it, faster (docs/dem.md, Speed: what the large beds
      // taught).
      if (e + prefetchDistance < entryCount)
      {
        const auto ahead = static_cast<std::size_t>(contacts.entries[static_cast<std::size_t>(e + prefetchDistance)] >> 1);
        __builtin_prefetch(&list[ahead]);
        // The moments of a law that keeps them: the first and last bytes of the pair, which
        // may lie on two lines.
        if (extra)
        {
          __builtin_prefetch(&extra[ahead].momentBending);
          __builtin_prefetch(reinterpret_cast<const char*>(&extra[ahead].momentTwist) + sizeof(Vec3) - 1);
        }
      }
      // No test of c.real and no branch on the side: a contact that is not real carries a zero
      // force (Contact::reset), and whether a body is a contact's first or second is as
      // unpredictable as whether a candidate pair touches. The sign is computed, not selected
      // (for `second ? 1.0 : -1.0` GCC 12 emits a branch). The force on this body and its moment
      // about the centre, applied at the contact point.
      const std::int64_t second = entry & 1;
      const Vec3 force = static_cast<double>(2 * second - 1) * c.force;
      f += force;
      if constexpr (Periodic)
      {
        // Only contacts across the boundary have an image to shift to, and they are few: a
        // predictable test spares the others the shift's matrix product.
        const Vec3 lever = c.cellDist == Eigen::Vector3i::Zero()
                               ? Vec3(c.contactPoint - b.pos[i])
                               : Vec3(c.contactPoint - (b.pos[i] + static_cast<double>(second) * cell.shift(c.cellDist)));
        t += lever.cross(force);
      }
      else
        t += (c.contactPoint - b.pos[i]).cross(force);
      if (extra && c.real)
      {
        const ContactExtra& x = extra[entry >> 1];
        const Vec3 moment = x.momentBending + x.momentTwist;
        t += static_cast<double>(2 * second - 1) * moment;
      }
    }
    if constexpr (Reset)
    {
      b.force[i] = b.extForce[i] + f;
      b.torque[i] = b.extTorque[i] + t;
    }
    else
    {
      b.force[i] += f;
      b.torque[i] += t;
    }
  }
}

} // namespace

const ContactExtra* InteractionLoop::contactMoments(const Contacts& contacts) const
{
  const bool moments = std::any_of(laws.begin(), laws.end(), [](const auto& law) { return law->keepsMoments(); });
  return moments ? contacts.extraState() : nullptr;
}

void InteractionLoop::gatherIn(Scene& scene, std::int64_t first, std::int64_t last, bool reset) const
{
  // Bodies added since the last re-detection have no contacts (nor entries in the index) yet.
  const std::int64_t indexed = std::min(last, scene.contacts.indexedBodies());
  const ContactExtra* moments = contactMoments(scene.contacts);
  const bool vectors = !scene.energy.enabled;
  if (reset)
  {
    if (scene.periodic)
      gatherRange<true, true>(scene, moments, first, indexed, vectors);
    else
      gatherRange<false, true>(scene, moments, first, indexed, vectors);
    ForceResetter::resetIn(scene.bodies, std::max(first, indexed), last);
  }
  else if (scene.periodic)
    gatherRange<true, false>(scene, moments, first, indexed, vectors);
  else
    gatherRange<false, false>(scene, moments, first, indexed, vectors);
}

void InteractionLoop::sumForcesPerBody(Scene& scene)
{
  balancedFor(gatherRanges_, scene.contacts.indexedBodies(),
              [&](std::int64_t first, std::int64_t last) { gatherIn(scene, first, last); });
}

void addGrownContactsEnergy(Scene& scene, const InteractionLoop& loop)
{
  EnergyTracker& e = scene.energy;
  e.grownBy.resize(scene.bodies.size(), 0.0); // bodies added since the growth did not grow
  for (std::size_t k = 0; k < loop.laws.size(); ++k)
    e.growthWork -= loop.laws[k]->grownElasticEnergy(scene, static_cast<std::uint8_t>(k), e.grownBy);
  e.grownBy.clear();
}
} // namespace talus::dem
