#pragma once

// Rock joints of Potential Blocks (Yade's KnKsPBPhys with useFaceProperties): a contact between
// two intact-rock faces (BlockGen's rock bridges and cemented joints) is a bond (BondState in
// core/ContactExtra.h) with a cohesion and a tensile strength until it breaks: which blocks
// and faces a contact joins, and the bond a new contact gets (the law's physics makes it; the
// joint's normal spring, JointSpring.h, and its shear, JointCoulomb.h, act on it).
#include "dem/laws/ContactLaw.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace talus::dem::parts
{
/// The Potential Block shape of body i.
/// @param i a Potential Block's body id
/// @return its shape, stored in `b`
inline const PotentialBlockShape& blockOf(const Bodies& b, std::size_t i)
{
  return b.blocks[static_cast<std::size_t>(b.shapeIndex[i])];
}

/// Body i is a boundary block (Yade's isBoundary: its own stiffnesses kn_i, ks_i, no bond).
/// @param i any body id
/// @return false for bodies that are not Potential Blocks
inline bool isBoundaryBlock(const Bodies& b, std::size_t i)
{
  return b.shape[i] == ShapeKind::PotentialBlock && blockOf(b, i).isBoundary;
}

/// The face of block s (orientation ori) whose outward normal is within 1 degree of `outward`,
/// or -1.
/// @param s the block's shape
/// @param ori the block's orientation
/// @param outward a unit direction, world frame
/// @return the face's plane index, or -1
inline int contactFace(const PotentialBlockShape& s, const Quat& ori, const Vec3& outward)
{
  const Vec3 local = ori.conjugate() * outward;
  const double cosLimit = std::cos(std::numbers::pi / 180);
  for (std::size_t k = 0; k < s.normals.size(); ++k)
    if (s.normals[k].dot(local) > cosLimit)
      return static_cast<int>(k);
  return -1;
}

/// The bond of a new contact of this area (A0, kept: the section through the contact point
/// shrinks as the overlap turns into a wedge when a block tilts, and a bridge's strength must
/// not follow it): with useFaceProperties, the contact's face on each block (+n for body 1, -n
/// for body 2) both intact rock gives a bond of the smaller cohesion and tension times A0, its
/// flags as given (Yade's functor's cohesionBroken, tensionBroken); anything else (an edge or
/// a corner, a wall, a boundary block) is frictional.
/// @param x the new contact's state: intactRock, strengths and flags set
/// @param area the contact's area A0 (m^2)
/// @param useFaceProperties the physics' option: faces' cohesion and tension used at all
/// @param cohesionBroken, tensionBroken the flags a bond starts with
inline void bondFaces(const Contact& c, ContactExtra& x, const Bodies& b, double area, bool useFaceProperties,
                      bool cohesionBroken, bool tensionBroken)
{
  x.intactRock = 0;
  x.cohesionBroken = x.tensionBroken = 1;
  x.shearAdhesion = x.normalAdhesion = 0;
  if (!useFaceProperties || c.kind != ContactGeometryKind::BlockBlock)
    return;
  const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
  if (isBoundaryBlock(b, i1) || isBoundaryBlock(b, i2))
    return;
  const PotentialBlockShape& s1 = blockOf(b, i1);
  const PotentialBlockShape& s2 = blockOf(b, i2);
  const int f1 = contactFace(s1, b.ori[i1], c.normal), f2 = contactFace(s2, b.ori[i2], -c.normal);
  if (f1 < 0 || f2 < 0)
    return;
  const auto p1 = static_cast<std::size_t>(f1), p2 = static_cast<std::size_t>(f2);
  if (!(s1.intactRock[p1] && s2.intactRock[p2]))
    return;
  x.intactRock = 1;
  x.shearAdhesion = std::min(s1.cohesion[p1], s2.cohesion[p2]) * area;
  x.normalAdhesion = std::min(s1.tension[p1], s2.tension[p2]) * area;
  x.cohesionBroken = cohesionBroken ? 1 : 0;
  x.tensionBroken = tensionBroken ? 1 : 0;
}
} // namespace talus::dem::parts
