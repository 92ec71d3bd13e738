#pragma once

#include "dem/types.h"

namespace talus::dem
{
/// Geometry of a contact between convex shapes given by planes (Potential Blocks, Potential
/// Particles) or between such a shape and a wall: Yade's ScGeom plus the contact area of the
/// KnKs laws.
struct ConvexContactGeometry
{
  Vec3 normal;       ///< unit, from body 1 to body 2
  Vec3 contactPoint; ///< middle of the overlap region's chord along the normal
  double penetration = 0; ///< length of that chord (Yade's penetrationDepth)
  double area = 0;   ///< area of the overlap region's section normal to `normal` through the contact point
  int lpSolves = 0;  ///< linear programs solved (Potential Blocks; 0 when a cheaper interior point was found)
};
} // namespace talus::dem
