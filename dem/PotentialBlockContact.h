#pragma once

#include "dem/Bodies.h"

namespace talus::dem
{
/// Geometry of a contact involving a Potential Block (Yade's Ig2_PB_PB_ScGeom).
struct BlockContactGeometry
{
  Vec3 normal;       ///< unit, from body 1 to body 2
  Vec3 contactPoint; ///< middle of the overlap region's chord along the normal
  double penetration = 0; ///< length of that chord (Yade's penetrationDepth)
  double area = 0;   ///< area of the overlap region's section normal to `normal` through the contact point
  int lpSolves = 0;  ///< linear programs solved (0 when a cheaper interior point was found)
};

/// Overlap of two Potential Blocks i1, i2, or of wall i1 and block i2.
///
/// The overlap region is the intersection of both sets of half-spaces. A linear program (CLP)
/// finds its deepest point (the centre of the largest inscribed ball), skipped while the
/// previous contact point `previous` (may be null) stays strictly inside or when the mean of
/// the corners of each body inside the other is strictly inside; damped Newton steps
/// from there reach the analytic centre (minimum of -sum log slack). The normal is the
/// gradient of the inner potential of the block whose face holds the point (the average of
/// both blocks' gradients when neither or both do; a wall's own normal). The penetration is
/// the overlap region's chord through the analytic centre along the normal, clipped exactly
/// against every plane (the limit of Yade's bracketed bisection). Pairs separated by a face
/// plane of either or by the cross product of two edges (separating-axis theorem, exact for
/// polyhedra) are rejected before any linear program.
/// @return false if the shapes do not overlap
bool potentialBlockContact(const Bodies& b, std::size_t i1, std::size_t i2, const Vec3* previous,
                           BlockContactGeometry& out);

/// World-frame axis-aligned bounding box of block i, from its turned vertices.
void potentialBlockAabb(const Bodies& b, std::size_t i, Vec3& lo, Vec3& hi);
} // namespace talus::dem
