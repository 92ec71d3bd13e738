#pragma once

#include "dem/base/types.h"

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

/// The Potential Blocks' default solver tolerance (see potentialBlockContact).
constexpr double defaultBlockAccuracyTol = 1e-10;

/// Settings of the Potential Blocks' contact geometry (attributes of Yade's Ig2_PB_PB_ScGeom),
/// shared by every block contact of a scene. They come from the engines (O.engines), so
/// checkpoints do not store them.
struct BlockContactSettings
{
  /// Yade's 2D mode (twoDimension): the blocks are prisms along `twoDdir` (unit), and the
  /// contact area is the joint length, the overlap region's chord through the contact point
  /// along normal x twoDdir, times `unitWidth2D` (the seed's contactArea = jointLength x
  /// unitWidth2D).
  bool twoDimension = false;
  Vec3 twoDdir = Vec3::UnitY();
  double unitWidth2D = 1;
  /// The overlap is the polyhedra's penetration depth (the shortest translation of one that
  /// separates them) and the normal its direction, instead of Yade's chord through the
  /// analytic centre along the inner potentials' normal (the seed's definition, which gives
  /// about half the depth for an edge-edge contact).
  bool exactDepth = false;
  /// The analytic centre's stopping Newton decrement (Ig2_PB_PB_ScGeom.accuracyTol; Yade's is
  /// the tolerance of its conic solver).
  double accuracyTol = defaultBlockAccuracyTol;
};

/// Settings of the Potential Particles' contact geometry (Yade's Ig2_PP_PP_ScGeom), from the
/// engines as the blocks' are.
struct ParticleContactSettings
{
  /// 2D mode, as the blocks' (the seed's contactArea = jointLength x unitWidth2D): the contact
  /// area is the overlap region's chord through the contact point along normal x twoDdir,
  /// times `unitWidth2D`.
  bool twoDimension = false;
  Vec3 twoDdir = Vec3::UnitY();
  double unitWidth2D = 1;
};
} // namespace talus::dem
