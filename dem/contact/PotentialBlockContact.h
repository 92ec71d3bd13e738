#pragma once

#include "dem/core/Bodies.h"
#include "dem/shapes/ConvexContact.h"

namespace talus::dem
{
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
/// `b.blockContact` (Ig2_PB_PB_ScGeom's settings): with `exactDepth` the normal is the
/// polyhedra's least-overlap axis and the penetration the depth along it; with `twoDimension`
/// the area is the joint length (the chord through the contact point along normal x twoDdir)
/// times unitWidth2D.
/// `accuracyTol`: the analytic centre's Newton iteration stops once its Newton decrement is
/// below it (the chord and the area are exact for the point and normal found).
/// @param b the scene's bodies
/// @param i1, i2 the bodies' ids (i1 may be a wall)
/// @param previous the last step's contact point (world, m), or null
/// @param out the contact's normal, penetration, point and area when they overlap
/// @param accuracyTol the analytic centre's Newton decrement at which it stops
/// @return false if the shapes do not overlap
bool potentialBlockContact(const Bodies& b, std::size_t i1, std::size_t i2, const Vec3* previous,
                           ConvexContactGeometry& out, double accuracyTol = defaultBlockAccuracyTol);

/// Deepest point x of the half-spaces normals_j . x <= h_j (unit normals), the centre of the
/// largest ball inside them: maximise s subject to normals_j . x + s <= h_j (CLP), with x
/// bounded by `bound` in each coordinate to keep the program well posed.
/// @param normals, h the half-spaces' unit normals and offsets (m)
/// @param bound the box |x_k| <= bound (m) the point is kept in
/// @param x set to the deepest point
/// @return the depth s (the ball's radius; <= 0: the region is empty or flat)
/// @throws std::logic_error in a build without CLP
double deepestPoint(const std::vector<Vec3>& normals, const std::vector<double>& h, double bound, Vec3& x);

/// World-frame axis-aligned bounding box of block i, from its turned vertices.
/// @param i the block's body id
/// @param lo, hi set to the box's corners
void potentialBlockAabb(const Bodies& b, std::size_t i, Vec3& lo, Vec3& hi);
} // namespace talus::dem
