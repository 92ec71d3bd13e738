#include "dem/distributed/clumps/Units.h"

#include "dem/distributed/Collective.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace talus::dem::distributed
{
Units unitsOf(const RankBodies& local)
{
  const Bodies& b = local.bodies;
  const std::size_t n = local.size();
  Units units;
  units.unitOf.assign(n, -1);
  // The heads: every row not a member (free spheres and clump bodies), ascending.
  std::vector<std::pair<GlobalId, std::int64_t>> headOfId; // (head's global id, unit), to find a member's clump
  for (std::size_t i = 0; i < n; ++i)
    if (b.clumpId[i] < 0)
    {
      units.unitOf[i] = static_cast<std::int64_t>(units.head.size());
      headOfId.emplace_back(local.globalId[i], units.unitOf[i]);
      units.head.push_back(static_cast<std::int64_t>(i));
    }
  if (units.size() < n) // members to find their clumps for (a scene without clumps needs no search)
    std::sort(headOfId.begin(), headOfId.end());
  units.start.assign(units.size() + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (b.clumpId[i] >= 0)
    {
      const auto at = std::lower_bound(headOfId.begin(), headOfId.end(), std::pair(GlobalId{b.clumpId[i]}, std::int64_t{-1}));
      if (at == headOfId.end() || at->first != b.clumpId[i])
        throw std::invalid_argument("unitsOf: body " + std::to_string(local.globalId[i]) + " is a member of clump "
                                    + std::to_string(b.clumpId[i]) + ", which is not held here");
      units.unitOf[i] = at->second;
    }
    ++units.start[static_cast<std::size_t>(units.unitOf[i]) + 1];
  }
  for (std::size_t u = 0; u < units.size(); ++u)
    units.start[u + 1] += units.start[u];
  // Each unit's rows ascending: rows taken in order, each to the next free slot of its unit.
  units.rows.resize(n);
  std::vector<std::int64_t> next(units.start.begin(), units.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    units.rows[static_cast<std::size_t>(next[static_cast<std::size_t>(units.unitOf[i])]++)] = static_cast<std::int64_t>(i);
  return units;
}

RankBodies unitHeads(const RankBodies& local, const Units& units)
{
  std::vector<std::byte> packed;
  packRows(local, units.head, packed);
  RankBodies heads;
  unpackRows(packed, heads);
  return heads;
}

std::vector<double> unitWeights(const Units& units, std::span<const double> rowWeights)
{
  std::vector<double> weights(units.size(), 0.0);
  for (std::size_t u = 0; u < units.size(); ++u)
    for (std::int64_t k = units.start[u]; k < units.start[u + 1]; ++k)
      weights[u] += rowWeights.empty() ? 1.0 : rowWeights[static_cast<std::size_t>(units.rows[static_cast<std::size_t>(k)])];
  return weights;
}

Plan unitPlanRows(MPI_Comm comm, const RankBodies& local, const Units& units, const Plan& unitPlan)
{
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<std::pair<std::int64_t, int>> leaving;
  for (std::size_t k = 0; k < unitPlan.exportRows.size(); ++k)
  {
    const auto u = static_cast<std::size_t>(unitPlan.exportRows[k]);
    for (std::int64_t j = units.start[u]; j < units.start[u + 1]; ++j)
      leaving.emplace_back(units.rows[static_cast<std::size_t>(j)], unitPlan.exportTo[k]);
  }
  std::sort(leaving.begin(), leaving.end());
  Plan plan;
  plan.boxes = unitPlan.boxes;
  std::vector<std::vector<std::byte>> out(static_cast<std::size_t>(ranks));
  for (const auto& [row, to] : leaving)
  {
    plan.exportRows.push_back(row);
    plan.exportTo.push_back(to);
    appendBytes(out[static_cast<std::size_t>(to)], local.globalId[static_cast<std::size_t>(row)]);
  }
  // What arrives here: every rank's leavers for this rank (their ids).
  const std::vector<std::byte> in = sendBytes(comm, out);
  plan.importIds.resize(in.size() / sizeof(GlobalId));
  for (std::size_t k = 0; k < plan.importIds.size(); ++k)
    (void)readBytes(in.data() + k * sizeof(GlobalId), plan.importIds[k]);
  return plan;
}

std::vector<Box> reachingBoxes(MPI_Comm comm, std::span<const Box> boxes, std::span<const Vec3> where)
{
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // lower corners, then upper corners negated: one MIN reduction gives both
  std::vector<double> corners(6 * static_cast<std::size_t>(ranks), std::numeric_limits<double>::infinity());
  double* mine = corners.data() + 6 * rank;
  for (const Vec3& x : where)
    for (int d = 0; d < 3; ++d)
    {
      mine[d] = std::min(mine[d], x[d]);
      mine[3 + d] = std::min(mine[3 + d], -x[d]);
    }
  MPI_Allreduce(MPI_IN_PLACE, corners.data(), static_cast<int>(corners.size()), MPI_DOUBLE, MPI_MIN, comm);
  std::vector<Box> reach(boxes.begin(), boxes.end());
  for (std::size_t r = 0; r < reach.size(); ++r)
  {
    const double* c = corners.data() + 6 * r;
    reach[r].min = reach[r].min.cwiseMin(Vec3(c[0], c[1], c[2]));
    reach[r].max = reach[r].max.cwiseMax(-Vec3(c[3], c[4], c[5]));
  }
  return reach;
}
void linkClumps(Bodies& bodies, std::span<const GlobalId> globalIdOfRow, const std::vector<std::vector<GlobalId>>& members)
{
  auto rowOf = [&](GlobalId id) -> BodyId {
    const auto at = std::lower_bound(globalIdOfRow.begin(), globalIdOfRow.end(), id);
    return at != globalIdOfRow.end() && *at == id ? static_cast<BodyId>(at - globalIdOfRow.begin()) : BodyId{-1};
  };
  // A clump not held here has no rows to name: its member list stays empty.
  for (ClumpShape& clump : bodies.clumps)
    clump.members.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i)
  {
    if (bodies.clumpId[i] >= 0)
    {
      const GlobalId clump = bodies.clumpId[i];
      bodies.clumpId[i] = rowOf(clump);
      if (bodies.clumpId[i] < 0)
        throw std::logic_error("linkClumps: body " + std::to_string(globalIdOfRow[i]) + " is held without its clump "
                               + std::to_string(clump));
    }
    else if (bodies.shape[i] == ShapeKind::Clump && bodies.alive[i])
    {
      const auto shape = static_cast<std::size_t>(bodies.shapeIndex[i]);
      std::vector<BodyId>& rows = bodies.clumps[shape].members;
      for (const GlobalId m : members[shape])
      {
        rows.push_back(rowOf(m));
        if (rows.back() < 0)
          throw std::logic_error("linkClumps: clump " + std::to_string(globalIdOfRow[i]) + " is held without its member "
                                 + std::to_string(m));
      }
    }
  }
}
} // namespace talus::dem::distributed
