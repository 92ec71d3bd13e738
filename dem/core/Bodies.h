#pragma once

#include "dem/shapes/ConvexContact.h"
#include "dem/shapes/PotentialBlock.h"
#include "dem/shapes/PotentialParticle.h"
#include "dem/base/types.h"

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace talus::dem
{
/// Shapes a body can have. Spheres are the fast path; other shapes add contact geometries.
enum class ShapeKind : std::uint8_t
{
  Sphere,
  Wall,  ///< infinite plane normal to a coordinate axis (Yade's Wall)
  Facet, ///< triangle (Yade's Facet), for meshes and boundaries
  Box,   ///< rectangular box (Yade's Box), interacting with spheres
  Clump, ///< rigid aggregate of member spheres (Yade's Clump); has no surface of its own
  PotentialBlock, ///< convex polyhedron from planes (Yade's PotentialBlock), with blocks and walls
  PotentialParticle, ///< rounded convex particle from planes and a sphere term (Yade's PotentialParticle), with particles and walls
};

/// Yade's class name of a shape kind ("Sphere", "PotentialBlock", ...), for messages.
/// @param kind any ShapeKind value
/// @return a static string, never null
const char* shapeName(ShapeKind kind);

/// The shape kind of a Yade class name (shapeName's inverse).
/// @param name Yade's class name, case-sensitive
/// @return the kind, or none for an unknown name
std::optional<ShapeKind> shapeKindNamed(std::string_view name);

/// An infinite wall: the plane x[axis] = pos[axis]; `sense` says which side interacts
/// (-1 negative side, +1 positive side, 0 both), as Yade's Wall.sense.
struct WallShape
{
  int axis = 2;
  int sense = 0;
};

/// A triangle. Vertices are stored relative to the body's position (Yade puts it at the
/// triangle's incentre) in the body's frame, so a facet moves and turns with its body.
struct FacetShape
{
  std::array<Vec3, 3> vertices;
  Vec3 normal; ///< unit normal, (v1 - v0) x (v2 - v0) normalised, in the body frame
  bool bounded = true; ///< false: Yade's noBound, the collider never pairs it (a factory's surface)
};

/// A box of half-sizes `extents` along the axes of the body's frame (Yade's Box.extents).
struct BoxShape
{
  Vec3 extents;
};

/// The members of a clump and their placement in the clump's principal frame (Yade's
/// Clump.members): member k sits at pos + ori * relPos[k] with orientation ori * relOri[k].
struct ClumpShape
{
  std::vector<BodyId> members; ///< ascending ids (the order forces are summed in)
  std::vector<Vec3> relPos;
  std::vector<Quat> relOri;
};

/// Every body of a scene as structure-of-arrays: index = BodyId. Arrays are contiguous, so the
/// exchange interface and Python hand out views of them without copying.
///
/// Erased bodies keep their slot (ids stay stable, as in Yade) with `alive` false.
struct Bodies
{
  // state
  std::vector<Vec3> pos, vel, angVel;
  std::vector<Quat> ori;
  /// Angular momentum (world frame) of aspherical bodies, integrated instead of the angular
  /// velocity (Yade's State.angMom with exactAsphericalRot); unused for spheres.
  std::vector<Vec3> angMom;
  // forces of the current step, and persistent external ones added by couplings or users
  std::vector<Vec3> force, torque, extForce, extTorque;
  // constant properties
  std::vector<double> mass;
  std::vector<Vec3> inertia; ///< principal moments of inertia (spheres: 2/5 m r^2)
  std::vector<double> radius; ///< sphere radius; 0 for other shapes
  std::vector<ShapeKind> shape;
  std::vector<int> shapeIndex; ///< index into `walls` or `facets`, -1 for spheres
  std::vector<int> material;   ///< index into the scene's materials
  std::vector<std::uint8_t> blockedDofs; ///< Dof bits; blocked DOFs keep their velocity
  std::vector<std::uint8_t> dynamic;     ///< 1: moved by forces; 0: moved only by its velocity
  std::vector<std::uint8_t> damped;      ///< Yade's State.isDamped; 0: NewtonIntegrator's damping leaves it alone
  std::vector<std::uint8_t> alive;
  std::vector<BodyId> clumpId; ///< the clump this body is a member of, -1 if none
  /// Yade's Body.groupMask (b.mask): two bodies may touch only if their masks share a bit
  /// (see mayCollide); engines with a `mask` act on the bodies sharing a bit with it. Default 1.
  std::vector<int> groupMask;
  /// Heat (Yade's ThermalState): temperature (K or °C, as the user's values), specific heat
  /// capacity Cp (J/(kg K)), conductivity k (W/(m K)) and linear thermal expansion coefficient
  /// alpha (1/K). NaN where not given: a scene without heat holds only NaN and nothing reads them
  /// during a step; a heat model gives its defaults to the NaN entries of the bodies it covers.
  std::vector<double> temperature, heatCapacity, conductivity, thermalExpansion;
  std::vector<WallShape> walls;
  std::vector<FacetShape> facets;
  std::vector<BoxShape> boxes;
  std::vector<ClumpShape> clumps;
  std::vector<PotentialBlockShape> blocks;
  std::vector<PotentialParticleShape> particles;
  /// How Potential Blocks touch (Ig2_PB_PB_ScGeom's settings, from the engines).
  BlockContactSettings blockContact;
  /// How Potential Particles touch (Ig2_PP_PP_ScGeom's settings, from the engines).
  ParticleContactSettings particleContact;

  /// Number of slots, erased bodies included.
  [[nodiscard]] std::size_t size() const { return pos.size(); }
  /// Append a slot with zero state and the given shape.
  /// @param kind the body's shape kind
  /// @param shapeIdx its index in the kind's array (`walls`, `facets`, ...); -1 for a sphere
  /// @param materialId index into the scene's materials
  /// @return the new body's id (the slot index)
  BodyId append(ShapeKind kind, int shapeIdx, int materialId);
  /// Set a body's angular velocity, and the angular momentum that goes with it (what the
  /// integrator advances for aspherical bodies).
  /// @param i the body's id
  /// @param w the angular velocity (rad/s, world frame)
  void setAngularVelocity(std::size_t i, const Vec3& w);
  /// Whether the collider may pair bodies i and j, for other than spatial reasons (Yade's
  /// Collider::mayCollide): not members of one clump, masks sharing a bit, and not two bodies of
  /// one mask that shares a bit with the collider's avoidSelfInteractionMask.
  /// @param i, j the bodies' ids
  /// @param avoidSelfInteractionMask the collider's (0: none)
  /// @return false if the pair must never touch
  [[nodiscard]] bool mayCollide(std::size_t i, std::size_t j, int avoidSelfInteractionMask) const
  {
    return (clumpId[i] < 0 || clumpId[i] != clumpId[j]) && masksAllow(i, j, avoidSelfInteractionMask);
  }
  /// The masks' part of mayCollide (the clump test left out, for callers that made it).
  /// @param i, j the bodies' ids
  /// @param avoidSelfInteractionMask the collider's (0: none)
  /// @return false if the masks forbid the pair
  [[nodiscard]] bool masksAllow(std::size_t i, std::size_t j, int avoidSelfInteractionMask) const
  {
    const int mi = groupMask[i], mj = groupMask[j];
    return (mi & mj) != 0 && !(mi == mj && (mi & avoidSelfInteractionMask) != 0);
  }
  /// True for bodies whose rotation integrates the angular momentum in the principal frame
  /// (clumps, boxes, blocks and potential particles with unequal principal moments, as Yade's
  /// isAspherical).
  /// @param i the body's id
  /// @return whether it rotates by the exact aspherical integration
  [[nodiscard]] bool aspherical(std::size_t i) const
  {
    return (shape[i] == ShapeKind::Clump || shape[i] == ShapeKind::Box || shape[i] == ShapeKind::PotentialBlock
            || shape[i] == ShapeKind::PotentialParticle)
           && (inertia[i][0] != inertia[i][1] || inertia[i][0] != inertia[i][2]);
  }
};
} // namespace talus::dem
