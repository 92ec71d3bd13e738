#pragma once

#include "dem/core/Contacts.h"
#include "dem/core/Domain.h"
#include "dem/distributed/Partition.h"
#include "dem/distributed/balance/Balance.h"
#include "dem/distributed/periodic/Regions.h"
#include "dem/distributed/slabs/HeldRows.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace talus::dem::distributed
{
/// A scene split over the ranks of an MPI communicator (the Domain the step calls).
///
/// Rows: the spheres this rank owns, the walls and facets (replicated: every rank holds all of
/// them, moves them alike, and computes their contacts with its own spheres only) and the ghosts (copies of the spheres of
/// other ranks within reach of this rank's region), all in ascending global id, so that the
/// collider orients every contact and the gather sums every body's contacts as in the serial
/// scene: the owned bodies' forces are the serial ones bit for bit.
///
/// Regions: Zoltan's partition of the spheres when the domain is made; at each re-detection a
/// sphere that left its rank's region moves to the rank whose region holds it (RCB's boxes tile
/// space), or, with HSFC, Zoltan partitions again. Contacts move with their bodies. In a
/// periodic cell the regions are boxes of the cell's reduced coordinates (periodic/Regions.h),
/// which move with the cell as it deforms, and a body near a face of the cell is a ghost on the
/// ranks across it.
class MpiDomain final : public Domain
{
public:
  /// Split `scene`, built whole and identically on every rank of `comm`, or in slabs (`held`)
  /// (collective): the
  /// spheres are partitioned, each rank keeps its own, the walls and its ghosts, and the contacts
  /// it computes.
  /// @throws std::invalid_argument on every rank, naming what is not distributed yet (a shape,
  ///         a wall or facet in a periodic cell), an unknown
  ///         partition method, or more ranks than spheres
  /// @param comm the ranks sharing the scene (kept, not duplicated: it must outlive the domain)
  /// @param settings the partition's method and imbalance tolerance, the same on every rank
  /// @param held the global ids of the rows when the scene was built in slabs (no rank holding
  ///        all of it), null when every rank built it whole
  MpiDomain(MPI_Comm comm, Scene& scene, const PartitionSettings& settings, const HeldRows* held = nullptr);

  std::size_t ownedBodies(const Scene& scene) const override;
  bool owns(std::size_t row) const override { return owned_[row] != 0; }
  /// Whether row `row` is a body every rank holds (a wall or facet): counted once in sums of states.
  [[nodiscard]] bool replicated(std::size_t row) const { return replicated_[row] != 0; }
  bool computesPair(std::size_t row1, std::size_t row2) const override;
  /// A wall (every rank holds it) is counted by rank 0 only.
  bool countsBody(std::size_t row) const override { return owned_[row] && (!replicated_[row] || rank_ == 0); }
  /// A contact between spheres on the rank owning its lower global id (the lower row: rows are in
  /// global-id order); a wall's contact where it is computed (the sphere's rank).
  bool countsContact(std::size_t row1, std::size_t row2) const override
  {
    if (replicated_[row1] || replicated_[row2])
      return computesPair(row1, row2);
    return owned_[std::min(row1, row2)] != 0;
  }
  void beforeDetection(Scene& scene) override;
  void afterIntegration(Scene& scene) override;
  void sum(std::span<double> values) const override;
  double min(double value) const override;
  void min(std::span<double> values) const override;

  /// This process's rank in the domain's communicator.
  [[nodiscard]] int rank() const { return rank_; }
  /// The communicator's size.
  [[nodiscard]] int ranks() const { return ranks_; }
  /// Bodies of the whole scene (global ids 0 .. globalCount - 1).
  [[nodiscard]] std::int64_t globalCount() const { return globalCount_; }
  /// The row of global id `id` here.
  /// @param id a global id (the body's id in the scene the user built)
  /// @return the local row; `elsewhere` if another rank holds it; `noBody` for an id out of the
  ///         scene or erased
  [[nodiscard]] std::int64_t rowOf(GlobalId id) const override;
  /// Erase body `id` on every rank (collective by rule: every rank calls it with the same ids in
  /// the same order, as a script running alike on every rank does): each rank erases its copy
  /// (its own body, a wall or facet, or a ghost) with its contacts, so no contact with it is
  /// computed anywhere, and every rank knows it was erased. A rank that erased other bodies than
  /// the others is found at the next re-detection, which raises on every rank. A clump frees
  /// its members, or erases them too; a member leaves its clump, which keeps its mass and goes
  /// with its last member (Scene::erase, Yade's rules).
  /// @param id a global id
  /// @param eraseClumpMembers for a clump: erase its members too instead of freeing them
  /// @return false if it was erased already
  /// @throws std::out_of_range for an id that is not a body of the scene
  bool erase(Scene& scene, GlobalId id, bool eraseClumpMembers = false);
  /// @param row a local row, below scene.bodies.size()
  /// @return its body's global id
  [[nodiscard]] GlobalId globalIdOf(std::size_t row) const { return globalId_[row]; }
  /// Whether the scene has clumps (each held whole by the rank of its centre of mass).
  [[nodiscard]] bool hasClumps() const { return hasClumps_; }
  /// Per clump shape (Bodies::clumps' index), its members' global ids (the same on every rank).
  [[nodiscard]] const std::vector<std::vector<GlobalId>>& clumpMembers() const { return clumpMembers_; }
  /// Distance within which a sphere of another rank is a ghost here: twice the largest radius
  /// plus the collider's skin, taken again at each re-detection (spheres may have grown).
  [[nodiscard]] double ghostDistance() const { return ghostDistance_; }

  /// What the halo moved: ghost updates (one per step) and re-detections (migration and ghost
  /// rebuild), bytes and messages this rank sent, and the seconds this rank spent in them, in
  /// the reductions and in splitting the scene (waiting for the other ranks included); of those,
  /// the CPU seconds spent waiting in the ghost updates' and the reductions' MPI calls.
  struct Traffic
  {
    std::int64_t updates = 0, updateBytes = 0, updateMessages = 0;
    std::int64_t rebuilds = 0, rebuildBytes = 0;
    /// Bodies this rank sent to their new rank, and contacts (with their state) it sent with them.
    std::int64_t migratedBodies = 0, migratedContacts = 0;
    double updateSeconds = 0, rebuildSeconds = 0, reductionSeconds = 0, splitSeconds = 0, waitCpuSeconds = 0;
  };
  /// What this rank's halo moved so far (since resetTraffic).
  [[nodiscard]] const Traffic& traffic() const { return traffic_; }
  /// Zero what the steps counted (the split's seconds stay).
  void resetTraffic() { traffic_ = Traffic{.splitSeconds = traffic_.splitSeconds}; }
  /// The load measured at each re-detection and the rebalances it set off.
  [[nodiscard]] const Balance& balance() const { return balance_; }
  /// This rank's compute seconds since the split: CPU seconds not spent waiting in MPI calls nor
  /// in the re-detections' migration (the measured intervals and the one still open).
  [[nodiscard]] double computeSeconds() const;
  /// PartitionSettings::rebalanceThreshold from now on (every rank sets the same).
  /// @throws std::invalid_argument below 1
  void setRebalanceThreshold(double threshold) { balance_.setThreshold(threshold); }
  /// Each rank's region (index = rank), as the last partition left them.
  [[nodiscard]] const std::vector<Box>& regions() const { return boxes_; }
  /// Rows of ghosts here (copies of other ranks' spheres).
  [[nodiscard]] std::size_t ghosts() const { return recvRows_.size(); }

private:
  /// Lay the scene out again from this rank's spheres `mine` (global ids ascending): walls, mine
  /// and the ghosts exchanged for them, in global-id order; `contacts` (with the global ids of
  /// their bodies) become the contact list, keeping those this rank computes.
  void assemble(Scene& scene, RankBodies& mine, std::vector<Contact>& contacts, std::vector<ContactExtra>& extra,
                std::vector<GlobalId>& contactIds);
  /// Where this rank's units (a free sphere, or a clump with its members: clumps/Units.h) go, as
  /// a plan over the rows of `mine` (their clumpId entries global ids), placing each unit by its
  /// head: into the RCB box holding it, or by Zoltan partitioning again.
  /// @param rowWeights per row of `mine`, for Zoltan (a unit weighs its rows' sum); empty: 1 each
  /// @param partitionAgain whether Zoltan partitions again (the regions change), else RCB's boxes stay
  [[nodiscard]] Plan placeUnits(const Scene& scene, const RankBodies& mine, std::span<const double> rowWeights,
                                bool partitionAgain);
  /// The ghost layer for spheres of radii rmin to rmax: twice rmax plus the collider's skin.
  [[nodiscard]] double ghostLayer(double rmin, double rmax) const;
  /// The row of global id `id` here, -1 if this rank holds no copy of it (erased or not).
  [[nodiscard]] std::int64_t rowHeld(GlobalId id) const;
  /// The rank whose region holds a body at `position` (RCB), -1 if none (not a finite position).
  [[nodiscard]] int regionOf(const Vec3& position) const;

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  PartitionSettings settings_;
  Method method_;
  std::vector<Box> boxes_;
  Regions regions_; ///< the space boxes_ tile: a periodic cell's reduced coordinates at the last re-detection
  double ghostDistance_ = 0;
  double verletDist_ = 0; ///< the collider's skin: absolute, or relative to the smallest radius when negative
  std::int64_t globalCount_ = 0;
  std::vector<GlobalId> globalId_; ///< per row, ascending (rowOf searches it)
  std::vector<std::uint8_t> owned_, replicated_; ///< per row: this rank's; a wall (every rank's)
  /// Ghost updates: rows sent to rank r are sendRows_[sendStart_[r] .. sendStart_[r+1]), the
  /// rows receiving from rank r are recvRows_[recvStart_[r] .. recvStart_[r+1]), in that order.
  std::vector<std::int64_t> sendRows_, sendStart_, recvRows_, recvStart_;
  std::vector<double> sendBuffer_, recvBuffer_;
  std::vector<Vec3> detectedAt_; ///< per row: its position at the last re-detection
  Mat3 detectedCell_ = Mat3::Identity(); ///< the periodic cell's hSize then
  std::vector<GlobalId> erased_; ///< the bodies erased, ascending (the same on every rank)
  bool hasClumps_ = false;       ///< the scene has clumps (the same on every rank)
  /// A clump or a member of one (the same on every rank): its id, its clump's and the clump's shape index.
  struct Clumped
  {
    GlobalId id, clump;
    std::size_t shape;
    bool operator<(const Clumped& other) const { return id < other.id; }
  };
  std::vector<Clumped> clumped_; ///< the clumps and their members, ascending
  std::vector<std::vector<GlobalId>> clumpMembers_; ///< per clump (its shape index), its members' global ids
  mutable Traffic traffic_; ///< mutable: the reductions (const) count their seconds
  mutable double waitedCpu_ = 0; ///< CPU seconds waiting in MPI calls since the split (resetTraffic keeps it)
  Balance balance_;
};
} // namespace talus::dem::distributed
