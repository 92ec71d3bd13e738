#pragma once

#include "dem/base/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace talus::dem
{
/// A convex polyhedron given by planes (Yade's PotentialBlock, Boon et al. 2012): the block is
/// { y : n_i . y <= d_i + r } in the body frame, and the inner smooth potential
/// f(y) = sum_i <n_i . y - d_i>^2 (Macaulay brackets), which lies r inside the faces and is
/// rounded with radius r, gives the contact normal.
///
/// Stored in the body's principal frame with the origin at the centroid (makePotentialBlock
/// moves the user's planes there), so the body's orientation turns the principal axes.
struct PotentialBlockShape
{
  std::vector<Vec3> normals; ///< unit outward normals n_i (body frame)
  std::vector<double> d;     ///< plane offsets of the inner potential; faces are at d_i + r
  double r = 0;              ///< rounding of the inner potential (distance of the faces from it)
  double R = 0;              ///< reference length: half the largest distance between vertices unless given
  bool isBoundary = false;   ///< boundary blocks interact only with non-boundary ones (stiffness kn_i, ks_i)
  std::vector<Vec3> vertices;            ///< corners of the block (body frame)
  std::vector<std::vector<int>> faces;   ///< per plane touching the block in an area: its vertices, counter-clockwise seen from outside
  std::vector<int> facePlane;            ///< the plane index of each face
  std::vector<Vec3> edgeDirections;      ///< unit directions of the edges, parallel ones once (separating-axis tests)
  double volume = 0;
  double boundingRadius = 0; ///< largest distance of a vertex from the centroid (for the collider's skin check)
  // Rock-joint properties of each plane's face (Yade's PotentialBlock cohesion, tension,
  // intactRock, jointType, which BlockGen fills from the joint file); one entry per plane.
  // Read by the KnKsPB law with useFaceProperties when a contact forms.
  std::vector<double> cohesion, tension; ///< strengths (stresses) of the face
  std::vector<std::uint8_t> intactRock;  ///< the face is intact rock (bonded to its neighbour)
  std::vector<std::int32_t> jointType;
};

/// What makePotentialBlock derives from the user's planes besides the shape.
struct PotentialBlockPlacement
{
  Vec3 centroid;          ///< centroid in the planes' frame
  Quat principalAxes;     ///< rotation from the principal frame to the planes' frame
  Vec3 inertiaPerDensity; ///< principal moments of inertia divided by the density
};

/// Build a block from planes a_i x + b_i y + c_i z <= d_i + r (Yade's PotentialBlock arguments).
/// Vertices are the intersections of plane triples inside every plane; volume, centroid and
/// principal inertia follow from the faces. R <= 0 asks for the automatic reference length.
/// @param a, b, c, d the planes, unit normals (a, b, c)
/// @param r the rounding of the inner potential, >= 0
/// @param R the reference length (<= 0: automatic)
/// @param isBoundary a boundary block (interacts with non-boundary ones only)
/// @param which how errors name the block
/// @param placement set, when not null, to the centroid and principal axes in the planes' frame
///        and the inertia per unit density
/// @return the block in its principal frame
/// @throws std::invalid_argument starting with `which` (e.g. "PotentialBlock #3") if the
///         arrays differ in length, a normal is not unit, r or R is negative or not finite, or
///         the planes do not bound a finite convex region of positive volume
PotentialBlockShape makePotentialBlock(const std::vector<double>& a, const std::vector<double>& b,
                                       const std::vector<double>& c, const std::vector<double>& d, double r,
                                       double R, bool isBoundary, const std::string& which,
                                       PotentialBlockPlacement* placement);

/// Give the faces of s their rock-joint properties, one entry per plane (empty: keep them).
/// @param s the block's shape, changed in place
/// @param cohesion, tension the faces' strengths (Pa), >= 0
/// @param intactRock whether each face is intact rock (bonded to its neighbour)
/// @param jointType each face's joint type
/// @param which how errors name the block
/// @throws std::invalid_argument starting with `which` if a list has not one entry per plane or
///         a strength is negative or not finite
void setBlockFaceProperties(PotentialBlockShape& s, const std::vector<double>& cohesion,
                            const std::vector<double>& tension, const std::vector<bool>& intactRock,
                            const std::vector<int>& jointType, const std::string& which);

/// Direction of the gradient of the inner potential at y (body frame), and the number of planes
/// active there; if y is inside the inner potential (gradient zero), the normal of the nearest
/// plane with `active` = 0.
/// @param s the block's shape
/// @param y the point, body frame
/// @param active set, when not null, to the number of active planes
/// @return the unit normal: the gradient's direction, or the nearest plane's normal
Vec3 potentialBlockNormal(const PotentialBlockShape& s, const Vec3& y, int* active);
} // namespace talus::dem
