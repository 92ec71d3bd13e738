#pragma once

#include "dem/CellGrid.h"
#include "dem/Contacts.h"
#include "dem/Engine.h"
#include "dem/Threads.h"
#include "dem/types.h"

#include <cstdint>
#include <vector>

namespace talus::dem
{
/// A candidate pair found by the collider: key (id1 << 32 | id2) and periodic image offset.
using PairKey = std::uint64_t;
struct Candidate
{
  PairKey key;
  Eigen::Vector3i cellDist;
};

/// Contact detection: linked cells with a Verlet skin (Yade scripts name it
/// InsertionSortCollider; the job and the parameters are the same).
///
/// At a rebuild every pair of shapes closer than the skin `verletDist` becomes a candidate pair
/// in the contact list (existing pairs keep their history). Between rebuilds only candidates are
/// checked, which is exact as long as no body has moved more than half the skin since the last
/// rebuild; the collider checks that every step and rebuilds when it fails or bodies changed.
class Collider : public Engine
{
public:
  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "Collider"; }

  /// Skin width; negative: that fraction of the smallest sphere radius (Yade's default -0.5).
  double verletDist = -0.5;
  /// Number of rebuilds so far (diagnostics).
  std::int64_t rebuilds = 0;

  /// The skin check's verdict before the per-body test: `rebuild` when it is already known
  /// (bodies changed, the cell deformed past the skin, a block or particle moved or turned too
  /// far); otherwise what movedIn needs.
  struct SkinCheck
  {
    bool rebuild = false;
    bool deformed = false; ///< a deforming periodic cell: references follow the affine map
    Mat3 affine = Mat3::Identity();
    double limit2 = 0; ///< squared displacement allowed since the last rebuild
  };
  [[nodiscard]] SkinCheck skinCheck(const Scene& scene) const;
  /// Whether a body of [first, last) moved beyond the check's limit (check.rebuild false).
  [[nodiscard]] bool movedIn(const Scene& scene, const SkinCheck& check, std::int64_t first, std::int64_t last) const;
  /// Re-detect the candidate pairs now.
  void rebuild(Scene& scene);

private:
  [[nodiscard]] bool needsRebuild(const Scene& scene) const;

  std::vector<Vec3> referencePos_;
  // Scratch space kept between rebuilds, so re-detection does not allocate (and fault in) memory.
  ContactList spare_; ///< the previous contact list's storage
  ContactExtraList spareExtra_;
  CellGrid grid_;
  std::vector<Candidate> pairs_, boundaryPairs_;
  std::vector<std::vector<Candidate>> perThread_;
  Mat3 referenceCellInverse_ = Mat3::Identity();
  double referenceRange_ = 0;
  std::vector<BodyId> spheres_, walls_, facets_, boxes_, convex_; ///< convex_: Potential Blocks and Particles
  /// Potential Blocks turn their corners about the centre: their orientations at the last
  /// rebuild, to bound how far a corner moved.
  std::vector<Quat> referenceOri_;
  std::int64_t seenBodiesVersion_ = -1;
  double skin_ = 0;
  mutable BalancedRanges skinRanges_; ///< the skin check's bodies per thread (its timing only)
};
} // namespace talus::dem
