#pragma once

#include "dem/core/Bodies.h"
#include "dem/contact/CellGrid.h"
#include "dem/core/Contacts.h"
#include "dem/core/Engine.h"
#include "dem/base/Threads.h"
#include "dem/base/types.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace talus::dem
{
class Domain;

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
  /// The skin check per body (displacementsIn, combined over ranges), the re-detection serial
  /// (rebuild, whose loops are parallel).
  [[nodiscard]] Stages stages() const override
  {
    return Stages{}.with(StagePoint::SkinCheck, Grain::PerBody).with(StagePoint::Detection, Grain::Serial);
  }

  /// Skin width; negative: that fraction of the smallest sphere radius (Yade's default -0.5).
  double verletDist = -0.5;
  /// In a periodic cell, a facet or box spanning more than half the cell along an axis (with
  /// the interaction range) meets the spheres where they are along it (Yade's
  /// InsertionSortCollider.allowBiggerThanPeriod); without it such a body is an error.
  bool allowBiggerThanPeriod = false;
  /// Bodies of one group mask sharing a bit with it never touch each other (Yade's
  /// InsertionSortCollider.avoidSelfInteractionMask; 0: none is kept apart).
  int avoidSelfInteractionMask = 0;
  /// Number of rebuilds so far (diagnostics).
  std::int64_t rebuilds = 0;

  /// Yade's Bound of body `id` (b.bound): its shape's axis-aligned box at the position the last
  /// re-detection saw (`refPos`), grown by the skin (`sweepLength`) on every side; a wall is
  /// unbounded along its plane. None before the first re-detection, after bodies changed, for
  /// an erased body or a clump (its members are bounded).
  struct Bound
  {
    Vec3 min, max, refPos;
    double sweepLength;
  };
  /// @param id any body id
  /// @return its bound (m), or none as said above
  [[nodiscard]] std::optional<Bound> boundOf(const Scene& scene, BodyId id) const;

  /// The skin check's verdict before the per-body test: `rebuild` when it is already known
  /// (bodies changed, the cell deformed past the skin, a block or particle moved or turned too
  /// far); otherwise what displacementsIn needs.
  ///
  /// A candidate pair stays valid while the two bodies' displacements since the re-detection,
  /// d1 and d2, change its distance by no more than the skin: |d1 - d2| <= |d1 - c| + |d2 - c|
  /// for any vector c common to all bodies. Spheres moving together (a falling or sliding
  /// packing) thus need no re-detection: the check subtracts `common`, the middle of the
  /// spheres' displacements at the previous check, for sphere pairs, and allows a sphere and a
  /// wall, facet or box the skin between them (all of it to the sphere if the others have not
  /// moved; half each to two blocks or particles). Re-detections only become rarer than with
  /// c = 0, which is also tried.
  struct SkinCheck
  {
    bool rebuild = false;
    bool deformed = false; ///< a deforming periodic cell: references follow the affine map
    Mat3 affine = Mat3::Identity();
    double limit2 = 0; ///< square of half the skin left (the displacement allowed each body)
    Vec3 common = Vec3::Zero(); ///< displacement subtracted for sphere pairs
    bool otherPairs = false;    ///< pairs of two bodies other than spheres exist (blocks, particles)
  };
  /// @return the verdict for the scene as it is now (changes nothing)
  [[nodiscard]] SkinCheck skinCheck(const Scene& scene) const;
  /// Displacements since the last re-detection, summarised for the skin check; combined over
  /// ranges of bodies with add() (maxima and minima: the same for every thread count).
  struct Displacements
  {
    double sphere2 = 0;       ///< largest squared displacement of a sphere
    double sphereSpread2 = 0; ///< largest squared distance of a sphere's displacement from the common one
    double other2 = -1;       ///< largest squared displacement of another body with a surface (-1: none)
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());   ///< spheres' smallest displacement, per axis
    Vec3 high = Vec3::Constant(-std::numeric_limits<double>::infinity()); ///< and largest
    /// A body's position is not finite (written so from Python, or a diverged run): the
    /// re-detection it forces names the body.
    bool nonFinite = false;
    /// @param d another range's (or process's) summary, merged into this one
    void add(const Displacements& d);
  };
  /// The displacements of the bodies of [first, last) (check.rebuild false).
  /// @param check skinCheck's verdict for this step
  /// @param first, last the body ids of one thread's range
  /// @return the range's summary, to be merged with add()
  [[nodiscard]] Displacements displacementsIn(const Scene& scene, const SkinCheck& check, std::int64_t first,
                                              std::int64_t last) const;
  /// The displacements `all` of every process (maxima and minima over them, in one reduction);
  /// true when some process must re-detect whatever they are (`rebuild`: its bodies changed).
  /// Every process must call it at the same point of the step.
  /// @param rebuild this process's check.rebuild
  /// @param all this process's summary, replaced by the summary over all processes
  /// @return true if some process's rebuild was true
  static bool acrossProcesses(const Domain& domain, bool rebuild, Displacements& all);
  /// Whether the displacements of all bodies call for a re-detection.
  /// @param check skinCheck's verdict
  /// @param all the summary over all bodies (and processes)
  /// @return true when some pair may have come within reach (or a position is not finite)
  [[nodiscard]] static bool mustRebuild(const SkinCheck& check, const Displacements& all);
  /// The common displacement a check after the one that measured `all` subtracts.
  /// @param all the summary over all bodies
  /// @return the middle of the spheres' smallest and largest displacements (m), zero without spheres
  [[nodiscard]] static Vec3 commonOf(const Displacements& all);
  /// Keep commonOf(all) for the next check.
  /// @param all the summary of the check that did not re-detect
  void noteDisplacements(const Displacements& all) { common_ = commonOf(all); }
  /// Re-detect the candidate pairs now.
  void rebuild(Scene& scene);

  /// Which pairs a re-detection may make (Bodies::mayCollide with avoidSelfInteractionMask).
  struct PairFilter
  {
    int avoidSelfInteractionMask = 0;
    bool masks = false; ///< some pair may be refused by the masks (else only clumps refuse pairs)
    /// @param b the scene's bodies
    /// @param i, j the pair's body ids
    /// @return whether the pair may become a contact
    bool operator()(const Bodies& b, std::size_t i, std::size_t j) const
    {
      return b.mayCollide(i, j, avoidSelfInteractionMask);
    }
  };

private:
  [[nodiscard]] bool needsRebuild(const Scene& scene);

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
  /// Bodies whose surface turns about their position: Potential Blocks and Particles, and the
  /// facets and boxes of clumps. Each with the farthest reach of its surface from its position
  /// and its orientation at the last rebuild, to bound how far a corner moved.
  struct Turning
  {
    BodyId id;
    double reach;
    Quat ori;
  };
  std::vector<Turning> turning_;
  std::int64_t seenBodiesVersion_ = -1;
  double skin_ = 0;
  Vec3 common_ = Vec3::Zero(); ///< SkinCheck::common of the next check (zero after a re-detection)
  BalancedRanges skinRanges_; ///< the skin check's bodies per thread (its timing only)
};
} // namespace talus::dem
