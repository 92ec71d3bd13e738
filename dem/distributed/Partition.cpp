#include "dem/distributed/Partition.h"

#include "dem/core/Contacts.h"
#include "dem/distributed/Collective.h"

#include <zoltan.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

namespace talus::dem::distributed
{
namespace
{
constexpr std::array<std::pair<std::string_view, Method>, 2> methods{{{"RCB", Method::RCB}, {"HSFC", Method::HSFC}}};

/// Zoltan ids are ZOLTAN_ID_TYPE words (32 bits in Debian's build): a global id takes as many
/// as it needs, a local row one.
constexpr int gidWords = (sizeof(GlobalId) + sizeof(ZOLTAN_ID_TYPE) - 1) / sizeof(ZOLTAN_ID_TYPE);
static_assert(sizeof(GlobalId) == gidWords * sizeof(ZOLTAN_ID_TYPE));

/// What Zoltan's query functions read: this rank's bodies and weights.
struct Query
{
  const RankBodies* local;
  std::span<const double> weights;
};

int countBodies(void* data, int* err)
{
  *err = ZOLTAN_OK;
  return static_cast<int>(static_cast<const Query*>(data)->local->size());
}

void listBodies(void* data, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int, float* weights, int* err)
{
  const auto& q = *static_cast<const Query*>(data);
  for (std::size_t i = 0; i < q.local->size(); ++i)
  {
    std::memcpy(gids + gidWords * i, &q.local->globalId[i], sizeof(GlobalId));
    lids[i] = static_cast<ZOLTAN_ID_TYPE>(i);
    weights[i] = q.weights.empty() ? 1.0F : static_cast<float>(q.weights[i]);
  }
  *err = ZOLTAN_OK;
}

int dimensions(void*, int* err)
{
  *err = ZOLTAN_OK;
  return 3;
}

void centres(void* data, int, int, int count, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int, double* xyz, int* err)
{
  const auto& pos = static_cast<const Query*>(data)->local->bodies.pos;
  for (int k = 0; k < count; ++k)
    for (int d = 0; d < 3; ++d)
      xyz[3 * k + d] = pos[lids[k]][d];
  *err = ZOLTAN_OK;
}

/// What this rank's arguments have wrong (empty if nothing): checked on every rank, then
/// raised on every rank by throwIfAnyRank.
std::string localError(const RankBodies& local, std::span<const double> weights, const PartitionSettings& settings,
                       int rank)
{
  try
  {
    (void)methodNamed(settings.method);
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  if (!(settings.imbalanceTolerance >= 1.0))
    return "partition: imbalanceTolerance " + std::to_string(settings.imbalanceTolerance)
           + " is below 1 (the ratio of the heaviest rank's weight to the average)";
  if (!(settings.rebalanceThreshold >= 1.0))
    return "partition: rebalanceThreshold " + std::to_string(settings.rebalanceThreshold)
           + " is below 1 (the slowest rank's compute time over the mean above which the ranks partition again; "
             "infinity: never)";
  if (!weights.empty() && weights.size() != local.size())
    return "partition: rank " + std::to_string(rank) + " passed " + std::to_string(weights.size())
           + " weights for " + std::to_string(local.size()) + " bodies";
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (!(weights[i] >= 0.0))
      return "partition: body " + std::to_string(local.globalId[i]) + " has weight " + std::to_string(weights[i])
             + " (weights are costs: zero or positive)";
  if (const std::int64_t bad = firstUndistributable(local); bad >= 0)
  {
    const auto i = static_cast<std::size_t>(bad);
    const Bodies& b = local.bodies;
    const std::string what = b.shape[i] != ShapeKind::Sphere ? std::string("a ") + shapeName(b.shape[i])
                                                             : "a member of a clump";
    return "partition: body " + std::to_string(local.globalId[i]) + " (on rank " + std::to_string(rank) + ") is "
           + what + "; the partition places spheres and clumps only (a clump's members go with it; walls, facets and "
                    "boxes are every rank's)";
  }
  return {};
}

/// Zoltan's process-wide set-up, once, after MPI_Init.
void initialiseZoltan()
{
  static std::once_flag once;
  std::call_once(once, [] {
    float version = 0;
    if (Zoltan_Initialize(0, nullptr, &version) != ZOLTAN_OK)
      throw std::runtime_error("partition: Zoltan_Initialize failed");
  });
}

void check(int code, const char* call)
{
  if (code != ZOLTAN_OK && code != ZOLTAN_WARN)
    throw std::runtime_error(std::string("partition: Zoltan's ") + call + " failed (code " + std::to_string(code) + ")");
}

/// The bounding box of the centres each rank owns once `plan`'s moves are made.
std::vector<Box> ownedBoundingBoxes(MPI_Comm comm, const RankBodies& local, const Plan& plan, int rank, int ranks)
{
  const double inf = std::numeric_limits<double>::infinity();
  // lower corners, then upper corners negated: one MIN reduction gives both
  std::vector<double> corners(6 * static_cast<std::size_t>(ranks), inf);
  std::vector<int> owner(local.size(), rank);
  for (std::size_t k = 0; k < plan.exportRows.size(); ++k)
    owner[static_cast<std::size_t>(plan.exportRows[k])] = plan.exportTo[k];
  for (std::size_t i = 0; i < local.size(); ++i)
    for (int d = 0; d < 3; ++d)
    {
      double* c = corners.data() + 6 * owner[i];
      c[d] = std::min(c[d], local.bodies.pos[i][d]);
      c[3 + d] = std::min(c[3 + d], -local.bodies.pos[i][d]);
    }
  MPI_Allreduce(MPI_IN_PLACE, corners.data(), static_cast<int>(corners.size()), MPI_DOUBLE, MPI_MIN, comm);
  std::vector<Box> boxes(static_cast<std::size_t>(ranks));
  for (std::size_t r = 0; r < boxes.size(); ++r)
  {
    const double* c = corners.data() + 6 * r;
    boxes[r].min = Vec3(c[0], c[1], c[2]);
    boxes[r].max = -Vec3(c[3], c[4], c[5]);
  }
  return boxes;
}
} // namespace

Method methodNamed(std::string_view name)
{
  std::string valid;
  for (const auto& [known, method] : methods)
  {
    if (name == known)
      return method;
    valid += (valid.empty() ? "" : ", ") + std::string(known);
  }
  throw std::invalid_argument("partition method '" + std::string(name) + "' is not one of Zoltan's methods here: "
                              + valid);
}

double distanceToBox(const Vec3& x, const Box& box)
{
  const Vec3 outside = (box.min - x).cwiseMax(x - box.max).cwiseMax(0.0);
  return outside.norm();
}

Plan partition(MPI_Comm comm, const RankBodies& local, std::span<const double> weights,
               const PartitionSettings& settings)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  throwIfAnyRank(comm, localError(local, weights, settings, rank));
  const Method method = methodNamed(settings.method);

  initialiseZoltan();
  Query query{&local, weights};
  Zoltan_Struct* zz = Zoltan_Create(comm);
  if (zz == nullptr)
    throw std::runtime_error("partition: Zoltan_Create failed");
  // Zoltan's structure and lists are released on every way out, errors included.
  struct Lists
  {
    Zoltan_Struct* zz;
    int imports = 0, exports = 0;
    ZOLTAN_ID_PTR importGids = nullptr, importLids = nullptr, exportGids = nullptr, exportLids = nullptr;
    int *importProcs = nullptr, *importParts = nullptr, *exportProcs = nullptr, *exportParts = nullptr;
    ~Lists()
    {
      Zoltan_LB_Free_Part(&importGids, &importLids, &importProcs, &importParts);
      Zoltan_LB_Free_Part(&exportGids, &exportLids, &exportProcs, &exportParts);
      Zoltan_Destroy(&zz);
    }
  } lists{zz};

  const std::string tolerance = std::to_string(settings.imbalanceTolerance);
  const std::string gidEntries = std::to_string(gidWords);
  for (const auto& [key, value] : {std::pair<const char*, const char*>{"DEBUG_LEVEL", "0"},
                                   {"LB_METHOD", settings.method.c_str()},
                                   {"NUM_GID_ENTRIES", gidEntries.c_str()},
                                   {"NUM_LID_ENTRIES", "1"},
                                   {"OBJ_WEIGHT_DIM", "1"},
                                   {"RETURN_LISTS", "ALL"},
                                   {"IMBALANCE_TOL", tolerance.c_str()},
                                   {"KEEP_CUTS", "1"}})
    check(Zoltan_Set_Param(zz, key, value), "Zoltan_Set_Param");
  check(Zoltan_Set_Num_Obj_Fn(zz, countBodies, &query), "Zoltan_Set_Num_Obj_Fn");
  check(Zoltan_Set_Obj_List_Fn(zz, listBodies, &query), "Zoltan_Set_Obj_List_Fn");
  check(Zoltan_Set_Num_Geom_Fn(zz, dimensions, &query), "Zoltan_Set_Num_Geom_Fn");
  check(Zoltan_Set_Geom_Multi_Fn(zz, centres, &query), "Zoltan_Set_Geom_Multi_Fn");

  int changes = 0, gidCount = 0, lidCount = 0;
  check(Zoltan_LB_Partition(zz, &changes, &gidCount, &lidCount, &lists.imports, &lists.importGids, &lists.importLids,
                            &lists.importProcs, &lists.importParts, &lists.exports, &lists.exportGids,
                            &lists.exportLids, &lists.exportProcs, &lists.exportParts),
        "Zoltan_LB_Partition");

  Plan plan;
  std::vector<std::pair<std::int64_t, int>> leaving(static_cast<std::size_t>(lists.exports));
  for (std::size_t k = 0; k < leaving.size(); ++k)
    leaving[k] = {static_cast<std::int64_t>(lists.exportLids[k]), lists.exportProcs[k]};
  std::sort(leaving.begin(), leaving.end());
  for (const auto& [row, to] : leaving)
  {
    plan.exportRows.push_back(row);
    plan.exportTo.push_back(to);
  }
  plan.importIds.resize(static_cast<std::size_t>(lists.imports));
  plan.importFrom.assign(lists.importProcs, lists.importProcs + lists.imports);
  for (std::size_t k = 0; k < plan.importIds.size(); ++k)
    std::memcpy(&plan.importIds[k], lists.importGids + gidWords * k, sizeof(GlobalId));

  if (method == Method::RCB)
  {
    plan.boxes.resize(static_cast<std::size_t>(ranks));
    for (int r = 0; r < ranks; ++r)
    {
      Box& b = plan.boxes[static_cast<std::size_t>(r)];
      int dims = 0;
      check(Zoltan_RCB_Box(zz, r, &dims, &b.min[0], &b.min[1], &b.min[2], &b.max[0], &b.max[1], &b.max[2]),
            "Zoltan_RCB_Box");
    }
  }
  else
    plan.boxes = ownedBoundingBoxes(comm, local, plan, rank, ranks);
  return plan;
}

std::vector<double> contactWeights(const Contacts& contacts, std::size_t bodyCount)
{
  std::vector<double> weights(bodyCount, 1.0);
  const auto indexed = static_cast<std::size_t>(contacts.indexedBodies());
  for (std::size_t b = 0; b < std::min(bodyCount, indexed); ++b)
    weights[b] += static_cast<double>(contacts.start[b + 1] - contacts.start[b]);
  return weights;
}
} // namespace talus::dem::distributed
