#pragma once

#include "dem/base/types.h"

#include <string>
#include <vector>

namespace talus::dem
{
/// Checks shared by the shapes given as planes a_i x + b_i y + c_i z = d_i (Potential Blocks
/// and Potential Particles, Yade's a, b, c, d arrays): equal lengths, finite values, unit
/// normals. Returns the normals.
/// @param a, b, c, d one entry per plane: the normal's components and the offset (m)
/// @param which how errors name the shape
/// @return the unit normals (a_i, b_i, c_i)
/// @throws std::invalid_argument starting with `which` (e.g. "PotentialBlock #3") and naming
///         the plane
std::vector<Vec3> planeNormals(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
                               const std::vector<double>& d, const std::string& which);

/// Vertices of the polyhedron { x : n_i . x <= h_i }: intersections of plane triples inside
/// every plane, merged within `tol`.
/// @param n, h the planes' unit normals and offsets (m)
/// @param tol the distance (m) within which vertices merge and a point counts as inside a plane
/// @return the vertices, in no particular order; empty for an empty region
std::vector<Vec3> polyhedronVertices(const std::vector<Vec3>& n, const std::vector<double>& h, double tol);

/// The vertices of { x : n_i . x <= h_i } after checking that it is a finite, non-empty region.
/// An unbounded region reaches a far box added around it: a vertex on that box tells the open
/// direction.
/// @param n, h the planes' unit normals and offsets (m)
/// @param which how errors name the shape
/// @return the vertices (merged at a tolerance relative to the region's size)
/// @throws std::invalid_argument starting with `which` if the planes have an empty intersection
///         or do not bound a finite region
std::vector<Vec3> boundedPolyhedronVertices(const std::vector<Vec3>& n, const std::vector<double>& h,
                                            const std::string& which);
} // namespace talus::dem
