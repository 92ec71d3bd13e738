#pragma once

// The motion part of Yade's visco-elastic law: the velocity of body 1 relative to body 2 at the
// contact point and the arms from the bodies' centres to it, the law's own (not ScGeom's
// incident velocity with the radii as arms).
#include "dem/core/Cell.h"
#include "dem/laws/ContactLaw.h"

namespace talus::dem::parts
{
/// Velocity v of body 1 relative to body 2 (or its periodic image) at the contact point, and the
/// arms c1x, c2x from their centres to it; vn its normal part (> 0 approaching), vs its
/// tangential part. The contact point is Yade's: against a wall, the
/// sphere's centre projected on the wall's plane (Yade's Ig2_Wall_Sphere_ScGeom), not
/// mid-overlap.
struct ContactPointMotion
{
  Vec3 point, c1x, c2x, v, vs;
  double vn;
  /// @param c the contact, its geometry of this step
  /// @param cell the periodic cell, or null
  ContactPointMotion(const Contact& c, const Bodies& b, const Cell* cell)
  {
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    Vec3 shift2 = Vec3::Zero(), shiftVel = Vec3::Zero();
    if (cell && c.cellDist != Eigen::Vector3i::Zero())
    {
      shift2 = cell->shift(c.cellDist);
      shiftVel = cell->shiftVelocity(c.cellDist);
    }
    point = c.contactPoint;
    if (c.kind == ContactGeometryKind::WallSphere)
    {
      const int axis = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])].axis;
      point = b.pos[i2] + shift2;
      point[axis] = b.pos[i1][axis];
    }
    c1x = point - b.pos[i1];
    c2x = point - b.pos[i2] - shift2;
    v = (b.vel[i1] + b.angVel[i1].cross(c1x)) - (b.vel[i2] + shiftVel + b.angVel[i2].cross(c2x));
    vn = c.normal.dot(v);
    vs = v - vn * c.normal;
  }
  /// The law's part: the forces act at this point (the bodies' torques take it).
  /// @param c the contact; its contactPoint is moved to the law's point
  /// @param step the bodies and the cell
  ContactPointMotion(Contact& c, const StepContext& step) : ContactPointMotion(c, step.bodies, step.cell)
  {
    c.contactPoint = point;
  }
};
} // namespace talus::dem::parts
