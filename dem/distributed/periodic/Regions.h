#pragma once

#include "dem/core/Cell.h"
#include "dem/distributed/Partition.h"

namespace talus::dem::distributed
{
/// The space the ranks' regions tile: space itself in an open scene, and in a periodic scene
/// the cell's reduced coordinates H^-1 x wrapped into [0, 1)^3.
///
/// Why reduced coordinates for a periodic cell: bodies keep unwrapped positions and move with
/// the cell's affine field (velGrad, PeriTriaxController), which leaves their reduced
/// coordinates unchanged; so a rank's region moves and deforms with the cell, a body changes
/// rank only by its own fluctuation, and the boxes Zoltan cuts in the unit cube tile the cell
/// and all its images whatever its shape. Boxes in real space would tile neither a sheared cell
/// nor its images, and would have to follow the cell at every step.
class Regions
{
public:
  /// The regions of an open scene: space itself.
  Regions() = default;
  /// The regions of a periodic scene whose cell is `cell` now.
  explicit Regions(const Cell& cell);

  /// Where a body at `x` lies in the regions' space (its position, or its wrapped reduced
  /// coordinates in a periodic cell).
  /// @param x a position (m), unwrapped
  [[nodiscard]] Vec3 coordinates(const Vec3& x) const;

  /// Where a body at `x` lies in the regions' space beside a body at `beside` (a clump's member
  /// beside its clump): in a periodic cell its reduced coordinates in the image of the cell
  /// where `beside`'s are wrapped, so that a member sticking out of the cell lies just outside
  /// [0, 1) rather than at the far face; its position in an open scene.
  /// @param x, beside positions (m), unwrapped
  [[nodiscard]] Vec3 coordinatesBeside(const Vec3& x, const Vec3& beside) const;

  /// `box` (a region, in coordinates()) within the cell: in a periodic cell its part of the unit
  /// cube (RCB's outer boxes reach infinity), as it is in an open scene.
  [[nodiscard]] Box withinCell(const Box& box) const;

  /// Whether a body at `x` may touch, through any periodic image, a body whose coordinates
  /// lie in `box` (a region in the regions' space): its distance to the region's part of space
  /// is at most `distance`. In a periodic cell the test is made in reduced coordinates, with
  /// the region grown along each axis by `distance` over the spacing of the cell's lattice
  /// planes across that axis: conservative (a body farther than `distance` may pass) and exact
  /// for a rectangular cell.
  /// @param x a position (m), unwrapped
  /// @param box a region, in coordinates(); an infinite bound is the cell's face; it may reach
  ///        out of the unit cube (a region grown to hold clumps' members); empty (min > max)
  ///        reaches nothing
  /// @param distance the reach (m), at most the cell's narrowest width
  [[nodiscard]] bool reaches(const Vec3& x, const Box& box, double distance) const;

private:
  bool periodic_ = false;
  Mat3 inverse_ = Mat3::Identity(); ///< H^-1 of the cell the regions were taken in
};
} // namespace talus::dem::distributed
