#include "dem/distributed/MpiDomain.h"

#include "dem/contact/Collider.h"
#include "dem/core/Scene.h"
#include "dem/distributed/Collective.h"
#include "dem/distributed/Ghosts.h"
#include "dem/distributed/Migration.h"
#include "dem/distributed/RowMemory.h"
#include "dem/distributed/clumps/Units.h"
#include "dem/distributed/periodic/Regions.h"
#include "dem/distributed/slabs/HeldRows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace talus::dem::distributed
{
namespace
{
/// Doubles of a ghost's state sent at every step: position, velocity, angular velocity,
/// orientation, angular momentum (what the contacts and the skin check read of it).
constexpr std::size_t stateDoubles = 16;
constexpr int updateTag = 7301;

/// Copy the state a ghost update carries of body `i` into the stateDoubles at `buffer`
/// (`out`), or from them into the body.
void copyState(Bodies& b, std::size_t i, double* buffer, bool out)
{
  const std::array<std::pair<double*, std::size_t>, 5> fields{{{b.pos[i].data(), 3},
                                                                {b.vel[i].data(), 3},
                                                                {b.angVel[i].data(), 3},
                                                                {b.ori[i].coeffs().data(), 4},
                                                                {b.angMom[i].data(), 3}}};
  for (const auto& [field, count] : fields)
  {
    std::memcpy(out ? buffer : field, out ? field : buffer, count * sizeof(double));
    buffer += count;
  }
}

/// Call f(a_field, b_field) for each per-body array of `a` and the same array of `b`.
template <class F>
void forEachFieldPair(Bodies& a, const Bodies& b, F&& f)
{
  std::vector<const void*> theirs;
  forEachBodyField(b, [&](const auto& field) { theirs.push_back(&field); });
  std::size_t k = 0;
  forEachBodyField(a, [&](auto& field) {
    using Field = std::decay_t<decltype(field)>;
    f(field, *static_cast<const Field*>(theirs[k++]));
  });
}

/// A contact as it travels between ranks: the record, the global ids of its bodies, its richer
/// state (ContactExtra) when the list keeps any.
struct Travelling
{
  std::vector<Contact> records;
  std::vector<ContactExtra> extra;
  std::vector<GlobalId> ids; ///< two per record
};

/// The lowest and highest of a value over the ranks, both from one MIN reduction: the highest
/// is carried negated. Empty (infinite both ways) until a value is added.
struct Extremes
{
  double low = std::numeric_limits<double>::infinity();
  double negatedHigh = std::numeric_limits<double>::infinity();

  void add(double value)
  {
    low = std::min(low, value);
    negatedHigh = std::min(negatedHigh, -value);
  }
  [[nodiscard]] double high() const { return -negatedHigh; }
  /// Whether every rank gave the same value.
  [[nodiscard]] bool alike() const { return low == high(); }
};

/// What the ranks compare before a re-detection, in one MIN reduction of its doubles.
///
/// A body that moved, since the last re-detection, further from the others' common drift than
/// the ghost layer reaches may have met bodies its rank had no copy of (a teleport from Python,
/// a diverged run): an error, not a wrong force. In a periodic cell the motion is measured
/// twice: from where the cell's affine map A = H H_detected^-1 carried each body's position at
/// the last re-detection (the bodies follow it as velGrad deforms the cell, which the
/// collider's skin check takes as no motion), and from that position itself (O.cell.hSize set
/// from a script moves no body); a body is out of reach when it is far by both. The common
/// drift of each is the middle of its extremes.
struct BeforeDetection
{
  std::array<Extremes, 3> followed; ///< per axis, the owned bodies' displacements from A x_detected
  std::array<Extremes, 3> moved;    ///< per axis, their displacements from x_detected
  /// What each rank erased (count, sum of the ids): the ranks must agree.
  Extremes erasedCount, erasedSum;
  /// The periodic cell's hSize, which every rank updates alike (the same velocity gradient from
  /// the same reductions): a rank whose cell differs would compute other contacts.
  std::array<Extremes, 9> cell;
  /// The spheres' radii: spheres grown since (growParticles, a TriaxialStressController's
  /// compaction) reach further, and the next ghost layer must reach as far.
  Extremes radius;
  /// Whether a rank holds a growth its contacts have not seen yet (EnergyTracker::grownBy): its
  /// bodies carry it to the ranks holding them next (shareMemory).
  Extremes growthPending;

  /// The doubles the reduction takes.
  std::span<double> values() { return {reinterpret_cast<double*>(this), sizeof(BeforeDetection) / sizeof(double)}; }
  /// The middle of each axis's extremes: the common drift.
  static Vec3 middles(const std::array<Extremes, 3>& axes)
  {
    return 0.5 * (Vec3(axes[0].low, axes[1].low, axes[2].low)
                  - Vec3(axes[0].negatedHigh, axes[1].negatedHigh, axes[2].negatedHigh));
  }
};
static_assert(std::is_standard_layout_v<BeforeDetection> && sizeof(BeforeDetection) == 38 * sizeof(double),
              "BeforeDetection is reduced as an array of doubles");

/// Zoltan's partition of `mine` in the space of `regions` (a periodic cell's reduced
/// coordinates: the bodies handed to Zoltan at those coordinates; an open scene's as they are).
Plan partitionIn(MPI_Comm comm, const Regions& regions, bool periodic, const RankBodies& mine,
                 std::span<const double> weights, const PartitionSettings& settings)
{
  if (!periodic)
    return partition(comm, mine, weights, settings);
  RankBodies located = mine;
  for (Vec3& x : located.bodies.pos)
    x = regions.coordinates(x);
  return partition(comm, located, weights, settings);
}

/// Whether the bodies' positions and radii are the same bits on every rank of `comm` (collective):
/// a hash of them, its minimum and maximum over the ranks compared.
bool sameOnEveryRank(MPI_Comm comm, const Bodies& b)
{
  std::uint64_t hash = 14695981039346656037ULL; // FNV-1a over the bytes
  auto add = [&](const void* data, std::size_t bytes) {
    for (std::size_t k = 0; k < bytes; ++k)
      hash = (hash ^ static_cast<const unsigned char*>(data)[k]) * 1099511628211ULL;
  };
  add(b.pos.data(), b.pos.size() * sizeof(Vec3));
  add(b.radius.data(), b.radius.size() * sizeof(double));
  std::uint64_t extremes[2] = {hash, ~hash}; // the minimum of ~hash is ~(the maximum of hash)
  MPI_Allreduce(MPI_IN_PLACE, extremes, 2, MPI_UINT64_T, MPI_MIN, comm);
  return extremes[0] == ~extremes[1];
}

/// The CPU seconds of this process so far (a rank waiting in MPI polls: its CPU time, unlike its
/// wall time, is what the wait costs the machine).
double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

} // namespace

MpiDomain::MpiDomain(MPI_Comm comm, Scene& scene, const PartitionSettings& settings, const HeldRows* held)
    : comm_(comm), settings_(settings), method_(Method::RCB), balance_(settings.rebalanceThreshold)
{
  const double start = MPI_Wtime();
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
  const Bodies& b = scene.bodies;
  std::vector<std::int64_t> spheres;
  double rmin = std::numeric_limits<double>::infinity(), rmax = 0;
  std::string error;
  const auto idOf = [held](std::size_t row) { return held ? held->globalId[row] : static_cast<GlobalId>(row); };
  for (std::size_t i = 0; i < b.size() && error.empty(); ++i)
  {
    if (!b.alive[i])
      erased_.push_back(idOf(i));
    else if (b.shape[i] == ShapeKind::Sphere || b.shape[i] == ShapeKind::Clump)
    {
      // What Zoltan places: free spheres and clumps (their members go with them).
      if (b.clumpId[i] < 0)
        spheres.push_back(static_cast<std::int64_t>(i));
      if (b.shape[i] == ShapeKind::Sphere)
      {
        rmin = std::min(rmin, b.radius[i]);
        rmax = std::max(rmax, b.radius[i]);
      }
      if (const std::size_t clump = b.clumpId[i] >= 0 ? static_cast<std::size_t>(b.clumpId[i]) : i;
          b.shape[clump] == ShapeKind::Clump)
        clumped_.push_back({idOf(i), idOf(clump), static_cast<std::size_t>(b.shapeIndex[clump])});
    }
    else if (b.shape[i] != ShapeKind::Wall && b.shape[i] != ShapeKind::Facet && b.shape[i] != ShapeKind::Box)
      error = "body " + std::to_string(idOf(i)) + " is a " + shapeName(b.shape[i])
              + (b.clumpId[i] >= 0 ? " member of a clump" : "")
              + ": the distributed DEM takes spheres, clumps of spheres, walls, facets and boxes only so far (no "
                "blocks, particles); run it in one process";
    else if (b.dynamic[i])
      error = "body " + std::to_string(idOf(i)) + " is a " + shapeName(b.shape[i])
              + " moved by forces (dynamic): under mpirun every process holds the walls, facets and boxes and "
                "moves them alike by their velocities (set by engines); make it fixed (dynamic=False) or run it "
                "in one process";
  }
  hasClumps_ = !clumped_.empty();
  if (const std::int64_t count = sceneSpheres(comm_, spheres, held); error.empty() && count < ranks_)
    error = "the scene has " + std::to_string(count) + " spheres for " + std::to_string(ranks_)
            + " processes: each process needs at least one; run it on fewer (mpirun -np)";
  // Every process built the scene from the script: the same bodies, or the split would mix
  // several scenes (random numbers the script draws without a seed differ on each).
  if (!held && !sameOnEveryRank(comm_, b) && error.empty())
    error = "the scene differs between the processes (its bodies' positions or sizes): under mpirun every process "
            "builds it from the script, which must make the same scene on each; random numbers it draws need a "
            "seed (random.seed(1)), a TriaxialTest radiusMean > 0 with its seed (makeCloud without a seed draws "
            "one cloud for every process)";
  const Collider* collider = nullptr;
  for (const auto& engine : scene.engines)
    if (const auto* c = dynamic_cast<const Collider*>(engine.get()); c && !engine->dead)
      collider = c;
  if (error.empty() && collider == nullptr)
    error = "the scene has no collider (InsertionSortCollider): the distributed DEM needs one";
  try
  {
    method_ = methodNamed(settings_.method);
  }
  catch (const std::invalid_argument& e)
  {
    if (error.empty())
      error = e.what();
  }
  raiseOnEveryRank(comm_, error);
  verletDist_ = collider->verletDist;
  ghostDistance_ = ghostLayer(rmin, rmax);

  // Rank r offers Zoltan the r-th slice of the spheres every rank holds, and its own slab of a
  // packing read in slabs.
  RankBodies whole{std::move(scene.bodies), {}};
  whole.globalId.resize(whole.bodies.size());
  std::iota(whole.globalId.begin(), whole.globalId.end(), GlobalId{0});
  if (held)
    whole.globalId = held->globalId;
  globalCount_ = held ? held->count : static_cast<std::int64_t>(whole.bodies.size());
  globalId_ = whole.globalId;
  std::vector<std::int64_t> slice = offeredRows(spheres, held, rank_, ranks_);
  // By global id (in a scene built whole, its rows; the clumps of a scene read in slabs are of the
  // bodies every rank holds).
  for (const ClumpShape& clump : whole.bodies.clumps)
  {
    clumpMembers_.emplace_back();
    for (const BodyId m : clump.members)
      clumpMembers_.back().push_back(idOf(static_cast<std::size_t>(m)));
  }
  for (std::size_t k = 0, heads = slice.size(); k < heads; ++k) // a clump's members go with it
    if (const auto i = static_cast<std::size_t>(slice[k]); whole.bodies.shape[i] == ShapeKind::Clump)
    {
      const std::vector<BodyId>& members = whole.bodies.clumps[static_cast<std::size_t>(whole.bodies.shapeIndex[i])].members;
      slice.insert(slice.end(), members.begin(), members.end());
    }
  RankBodies mine;
  std::vector<std::byte> rows;
  packRows(whole, slice, rows);
  unpackRows(rows, mine);
  for (BodyId& clump : mine.bodies.clumpId) // while rows travel, a member names its clump by global id
    if (clump >= 0)
      clump = static_cast<BodyId>(idOf(static_cast<std::size_t>(clump)));
  if (scene.periodic)
    regions_ = Regions(scene.cell);
  const Plan plan = placeUnits(scene, mine, {}, true);
  migrate(comm_, mine, plan);

  // Contacts made before the domain (steps run in one process): every rank has them all.
  Travelling contacts;
  for (std::size_t k = 0; k < scene.contacts.list.size(); ++k)
  {
    const Contact& c = scene.contacts.list[k];
    contacts.records.push_back(c);
    if (!scene.contacts.extra.empty())
      contacts.extra.push_back(scene.contacts.extra[k]);
    contacts.ids.push_back(c.id1);
    contacts.ids.push_back(c.id2);
  }
  scene.bodies = std::move(whole.bodies);
  replicated_.assign(scene.bodies.size(), 0);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    replicated_[i] = scene.bodies.alive[i]
                     && (scene.bodies.shape[i] == ShapeKind::Wall || scene.bodies.shape[i] == ShapeKind::Facet
                         || scene.bodies.shape[i] == ShapeKind::Box);
  assemble(scene, mine, contacts.records, contacts.extra, contacts.ids);
  // Of the whole scene every rank built, only this rank's rows are left: its memory goes back.
  forEachBodyField(scene.bodies, [](auto& field) { field.shrink_to_fit(); });
  scene.contacts.list.shrink_to_fit();
  scene.contacts.extra.shrink_to_fit();
#ifdef __GLIBC__
  // The split's medium buffers (rows packed, sent and unpacked, Zoltan's lists, the whole
  // scene's rows) are freed into the heap, where the allocator keeps them, while the first
  // detection's large lists are mapped anew beside them: handed back, they no longer add to the
  // process's peak (a tenth of it on each of two processes holding a million spheres).
  malloc_trim(0);
#endif
  traffic_.splitSeconds = MPI_Wtime() - start;
  balance_.begin(cpuSeconds(), waitedCpu_, scene.iter);
}

double MpiDomain::computeSeconds() const
{
  return balance_.stats().computeSeconds + balance_.openSeconds(cpuSeconds(), waitedCpu_);
}

std::size_t MpiDomain::ownedBodies(const Scene& scene) const { return scene.bodies.size(); }

double MpiDomain::ghostLayer(double rmin, double rmax) const
{
  const double skin = verletDist_ >= 0 ? verletDist_ : -verletDist_ * rmin; // as the collider takes it
  return 2 * rmax + skin;
}

bool MpiDomain::computesPair(std::size_t row1, std::size_t row2) const
{
  if (replicated_[row1] || replicated_[row2])
    return owned_[row1] && owned_[row2];
  return owned_[row1] || owned_[row2];
}

std::int64_t MpiDomain::rowHeld(GlobalId id) const
{
  // Rows are in ascending global id: no table over the whole scene.
  const auto at = std::lower_bound(globalId_.begin(), globalId_.end(), id);
  return at != globalId_.end() && *at == id ? at - globalId_.begin() : -1;
}

std::int64_t MpiDomain::rowOf(GlobalId id) const
{
  if (id < 0 || id >= globalCount_ || std::binary_search(erased_.begin(), erased_.end(), id))
    return noBody;
  const std::int64_t row = rowHeld(id);
  return row >= 0 ? row : elsewhere;
}

bool MpiDomain::erase(Scene& scene, GlobalId id, bool eraseClumpMembers)
{
  if (id < 0 || id >= globalCount_)
    throw std::out_of_range("no body with id " + std::to_string(id) + " (ids run from 0 to "
                            + std::to_string(globalCount_ - 1) + ")");
  if (std::binary_search(erased_.begin(), erased_.end(), id))
    return false;
  // Every rank keeps the clumps' member lists by global id and changes them alike, whether it
  // holds the clump or not, as Scene::erase changes them where it is held (Yade's rules: a
  // clump's members are freed, or erased with it; a member leaves its clump, which goes with its
  // last member).
  std::vector<GlobalId> gone{id};
  auto unclump = [this](GlobalId body) {
    clumped_.erase(std::lower_bound(clumped_.begin(), clumped_.end(), Clumped{body, 0, 0}));
  };
  const auto entry = std::lower_bound(clumped_.begin(), clumped_.end(), Clumped{id, 0, 0});
  if (entry != clumped_.end() && entry->id == id)
  {
    const Clumped c = *entry;
    std::vector<GlobalId>& members = clumpMembers_[c.shape];
    if (c.clump == id)
    {
      if (eraseClumpMembers)
        gone.insert(gone.end(), members.begin(), members.end());
      for (const GlobalId m : members)
        unclump(m);
      members.clear();
    }
    else
    {
      const auto at = std::find(members.begin(), members.end(), id);
      if (rowHeld(c.clump) < 0) // where the clump is held, Scene::erase takes out the member's placement
      {
        ClumpShape& shape = scene.bodies.clumps[c.shape];
        const auto k = at - members.begin();
        if (static_cast<std::size_t>(k) < shape.relPos.size())
        {
          shape.relPos.erase(shape.relPos.begin() + k);
          shape.relOri.erase(shape.relOri.begin() + k);
        }
      }
      members.erase(at);
      if (members.empty())
      {
        gone.push_back(c.clump);
        unclump(c.clump);
      }
    }
    unclump(id);
  }
  for (const GlobalId g : gone)
    erased_.insert(std::lower_bound(erased_.begin(), erased_.end(), g), g);
  // Until the next re-detection drops its rows, a copy here (owned, replicated or a ghost) is
  // erased as in a whole scene: its contacts go at once (a clump's members are held with it).
  if (const std::int64_t row = rowHeld(id); row >= 0 && scene.bodies.alive[static_cast<std::size_t>(row)])
    scene.erase(static_cast<BodyId>(row), eraseClumpMembers);
  return true;
}

int MpiDomain::regionOf(const Vec3& position) const
{
  if (!position.allFinite())
    return -1;
  const Vec3 x = regions_.coordinates(position);
  for (std::size_t r = 0; r < boxes_.size(); ++r)
    if ((x.array() >= boxes_[r].min.array()).all() && (x.array() <= boxes_[r].max.array()).all())
      return static_cast<int>(r);
  return -1;
}

void MpiDomain::sum(std::span<double> values) const
{
  const double start = MPI_Wtime(), cpu = cpuSeconds();
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, comm_);
  traffic_.reductionSeconds += MPI_Wtime() - start;
  traffic_.waitCpuSeconds += cpuSeconds() - cpu;
  waitedCpu_ += cpuSeconds() - cpu;
}

double MpiDomain::min(double value) const
{
  min(std::span<double>(&value, 1));
  return value;
}

void MpiDomain::min(std::span<double> values) const
{
  const double start = MPI_Wtime(), cpu = cpuSeconds();
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MIN, comm_);
  traffic_.reductionSeconds += MPI_Wtime() - start;
  traffic_.waitCpuSeconds += cpuSeconds() - cpu;
  waitedCpu_ += cpuSeconds() - cpu;
}

void MpiDomain::beforeDetection(Scene& scene)
{
  const double start = MPI_Wtime(), cpuAtStart = cpuSeconds(), waitedAtStart = waitedCpu_;
  const Bodies& b = scene.bodies;
  const std::size_t n = b.size();
  BeforeDetection check;
  check.erasedCount.add(static_cast<double>(erased_.size()));
  check.erasedSum.add(static_cast<double>(std::accumulate(erased_.begin(), erased_.end(), GlobalId{0})));
  for (std::size_t k = 0; k < check.cell.size(); ++k)
    check.cell[k].add(scene.cell.hSize.data()[k]);
  const Mat3 affine = scene.periodic ? Mat3(scene.cell.hSize * detectedCell_.inverse()) : Mat3::Identity();
  for (std::size_t i = 0; i < n; ++i)
    if (owned_[i] && !replicated_[i] && b.alive[i])
    {
      const Vec3 followed = b.pos[i] - affine * detectedAt_[i], moved = b.pos[i] - detectedAt_[i];
      for (int d = 0; d < 3; ++d)
      {
        check.followed[static_cast<std::size_t>(d)].add(followed[d]);
        check.moved[static_cast<std::size_t>(d)].add(moved[d]);
      }
      if (b.shape[i] == ShapeKind::Sphere)
        check.radius.add(b.radius[i]);
    }
  check.growthPending.add(scene.energy.grownBy.empty() ? 0 : 1);
  min(check.values());
  const Vec3 common = BeforeDetection::middles(check.followed), still = BeforeDetection::middles(check.moved);
  std::string error;
  if (!check.erasedCount.alike() || !check.erasedSum.alike())
    error = "step " + std::to_string(scene.iter) + ": the processes erased different bodies (" + std::to_string(erased_.size())
            + " on process " + std::to_string(rank_) + "; from " + std::to_string(static_cast<std::int64_t>(check.erasedCount.low))
            + " to " + std::to_string(static_cast<std::int64_t>(check.erasedCount.high()))
            + " over the processes): under mpirun O.bodies.erase must be called on every process with the same ids "
              "(from code every process runs alike, deciding from global values such as "
              "talus.dem.distributed.positions())";
  for (std::size_t k = 0; k < check.cell.size() && error.empty(); ++k)
    if (!check.cell[k].alike())
      error = "step " + std::to_string(scene.iter)
              + ": the periodic cell (O.cell.hSize) differs between the processes: under mpirun every process must "
                "change the cell alike (from code every process runs alike, deciding from global values)";
  for (std::size_t i = 0; i < n && error.empty(); ++i)
  {
    if (!owned_[i] || replicated_[i] || !b.alive[i])
      continue;
    const double off = std::min((b.pos[i] - affine * detectedAt_[i] - common).norm(),
                                (b.pos[i] - detectedAt_[i] - still).norm());
    if (!(off <= ghostDistance_))
      error = "step " + std::to_string(scene.iter) + ": body " + std::to_string(globalId_[i]) + " moved "
              + std::to_string(off) + " apart from the others since the last re-detection, beyond the ghost layer ("
              + std::to_string(ghostDistance_)
              + ": twice the largest radius plus the collider's skin), or to a position that is not finite: "
                "contacts with bodies of other processes may have been missed (a body moved from Python, or a "
                "diverged run)";
  }
  raiseOnEveryRank(comm_, error);
  ghostDistance_ = ghostLayer(check.radius.low, check.radius.high()); // the layer of the ghosts taken now

  // This rank's spheres, and where each goes (in the cell as it is now).
  if (scene.periodic)
    regions_ = Regions(scene.cell);
  std::vector<std::int64_t> mineRows; // erased bodies are left behind
  for (std::size_t i = 0; i < n; ++i)
    if (owned_[i] && !replicated_[i] && b.alive[i])
      mineRows.push_back(static_cast<std::int64_t>(i));
  // The load since the last re-detection; partition again, weighted by the measured costs, when
  // the ranks' compute times differ too much.
  const bool rebalance = balance_.measure(comm_, cpuAtStart, waitedAtStart, scene.iter,
                                          static_cast<std::int64_t>(mineRows.size()),
                                          static_cast<std::int64_t>(scene.contacts.list.size()));
  RankBodies current{std::move(scene.bodies), globalId_};
  RankBodies mine;
  std::vector<std::byte> packed;
  packRows(current, mineRows, packed);
  unpackRows(packed, mine);
  scene.bodies = std::move(current.bodies);
  for (BodyId& clump : mine.bodies.clumpId) // while rows travel, a member names its clump by global id
    if (clump >= 0)
      clump = static_cast<BodyId>(globalId_[static_cast<std::size_t>(clump)]);
  const bool partitionAgain = method_ != Method::RCB || rebalance;
  // The energy memory of bodies that may land where no copy of them was goes with them.
  const bool shareMemoryAfter = check.growthPending.high() > 0 || (partitionAgain && scene.energy.enabled);
  const std::vector<Remembered> memory =
      shareMemoryAfter ? ownMemory(scene.energy, scene.bodies, globalId_, mineRows, partitionAgain) : std::vector<Remembered>{};
  const Plan plan = placeUnits(scene, mine, partitionAgain ? balance_.weights(scene.contacts, mineRows, replicated_)
                                                           : std::vector<double>{},
                               partitionAgain);

  // Contacts: each rank keeps its own, and sends each contact of a body leaving it to the
  // body's new rank, which may not have held it (both ranks computing a contact hold it).
  std::vector<int> leavesTo(n, -1);
  for (std::size_t k = 0; k < plan.exportRows.size(); ++k)
    leavesTo[static_cast<std::size_t>(mineRows[static_cast<std::size_t>(plan.exportRows[k])])] = plan.exportTo[k];
  const ContactList& list = scene.contacts.list;
  const bool withExtra = !scene.contacts.extra.empty();
  std::vector<std::vector<std::byte>> out(static_cast<std::size_t>(ranks_));
  Travelling contacts;
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    const Contact& c = list[k];
    const GlobalId g1 = globalId_[static_cast<std::size_t>(c.id1)], g2 = globalId_[static_cast<std::size_t>(c.id2)];
    contacts.records.push_back(c);
    if (withExtra)
      contacts.extra.push_back(scene.contacts.extra[k]);
    contacts.ids.push_back(g1);
    contacts.ids.push_back(g2);
    const int to1 = leavesTo[static_cast<std::size_t>(c.id1)], to2 = leavesTo[static_cast<std::size_t>(c.id2)];
    for (const int to : {to1, to2 != to1 ? to2 : -1})
      if (to >= 0)
      {
        std::vector<std::byte>& o = out[static_cast<std::size_t>(to)];
        ++traffic_.migratedContacts;
        appendBytes(o, c);
        appendBytes(o, g1);
        appendBytes(o, g2);
        if (withExtra)
          appendBytes(o, scene.contacts.extra[k]);
      }
  }
  std::int64_t sent = 0;
  for (const auto& o : out)
    sent += static_cast<std::int64_t>(o.size());
  const std::vector<std::byte> in = sendBytes(comm_, out);
  for (const std::byte* p = in.data(); p < in.data() + in.size();)
  {
    Contact c;
    GlobalId g1 = 0, g2 = 0;
    p = readBytes(readBytes(readBytes(p, c), g1), g2);
    contacts.records.push_back(c);
    contacts.ids.push_back(g1);
    contacts.ids.push_back(g2);
    if (withExtra)
    {
      ContactExtra x;
      p = readBytes(p, x);
      contacts.extra.push_back(x);
    }
  }

  migrate(comm_, mine, plan);
  traffic_.rebuilds += 1;
  traffic_.migratedBodies += static_cast<std::int64_t>(plan.exportRows.size());
  traffic_.rebuildBytes += sent + static_cast<std::int64_t>(plan.exportRows.size() * rowBytes());
  assemble(scene, mine, contacts.records, contacts.extra, contacts.ids);
  if (shareMemoryAfter)
    shareMemory(comm_, scene.energy, memory, globalId_, replicated_);
  traffic_.rebuildSeconds += MPI_Wtime() - start;
  balance_.begin(cpuSeconds(), waitedCpu_, scene.iter);
}

Plan MpiDomain::placeUnits(const Scene& scene, const RankBodies& mine, std::span<const double> rowWeights,
                           bool partitionAgain)
{
  const Units units = unitsOf(mine);
  RankBodies heads;
  if (hasClumps_)
    heads = unitHeads(mine, units);
  const RankBodies& placed = hasClumps_ ? heads : mine; // without clumps, unit k is row k
  Plan plan;
  if (!partitionAgain) // RCB's boxes stay: a unit whose head left its rank's box goes to the box holding it
  {
    for (std::size_t k = 0; k < placed.size(); ++k)
      if (const int to = regionOf(placed.bodies.pos[k]); to != rank_)
      {
        plan.exportRows.push_back(static_cast<std::int64_t>(k));
        plan.exportTo.push_back(to);
      }
    plan.boxes = boxes_;
  }
  else
  {
    plan = partitionIn(comm_, regions_, scene.periodic, placed, unitWeights(units, rowWeights), settings_);
    boxes_ = plan.boxes;
  }
  return unitPlanRows(comm_, mine, units, plan);
}

void MpiDomain::assemble(Scene& scene, RankBodies& mine, std::vector<Contact>& contacts,
                         std::vector<ContactExtra>& extra, std::vector<GlobalId>& contactIds)
{
  // In a periodic cell a ghost keeps its owner's unwrapped position: the collider finds the
  // image through which it touches, and the contact's cellDist, as in the serial scene.
  // A clump is a ghost whole wherever one of its members reaches (its members stick out of its
  // rank's box: the regions are grown to hold them).
  // In a periodic cell a member lies beside its clump, in the clump's image of the cell.
  const Units units = hasClumps_ ? unitsOf(mine) : Units{};
  std::vector<Box> reach = boxes_;
  if (hasClumps_)
  {
    std::vector<Vec3> where(mine.size());
    for (std::size_t i = 0; i < mine.size(); ++i)
      where[i] = regions_.coordinatesBeside(
          mine.bodies.pos[i], mine.bodies.pos[static_cast<std::size_t>(units.head[static_cast<std::size_t>(units.unitOf[i])])]);
    for (Box& box : reach)
      box = regions_.withinCell(box);
    reach = reachingBoxes(comm_, reach, where);
  }
  Ghosts ghosts = exchangeGhosts(
      comm_, mine, reach, [this](const Vec3& x, const Box& box) { return regions_.reaches(x, box, ghostDistance_); },
      units.unitOf);
  traffic_.rebuildBytes += static_cast<std::int64_t>(ghosts.sentRows.size() * rowBytes());

  // The pool of rows: the walls, this rank's spheres, the ghosts; then in global-id order.
  RankBodies pool;
  {
    std::vector<std::int64_t> wallRows;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (replicated_[i] && scene.bodies.alive[i])
        wallRows.push_back(static_cast<std::int64_t>(i));
    RankBodies current{std::move(scene.bodies), globalId_};
    std::vector<std::byte> packed;
    packRows(current, wallRows, packed);
    scene.bodies = std::move(current.bodies);
    unpackRows(packed, pool);
  }
  const std::size_t walls = pool.size();
  for (const RankBodies* part : {&mine, &ghosts.copies})
  {
    std::vector<std::int64_t> all(part->size());
    std::iota(all.begin(), all.end(), std::int64_t{0});
    std::vector<std::byte> packed;
    packRows(*part, all, packed);
    unpackRows(packed, pool);
  }
  const std::size_t n = pool.size(), ownedEnd = walls + mine.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) { return pool.globalId[a] < pool.globalId[c]; });
  // The per-body arrays of the scene take the pool's rows in that order; its shape tables
  // (walls, ...) stay.
  forEachFieldPair(scene.bodies, pool.bodies, [&](auto& field, const auto& from) {
    field.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      field[k] = from[order[k]];
  });
  const std::vector<GlobalId> before = globalId_;
  globalId_.resize(n);
  owned_.resize(n);
  replicated_.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    globalId_[k] = pool.globalId[order[k]];
    owned_[k] = order[k] < ownedEnd;
    replicated_[k] = order[k] < walls;
  }
  followRows(scene.energy, before, globalId_);
  if (hasClumps_)
    linkClumps(scene.bodies, globalId_, clumpMembers_);

  // Ghost updates: the rows sent to each rank, the rows each rank's updates land in.
  auto rowOfId = [&](GlobalId id) { return rowHeld(id); };
  sendRows_.resize(ghosts.sentRows.size());
  for (std::size_t k = 0; k < sendRows_.size(); ++k)
    sendRows_[k] = rowOfId(mine.globalId[static_cast<std::size_t>(ghosts.sentRows[k])]);
  sendStart_ = ghosts.sentStart;
  recvStart_.assign(static_cast<std::size_t>(ranks_) + 1, 0);
  for (const int owner : ghosts.owner)
    ++recvStart_[static_cast<std::size_t>(owner) + 1];
  for (std::size_t r = 0; r < static_cast<std::size_t>(ranks_); ++r)
    recvStart_[r + 1] += recvStart_[r];
  recvRows_.resize(ghosts.copies.size());
  for (std::size_t k = 0; k < recvRows_.size(); ++k)
    recvRows_[k] = rowOfId(ghosts.copies.globalId[k]);

  // The contacts this rank computes, in the collider's order (by rows, which follow global ids),
  // each once.
  std::vector<std::size_t> keep;
  for (std::size_t k = 0; k < contacts.size(); ++k)
  {
    const std::int64_t r1 = rowOfId(contactIds[2 * k]), r2 = rowOfId(contactIds[2 * k + 1]);
    if (r1 < 0 || r2 < 0 || !computesPair(static_cast<std::size_t>(r1), static_cast<std::size_t>(r2)))
      continue;
    contacts[k].id1 = static_cast<BodyId>(r1);
    contacts[k].id2 = static_cast<BodyId>(r2);
    keep.push_back(k);
  }
  auto pairOf = [&](std::size_t k) { return std::pair(contacts[k].id1, contacts[k].id2); };
  std::stable_sort(keep.begin(), keep.end(), [&](std::size_t a, std::size_t c) { return pairOf(a) < pairOf(c); });
  keep.erase(std::unique(keep.begin(), keep.end(), [&](std::size_t a, std::size_t c) { return pairOf(a) == pairOf(c); }),
             keep.end());
  Contacts& list = scene.contacts;
  list.list.clear();
  list.extra.clear();
  for (const std::size_t k : keep)
  {
    list.list.push_back(contacts[k]);
    if (!extra.empty())
      list.extra.push_back(extra[k]);
  }
  list.index(n);

  detectedAt_ = scene.bodies.pos;
  detectedCell_ = scene.cell.hSize;
  sendBuffer_.resize(sendRows_.size() * stateDoubles);
  recvBuffer_.resize(recvRows_.size() * stateDoubles);
  // The rows changed: what engines cached per row (inverse masses, the collider's references)
  // is stale.
  ++scene.bodiesVersion;
  ++scene.bodyPropertiesVersion;
}

void MpiDomain::afterIntegration(Scene& scene)
{
  const double start = MPI_Wtime();
  Bodies& b = scene.bodies;
  std::vector<MPI_Request> requests;
  const auto P = static_cast<std::size_t>(ranks_);
  for (std::size_t r = 0; r < P; ++r)
    if (const std::int64_t count = recvStart_[r + 1] - recvStart_[r]; count > 0)
    {
      requests.emplace_back();
      MPI_Irecv(recvBuffer_.data() + static_cast<std::size_t>(recvStart_[r]) * stateDoubles,
                static_cast<int>(static_cast<std::size_t>(count) * stateDoubles), MPI_DOUBLE, static_cast<int>(r),
                updateTag, comm_, &requests.back());
    }
  for (std::size_t k = 0; k < sendRows_.size(); ++k)
    copyState(b, static_cast<std::size_t>(sendRows_[k]), sendBuffer_.data() + k * stateDoubles, true);
  for (std::size_t r = 0; r < P; ++r)
    if (const std::int64_t count = sendStart_[r + 1] - sendStart_[r]; count > 0)
    {
      requests.emplace_back();
      MPI_Isend(sendBuffer_.data() + static_cast<std::size_t>(sendStart_[r]) * stateDoubles,
                static_cast<int>(static_cast<std::size_t>(count) * stateDoubles), MPI_DOUBLE, static_cast<int>(r),
                updateTag, comm_, &requests.back());
      ++traffic_.updateMessages;
      traffic_.updateBytes += count * static_cast<std::int64_t>(stateDoubles * sizeof(double));
    }
  const double cpu = cpuSeconds();
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  traffic_.waitCpuSeconds += cpuSeconds() - cpu;
  waitedCpu_ += cpuSeconds() - cpu;
  for (std::size_t k = 0; k < recvRows_.size(); ++k)
    copyState(b, static_cast<std::size_t>(recvRows_[k]), recvBuffer_.data() + k * stateDoubles, false);
  ++traffic_.updates;
  traffic_.updateSeconds += MPI_Wtime() - start;
}
} // namespace talus::dem::distributed
