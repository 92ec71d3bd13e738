// The distributed DEM's partition, migration and ghosts over MPI: a random cloud of spheres,
// spread over the ranks unevenly, partitioned by Zoltan and migrated. Run under mpirun with 2
// and 3 ranks (tests/CMakeLists.txt).
#include "dem/distributed/Ghosts.h"
#include "dem/distributed/Migration.h"
#include "dem/distributed/Partition.h"

#include <mpi.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace talus::dem;
using namespace talus::dem::distributed;

namespace
{
constexpr GlobalId cloudSize = 3000;
constexpr double largestRadius = 0.01;

int rankOf(MPI_Comm comm)
{
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
int ranksOf(MPI_Comm comm)
{
  int p = 1;
  MPI_Comm_size(comm, &p);
  return p;
}

/// Body `id` of the cloud: every per-body field drawn from a generator seeded by the id, so any
/// rank can rebuild the original of any body.
void appendBody(RankBodies& into, GlobalId id)
{
  std::mt19937_64 rng(static_cast<std::uint64_t>(id) * 7919U + 1U);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  Bodies& b = into.bodies;
  const BodyId i = b.append(ShapeKind::Sphere, -1, static_cast<int>(rng() % 4));
  // A slab thin in z and long in y, so the cuts are not all along one axis.
  b.pos[i] = Vec3(0.5 + 0.5 * u(rng), 1.0 + u(rng), 0.25 + 0.25 * u(rng));
  b.vel[i] = vec();
  b.angVel[i] = vec();
  b.ori[i] = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
  b.angMom[i] = vec();
  b.force[i] = vec();
  b.torque[i] = vec();
  b.extForce[i] = vec();
  b.extTorque[i] = vec();
  b.radius[i] = largestRadius * (0.5 + 0.25 * (1.0 + u(rng)));
  b.mass[i] = 1.0 + u(rng);
  b.inertia[i] = Vec3::Constant(0.4 * b.mass[i] * b.radius[i] * b.radius[i]);
  b.blockedDofs[i] = static_cast<std::uint8_t>(rng() % 64);
  b.dynamic[i] = static_cast<std::uint8_t>(rng() % 2);
  b.damped[i] = static_cast<std::uint8_t>(rng() % 2);
  b.alive[i] = static_cast<std::uint8_t>(1 + rng() % 2);
  b.groupMask[i] = static_cast<int>(1 + rng() % 255);
  b.temperature[i] = 300.0 + 50.0 * u(rng);
  b.heatCapacity[i] = 700.0 + u(rng);
  b.conductivity[i] = 2.0 + u(rng);
  b.thermalExpansion[i] = 1e-5 * (1.0 + u(rng));
  into.globalId.push_back(id);
}

/// Cost of body `id` (as a contact count plus one would be).
double weightOf(GlobalId id) { return 1.0 + static_cast<double>(id % 7); }

/// The bodies each rank starts with: most on rank 0, the fewest on the last (rank r holds the
/// ids g with floor(P (g/N)^2) = r), in no spatial order.
RankBodies unevenStart(MPI_Comm comm)
{
  const int rank = rankOf(comm), ranks = ranksOf(comm);
  RankBodies local;
  for (GlobalId g = 0; g < cloudSize; ++g)
  {
    const double f = static_cast<double>(g) / static_cast<double>(cloudSize);
    if (static_cast<int>(ranks * f * f) == rank)
      appendBody(local, g);
  }
  return local;
}

/// FNV-1a over every per-body field of row i, listed here by hand (not through the module's
/// own list), and the global id.
std::uint64_t checksum(const RankBodies& r, std::size_t i)
{
  std::uint64_t h = 1469598103934665603ULL;
  auto add = [&](const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t k = 0; k < n; ++k)
      h = (h ^ c[k]) * 1099511628211ULL;
  };
  const Bodies& b = r.bodies;
  for (const auto* v : {&b.pos[i], &b.vel[i], &b.angVel[i], &b.angMom[i], &b.force[i], &b.torque[i],
                        &b.extForce[i], &b.extTorque[i], &b.inertia[i]})
    add(v->data(), 3 * sizeof(double));
  add(b.ori[i].coeffs().data(), 4 * sizeof(double));
  add(&b.mass[i], sizeof(double));
  add(&b.radius[i], sizeof(double));
  add(&b.shape[i], sizeof(ShapeKind));
  add(&b.shapeIndex[i], sizeof(int));
  add(&b.material[i], sizeof(int));
  add(&b.blockedDofs[i], 1);
  add(&b.dynamic[i], 1);
  add(&b.damped[i], 1);
  add(&b.alive[i], 1);
  add(&b.clumpId[i], sizeof(BodyId));
  add(&b.groupMask[i], sizeof(int));
  for (const double* heat : {&b.temperature[i], &b.heatCapacity[i], &b.conductivity[i], &b.thermalExpansion[i]})
    add(heat, sizeof(double));
  add(&r.globalId[i], sizeof(GlobalId));
  return h;
}

/// Every per-body array of `r` has one entry per global id (checksum may read them all).
bool sizesAgree(const RankBodies& r)
{
  const Bodies& b = r.bodies;
  const std::size_t n = r.size();
  for (const std::size_t size :
       {b.pos.size(), b.vel.size(), b.angVel.size(), b.ori.size(), b.angMom.size(), b.force.size(), b.torque.size(),
        b.extForce.size(), b.extTorque.size(), b.mass.size(), b.inertia.size(), b.radius.size(), b.shape.size(),
        b.shapeIndex.size(), b.material.size(), b.blockedDofs.size(), b.dynamic.size(), b.damped.size(),
        b.alive.size(), b.clumpId.size(), b.groupMask.size(), b.temperature.size(), b.heatCapacity.size(),
        b.conductivity.size(), b.thermalExpansion.size()})
    if (size != n)
      return false;
  return true;
}

std::uint64_t originalChecksum(GlobalId id)
{
  RankBodies one;
  appendBody(one, id);
  return checksum(one, 0);
}

/// Every rank's bodies on every rank: global id, centre and owner.
struct Gathered
{
  std::vector<GlobalId> id;
  std::vector<Vec3> pos;
  std::vector<int> owner;
};
Gathered gatherAll(MPI_Comm comm, const RankBodies& local)
{
  const int ranks = ranksOf(comm);
  int count = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(static_cast<std::size_t>(ranks) + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (std::size_t r = 0; r < counts.size(); ++r)
    starts[r + 1] = starts[r] + counts[r];
  Gathered all;
  const auto total = static_cast<std::size_t>(starts.back());
  all.id.resize(total);
  MPI_Allgatherv(local.globalId.data(), count, MPI_INT64_T, all.id.data(), counts.data(), starts.data(),
                 MPI_INT64_T, comm);
  std::vector<double> mine(3 * local.size()), xyz(3 * total);
  for (std::size_t i = 0; i < local.size(); ++i)
    for (int d = 0; d < 3; ++d)
      mine[3 * i + static_cast<std::size_t>(d)] = local.bodies.pos[i][d];
  std::vector<int> counts3(counts), starts3(starts);
  for (auto& c : counts3)
    c *= 3;
  for (auto& s : starts3)
    s *= 3;
  MPI_Allgatherv(mine.data(), 3 * count, MPI_DOUBLE, xyz.data(), counts3.data(), starts3.data(), MPI_DOUBLE, comm);
  for (std::size_t k = 0; k < total; ++k)
    all.pos.emplace_back(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
  for (int r = 0; r < ranks; ++r)
    all.owner.insert(all.owner.end(), static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]), r);
  return all;
}

/// Partition and migrate the uneven cloud with `method`; checks the plan's own bookkeeping.
std::pair<RankBodies, Plan> spread(MPI_Comm comm, const std::string& method)
{
  RankBodies local = unevenStart(comm);
  std::vector<double> weights;
  for (const GlobalId g : local.globalId)
    weights.push_back(weightOf(g));
  PartitionSettings settings;
  settings.method = method;
  Plan plan = partition(comm, local, weights, settings);
  EXPECT_TRUE(std::is_sorted(plan.exportRows.begin(), plan.exportRows.end()));
  EXPECT_EQ(plan.boxes.size(), static_cast<std::size_t>(ranksOf(comm)));
  std::int64_t moves[2] = {static_cast<std::int64_t>(plan.exportRows.size()),
                           static_cast<std::int64_t>(plan.importIds.size())};
  MPI_Allreduce(MPI_IN_PLACE, moves, 2, MPI_INT64_T, MPI_SUM, comm);
  EXPECT_EQ(moves[0], moves[1]);
  EXPECT_GT(moves[0], 0) << "the uneven start must make bodies move";
  migrate(comm, local, plan);
  return {std::move(local), std::move(plan)};
}

class Spread : public ::testing::TestWithParam<std::string>
{
};

TEST_P(Spread, EveryBodyArrivesOnceBitIdenticalBalancedAndInsideItsRegion)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const int rank = rankOf(comm), ranks = ranksOf(comm);
  const auto [local, plan] = spread(comm, GetParam());
  ASSERT_TRUE(sizesAgree(local)) << "a per-body array was not migrated";

  std::vector<int> seen(static_cast<std::size_t>(cloudSize), 0);
  for (std::size_t i = 0; i < local.size(); ++i)
  {
    ++seen[static_cast<std::size_t>(local.globalId[i])];
    EXPECT_EQ(checksum(local, i), originalChecksum(local.globalId[i])) << "body " << local.globalId[i];
    EXPECT_EQ(distanceToBox(local.bodies.pos[i], plan.boxes[static_cast<std::size_t>(rank)]), 0.0)
        << "body " << local.globalId[i] << " lies outside its owner's region";
  }
  MPI_Allreduce(MPI_IN_PLACE, seen.data(), static_cast<int>(seen.size()), MPI_INT, MPI_SUM, comm);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), cloudSize) << "a body is missing or duplicated";

  double load = 0.0, largest = 0.0;
  for (const GlobalId g : local.globalId)
    load += weightOf(g);
  std::vector<double> loads(static_cast<std::size_t>(ranks));
  MPI_Allgather(&load, 1, MPI_DOUBLE, loads.data(), 1, MPI_DOUBLE, comm);
  for (GlobalId g = 0; g < cloudSize; ++g)
    largest = std::max(largest, weightOf(g));
  double total = 0.0;
  for (const double l : loads)
    total += l;
  const double average = total / ranks, heaviest = *std::max_element(loads.begin(), loads.end());
  // Zoltan's tolerance, plus one body: a cut cannot split a body.
  EXPECT_LE(heaviest, PartitionSettings{}.imbalanceTolerance * average + largest)
      << "heaviest rank " << heaviest << ", average " << average;
}

TEST_P(Spread, GhostsAreExactlyTheBodiesNearEachRegion)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const int rank = rankOf(comm);
  const auto [local, plan] = spread(comm, GetParam());
  const double skin = 0.3 * largestRadius, distance = 2 * largestRadius + skin;
  const Ghosts ghosts = exchangeGhosts(comm, local, plan.boxes, distance);
  ASSERT_TRUE(sizesAgree(ghosts.copies)) << "a per-body array was not sent with the ghosts";

  // Brute force on the gathered cloud.
  const Gathered all = gatherAll(comm, local);
  std::vector<GlobalId> expected, got = ghosts.copies.globalId;
  std::map<GlobalId, int> ownerOf;
  for (std::size_t k = 0; k < all.id.size(); ++k)
  {
    ownerOf[all.id[k]] = all.owner[k];
    if (all.owner[k] != rank && distanceToBox(all.pos[k], plan.boxes[static_cast<std::size_t>(rank)]) <= distance)
      expected.push_back(all.id[k]);
  }
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, expected);
  ASSERT_EQ(ghosts.owner.size(), ghosts.copies.size());
  for (std::size_t k = 0; k < ghosts.copies.size(); ++k)
  {
    EXPECT_EQ(ghosts.owner[k], ownerOf[ghosts.copies.globalId[k]]);
    EXPECT_EQ(checksum(ghosts.copies, k), originalChecksum(ghosts.copies.globalId[k]));
  }

  // What the DEM needs of them: every body of another rank within reach of one of mine is here.
  for (std::size_t k = 0; k < all.id.size(); ++k)
    if (all.owner[k] != rank)
      for (std::size_t i = 0; i < local.size(); ++i)
        if ((all.pos[k] - local.bodies.pos[i]).norm() <= distance)
        {
          EXPECT_TRUE(std::binary_search(got.begin(), got.end(), all.id[k]))
              << "body " << all.id[k] << " can touch body " << local.globalId[i] << " but is not a ghost";
          break;
        }

  // Not vacuous: some bodies are ghosts, not every body everywhere; what was sent was received.
  // (HSFC's regions are bounding boxes of curve stretches, which overlap: far more ghosts.)
  std::int64_t counts[2] = {static_cast<std::int64_t>(ghosts.sentRows.size()),
                            static_cast<std::int64_t>(ghosts.copies.size())};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, comm);
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_GT(counts[1], 0);
  EXPECT_LT(counts[1], cloudSize * (ranksOf(comm) - 1));
}

INSTANTIATE_TEST_SUITE_P(Methods, Spread, ::testing::Values("RCB", "HSFC"));

TEST(Partition, UnknownMethodIsRefusedOnEveryRank)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const RankBodies local = unevenStart(comm);
  PartitionSettings settings;
  settings.method = "RCBX";
  try
  {
    (void)partition(comm, local, {}, settings);
    ADD_FAILURE() << "an unknown method was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("'RCBX'"), std::string::npos) << what;
    EXPECT_NE(what.find("RCB, HSFC"), std::string::npos) << what;
  }
  MPI_Barrier(comm); // every rank got here: none is left waiting in a collective
}

TEST(Partition, OneRanksBadInputIsRaisedOnEveryRank)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const int last = ranksOf(comm) - 1;
  RankBodies local = unevenStart(comm);
  std::vector<double> weights(local.size(), 1.0);
  if (rankOf(comm) == last)
    weights.pop_back();
  EXPECT_THROW((void)partition(comm, local, weights), std::invalid_argument);

  // A facet on the last rank only: every rank says which body it is.
  if (rankOf(comm) == last)
    local.bodies.shape.back() = ShapeKind::Facet;
  try
  {
    (void)partition(comm, local, {});
    ADD_FAILURE() << "a facet was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("is a Facet"), std::string::npos) << what;
    EXPECT_NE(what.find("body " + std::to_string(cloudSize - 1)), std::string::npos) << what;
  }
  MPI_Barrier(comm);
}

TEST(BodyRows, PackUnpackAndKeepRoundTrip)
{
  RankBodies cloud;
  for (GlobalId g = 0; g < 10; ++g)
    appendBody(cloud, 100 + g);
  std::vector<std::byte> bytes;
  const std::vector<std::int64_t> rows{7, 2, 9};
  packRows(cloud, rows, bytes);
  ASSERT_EQ(bytes.size(), 3 * rowBytes());
  RankBodies copy;
  unpackRows(bytes, copy);
  ASSERT_EQ(copy.size(), 3U);
  ASSERT_TRUE(sizesAgree(copy));
  for (std::size_t k = 0; k < rows.size(); ++k)
    EXPECT_EQ(checksum(copy, k), checksum(cloud, static_cast<std::size_t>(rows[k])));
  EXPECT_THROW(unpackRows(std::span(bytes).first(bytes.size() - 1), copy), std::invalid_argument);

  const std::vector<std::uint8_t> keep{1, 0, 1, 1, 0, 0, 0, 0, 0, 1};
  keepRows(cloud, keep);
  EXPECT_EQ(cloud.globalId, (std::vector<GlobalId>{100, 102, 103, 109}));
  EXPECT_EQ(cloud.bodies.size(), 4U);
  EXPECT_EQ(checksum(cloud, 3), originalChecksum(109));
}

TEST(Partition, DistanceToBoxAndMethodNames)
{
  const Box box{Vec3(0, 0, 0), Vec3(1, 2, 3)};
  EXPECT_EQ(distanceToBox(Vec3(0.5, 1, 1), box), 0.0);
  EXPECT_DOUBLE_EQ(distanceToBox(Vec3(-3, 1, 1), box), 3.0);
  EXPECT_DOUBLE_EQ(distanceToBox(Vec3(4, 6, 1), box), 5.0);
  EXPECT_EQ(methodNamed("RCB"), Method::RCB);
  EXPECT_EQ(methodNamed("HSFC"), Method::HSFC);
  EXPECT_THROW((void)methodNamed("rcb"), std::invalid_argument);
}
} // namespace

int main(int argc, char** argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Only rank 0 prints, so ctest's log is readable; every rank's failure still fails the run.
  if (rankOf(MPI_COMM_WORLD) != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
        ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int failed = RUN_ALL_TESTS();
  int anyFailed = 0;
  MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return anyFailed;
}
