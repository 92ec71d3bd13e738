// Checkpoints of a scene split over MPI ranks: the rows put in I/O order, then one file written
// by every rank (dem/checkpoint/Together.h); reading is the serial reader's on every rank.
#include "dem/distributed/collect/Checkpoint.h"

#include "dem/checkpoint/Together.h"
#include "dem/core/Scene.h"
#include "dem/distributed/Collective.h"
#include "dem/distributed/MpiDomain.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace talus::dem::distributed
{
namespace
{
/// How long a rank whose write failed waits for the others to check with it before it ends the
/// run: they come at once unless the failure was inside one of HDF5's collective calls (a full
/// disk), which then holds them waiting for this rank.
constexpr double patienceSeconds = 10;

/// Raise CollectiveCheckpointError on every rank, with the lowest failing rank's message, when
/// any rank has an error (collective; lowestRankError's patience).
void agree(MPI_Comm comm, const std::string& localError)
{
  if (std::string message = lowestRankError(comm, localError, patienceSeconds); !message.empty())
    throw CollectiveCheckpointError(message);
}

/// The rank whose slab of the file holds global id `id`: rank r writes [N r / P, N (r + 1) / P).
int slabOf(GlobalId id, std::int64_t N, int P) { return static_cast<int>(((id + 1) * P - 1) / N); }

/// The first global id of rank r's slab.
GlobalId slabStart(int r, std::int64_t N, int P) { return N * r / P; }

/// The value of an erased slot's field: zero (an identity rotation).
template <class T>
T blank()
{
  if constexpr (requires { T::Zero(); })
    return T::Zero();
  else if constexpr (requires { T::Identity(); })
    return T::Identity();
  else
    return T{};
}

/// Process 0's text records, on every rank (collective).
CheckpointExtras extrasOfRankZero(MPI_Comm comm, const CheckpointExtras& extras)
{
  std::vector<char> packed;
  for (const auto& [name, value] : extras)
    for (const std::string* s : {&name, &value})
    {
      const std::uint64_t length = s->size();
      packed.insert(packed.end(), reinterpret_cast<const char*>(&length), reinterpret_cast<const char*>(&length + 1));
      packed.insert(packed.end(), s->begin(), s->end());
    }
  std::uint64_t size = packed.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm);
  packed.resize(size);
  MPI_Bcast(packed.data(), static_cast<int>(size), MPI_CHAR, 0, comm);
  CheckpointExtras out;
  for (std::size_t at = 0; at < packed.size();)
  {
    std::string pair[2];
    for (std::string& s : pair)
    {
      std::uint64_t length = 0;
      std::memcpy(&length, packed.data() + at, sizeof(length));
      at += sizeof(length);
      s.assign(packed.data() + at, length);
      at += length;
    }
    out[pair[0]] = pair[1];
  }
  return out;
}

/// This rank's slab of the bodies, in global-id order: the spheres from their owners, the
/// bodies every rank holds from this rank's copy with their forces summed over the ranks (what
/// O.forces reads of them), the erased ones as blank slots. Its shape tables are the scene's.
Bodies bodySlab(MPI_Comm comm, const MpiDomain& d, Scene& scene)
{
  const std::int64_t N = d.globalCount();
  const int P = d.ranks();
  const GlobalId lo = slabStart(d.rank(), N, P), hi = slabStart(d.rank() + 1, N, P);
  const std::size_t n = scene.bodies.size();
  std::vector<GlobalId> ids(n);
  for (std::size_t i = 0; i < n; ++i)
    ids[i] = d.globalIdOf(i);
  std::vector<std::int64_t> sent, mineHere;
  std::vector<int> to;
  std::vector<double> replicatedForces; // six per replicated body, in global-id order
  std::vector<std::size_t> forcesOf;    // per row of mineHere: its entry there
  for (std::size_t i = 0; i < n; ++i)
    if (d.replicated(i))
    {
      if (ids[i] >= lo && ids[i] < hi)
      {
        mineHere.push_back(static_cast<std::int64_t>(i));
        forcesOf.push_back(replicatedForces.size());
      }
      const Vec3 &f = scene.bodies.force[i], &t = scene.bodies.torque[i];
      replicatedForces.insert(replicatedForces.end(), {f.x(), f.y(), f.z(), t.x(), t.y(), t.z()});
    }
    else if (d.owns(i))
    {
      sent.push_back(static_cast<std::int64_t>(i));
      to.push_back(slabOf(ids[i], N, P));
    }
  // Every rank holds the same replicated bodies, in the same order: each holds its part of
  // their forces.
  d.sum(replicatedForces);

  // While the rows travel, a clump's member names it by global id (each rank's rows are its own).
  std::vector<BodyId> clumpRows = scene.bodies.clumpId;
  for (BodyId& clump : scene.bodies.clumpId)
    if (clump >= 0)
      clump = static_cast<BodyId>(ids[static_cast<std::size_t>(clump)]);
  // The rows are lent to the exchange (no copy of them), and given back whatever happens.
  struct Lent
  {
    Scene& scene;
    RankBodies rows;
    std::vector<BodyId> clumpRows;
    ~Lent()
    {
      rows.bodies.clumpId = std::move(clumpRows);
      scene.bodies = std::move(rows.bodies);
    }
  } lent{scene, {std::move(scene.bodies), std::move(ids)}, std::move(clumpRows)};
  RankBodies slab;
  sendRows(comm, lent.rows, sent, to, slab);
  std::vector<std::byte> packed;
  packRows(lent.rows, mineHere, packed);
  const std::size_t firstReplicated = slab.size();
  unpackRows(packed, slab);
  for (std::size_t k = 0; k < mineHere.size(); ++k)
  {
    const double* ft = replicatedForces.data() + forcesOf[k];
    slab.bodies.force[firstReplicated + k] = Vec3(ft[0], ft[1], ft[2]);
    slab.bodies.torque[firstReplicated + k] = Vec3(ft[3], ft[4], ft[5]);
  }
  // Erased bodies: no rank holds them.
  std::vector<GlobalId> held = slab.globalId;
  std::sort(held.begin(), held.end());
  for (GlobalId id = lo; id < hi; ++id)
    if (!std::binary_search(held.begin(), held.end(), id))
    {
      forEachBodyField(slab.bodies, [](auto& field) {
        using T = typename std::decay_t<decltype(field)>::value_type;
        field.push_back(blank<T>());
      });
      slab.bodies.alive.back() = 0;
      slab.globalId.push_back(id);
    }
  std::vector<std::int64_t> order(slab.size());
  std::iota(order.begin(), order.end(), std::int64_t{0});
  std::sort(order.begin(), order.end(), [&](std::int64_t a, std::int64_t b) {
    return slab.globalId[static_cast<std::size_t>(a)] < slab.globalId[static_cast<std::size_t>(b)];
  });
  RankBodies out;
  out.bodies = lent.rows.bodies; // the shape tables and settings; the per-body arrays follow
  forEachBodyField(out.bodies, [](auto& field) {
    field.clear();
    field.shrink_to_fit();
  });
  for (std::size_t k = 0; k < out.bodies.clumps.size(); ++k) // every clump's members, by global id
  {
    const std::vector<GlobalId>& members = d.clumpMembers()[k];
    out.bodies.clumps[k].members.assign(members.begin(), members.end());
  }
  packed.clear();
  packRows(slab, order, packed);
  unpackRows(packed, out);
  if (out.size() != static_cast<std::size_t>(hi - lo)
      || (out.size() > 0 && (out.globalId.front() != lo || out.globalId.back() != hi - 1)))
    throw std::logic_error("checkpoint: rank " + std::to_string(d.rank()) + " gathered "
                           + std::to_string(out.size()) + " bodies for the global ids " + std::to_string(lo) + " to "
                           + std::to_string(hi - 1) + ", not each once");
  return std::move(out.bodies);
}

/// The contacts of this rank's slab (those whose first body is in it), each once, sorted by
/// their bodies' global ids, with their richer state when any rank keeps some.
void contactSlab(MPI_Comm comm, const MpiDomain& d, const Scene& scene, Contacts& into, bool& withExtra)
{
  const std::int64_t N = d.globalCount();
  const int P = d.ranks();
  const ContactList& list = scene.contacts.list;
  int anyExtra = scene.contacts.extra.empty() ? 0 : 1;
  MPI_Allreduce(MPI_IN_PLACE, &anyExtra, 1, MPI_INT, MPI_MAX, comm);
  withExtra = anyExtra != 0;
  std::vector<std::vector<std::byte>> out(static_cast<std::size_t>(P));
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    Contact c = list[k];
    const auto r1 = static_cast<std::size_t>(c.id1), r2 = static_cast<std::size_t>(c.id2);
    // Held by both ranks of its bodies; counted by one.
    if (!c.real || !d.owns(d.replicated(r1) ? r2 : r1))
      continue;
    c.id1 = static_cast<BodyId>(d.globalIdOf(r1));
    c.id2 = static_cast<BodyId>(d.globalIdOf(r2));
    std::vector<std::byte>& o = out[static_cast<std::size_t>(slabOf(c.id1, N, P))];
    appendBytes(o, c);
    if (withExtra)
      appendBytes(o, k < scene.contacts.extra.size() ? scene.contacts.extra[k] : ContactExtra{});
  }
  const std::vector<std::byte> in = sendBytes(comm, out);
  ContactList records;
  ContactExtraList extra;
  for (const std::byte* p = in.data(); p < in.data() + in.size();)
  {
    Contact c;
    p = readBytes(p, c);
    records.push_back(c);
    if (withExtra)
    {
      ContactExtra x;
      p = readBytes(p, x);
      extra.push_back(x);
    }
  }
  std::vector<std::size_t> order(records.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::pair(records[a].id1, records[a].id2) < std::pair(records[b].id1, records[b].id2);
  });
  for (const std::size_t k : order)
  {
    into.list.push_back(records[k]);
    if (withExtra)
      into.extra.push_back(extra[k]);
  }
}
/// The energy tracker's memory of each body's last imposed motion (previousDisplacement,
/// previousRotation) for this rank's slab, by global id (NaN where no process keeps one: a body
/// not tracked yet), into `into`; false, leaving it empty, when no process keeps any.
bool energyMemorySlab(MPI_Comm comm, const MpiDomain& d, const Scene& scene, EnergyTracker& into)
{
  const EnergyTracker& e = scene.energy;
  const std::size_t n = scene.bodies.size();
  const bool here = n > 0 && e.previousDisplacement.size() == n && e.previousRotation.size() == n;
  int any = here ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, comm);
  into.previousDisplacement.clear();
  into.previousRotation.clear();
  if (any == 0)
    return false;
  const std::int64_t N = d.globalCount();
  const int P = d.ranks();
  const GlobalId lo = slabStart(d.rank(), N, P), hi = slabStart(d.rank() + 1, N, P);
  const Vec3 none = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  into.previousDisplacement.assign(static_cast<std::size_t>(hi - lo), none);
  into.previousRotation.assign(static_cast<std::size_t>(hi - lo), none);
  std::vector<std::vector<std::byte>> out(static_cast<std::size_t>(P));
  for (std::size_t i = 0; here && i < n; ++i)
  {
    const GlobalId id = d.globalIdOf(i);
    if (d.replicated(i) && id >= lo && id < hi) // moved alike on every rank: this rank's copy
    {
      into.previousDisplacement[static_cast<std::size_t>(id - lo)] = e.previousDisplacement[i];
      into.previousRotation[static_cast<std::size_t>(id - lo)] = e.previousRotation[i];
    }
    else if (!d.replicated(i) && d.owns(i))
    {
      std::vector<std::byte>& o = out[static_cast<std::size_t>(slabOf(id, N, P))];
      appendBytes(o, id);
      appendBytes(o, e.previousDisplacement[i]);
      appendBytes(o, e.previousRotation[i]);
    }
  }
  const std::vector<std::byte> in = sendBytes(comm, out);
  for (const std::byte* p = in.data(); p < in.data() + in.size();)
  {
    GlobalId id = 0;
    p = readBytes(p, id);
    p = readBytes(p, into.previousDisplacement[static_cast<std::size_t>(id - lo)]);
    p = readBytes(p, into.previousRotation[static_cast<std::size_t>(id - lo)]);
  }
  return true;
}
} // namespace

void saveCheckpoint(MPI_Comm comm, const MpiDomain* split, Scene& scene, const std::string& path,
                    const CheckpointExtras& extras)
{
  if (split == nullptr)
  {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::string error;
    if (rank == 0)
      try
      {
        talus::dem::saveCheckpoint(scene, path, extras);
      }
      catch (const CheckpointError& e)
      {
        error = e.what();
      }
    agree(comm, error);
    return;
  }
  const MpiDomain& domain = *split;
  const CheckpointExtras shared = extrasOfRankZero(comm, extras);
  // The part this rank writes: its slabs, and what every rank holds alike.
  Scene part;
  part.materials = scene.materials;
  // The energy tracker: each process accumulates its share of the terms (O.energy sums them):
  // the file holds their sums; its per-body memory goes by global id as the bodies do.
  part.energy = scene.energy;
  std::vector<double> terms;
  for (const auto& [name, field] : checkpoint::energyTerms)
    terms.push_back(scene.energy.*field);
  domain.sum(terms);
  for (std::size_t k = 0; const auto& [name, field] : checkpoint::energyTerms)
    part.energy.*field = terms[k++];
  part.energy.grownBy.clear();
  part.periodic = scene.periodic;
  part.cell = scene.cell;
  part.maxOverlapRatio = scene.maxOverlapRatio;
  part.maxEnergyGrowth = scene.maxEnergyGrowth;
  part.dt = scene.dt;
  part.time = scene.time;
  part.iter = scene.iter;
  std::int64_t versions[2] = {scene.bodiesVersion, scene.bodyPropertiesVersion};
  MPI_Allreduce(MPI_IN_PLACE, versions, 2, MPI_INT64_T, MPI_MAX, comm);
  part.bodiesVersion = versions[0];
  part.bodyPropertiesVersion = versions[1];
  part.bodies = bodySlab(comm, domain, scene);
  // The heat fields some body of the scene has a value of.
  std::array<bool, std::size(checkpoint::bodyHeat)> heat = checkpoint::bodyHeatHeld(part.bodies);
  std::array<int, std::size(checkpoint::bodyHeat)> anyHeat{};
  std::copy(heat.begin(), heat.end(), anyHeat.begin());
  MPI_Allreduce(MPI_IN_PLACE, anyHeat.data(), static_cast<int>(anyHeat.size()), MPI_INT, MPI_MAX, comm);
  std::copy(anyHeat.begin(), anyHeat.end(), heat.begin());
  bool withExtra = false;
  contactSlab(comm, domain, scene, part.contacts, withExtra);

  const std::int64_t N = domain.globalCount();
  std::int64_t contacts = static_cast<std::int64_t>(part.contacts.list.size()), before = 0, total = contacts;
  MPI_Exscan(&contacts, &before, 1, MPI_INT64_T, MPI_SUM, comm);
  if (domain.rank() == 0)
    before = 0; // MPI_Exscan leaves rank 0's undefined
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_INT64_T, MPI_SUM, comm);
  checkpoint::Slabs slabs;
  slabs.bodies = {static_cast<hsize_t>(slabStart(domain.rank(), N, domain.ranks())), static_cast<hsize_t>(N)};
  slabs.contacts = {static_cast<hsize_t>(before), static_cast<hsize_t>(total)};
  slabs.contactExtra = {static_cast<hsize_t>(before), withExtra ? static_cast<hsize_t>(total) : 0};
  slabs.energyHistory = energyMemorySlab(comm, domain, scene, part.energy);
  slabs.heat = heat;
  checkpoint::saveCheckpointTogether(comm, part, slabs, path, shared,
                                     [comm](const std::string& error) { agree(comm, error); });
}

CheckpointExtras loadCheckpoint(MPI_Comm comm, Scene& scene, const std::string& path)
{
  std::string error;
  CheckpointExtras extras;
  try
  {
    extras = talus::dem::loadCheckpoint(scene, path);
  }
  catch (const CheckpointError& e)
  {
    error = e.what();
  }
  agree(comm, error);
  // The whole scene is here again; its energy terms are the whole scene's: kept by rank 0, as
  // each process accumulates its share from now on and O.energy sums the shares.
  scene.domain.reset();
  if (int rank = 0; MPI_Comm_rank(comm, &rank) == MPI_SUCCESS && rank != 0)
    for (const auto& [name, field] : checkpoint::energyTerms)
      scene.energy.*field = 0;
  return extras;
}
} // namespace talus::dem::distributed
