#pragma once

#include "dem/Bodies.h"
#include "dem/Contacts.h"

#include <cmath>

namespace talus::dem
{
/// Contact kinematics of Yade's ScGeom, for one candidate pair.
///
/// Computes normal, penetration depth and contact point; if the shapes do not overlap the
/// contact is reset (history forgotten) and false is returned. For a contact that was already
/// real, the stored shear force is first rotated with the contact frame: by the change of the
/// normal (n_old x n_new) and by the mean spin about the normal (dt/2 n.(w1 + w2)), to first
/// order as in the seed's "Shear deformation". The shear increment is the tangential part of
/// the incident velocity at the contact times dt, with lever arms refR1 n and -refR2 n (Yade's
/// avoidGranularRatcheting default).
inline bool updateContactGeometry(Contact& c, const Bodies& b, double dt)
{
  const auto i1 = static_cast<std::size_t>(c.id1);
  const auto i2 = static_cast<std::size_t>(c.id2);
  Vec3 normal;
  double penetration;
  Vec3 contactPoint;
  double r1, r2;
  if (c.kind == ContactGeometryKind::SphereSphere)
  {
    const Vec3 d = b.pos[i2] - b.pos[i1];
    r1 = b.radius[i1];
    r2 = b.radius[i2];
    const double dist2 = d.squaredNorm();
    const double reach = r1 + r2;
    if (dist2 > reach * reach)
    {
      if (c.real)
        c.reset();
      return false;
    }
    const double dist = std::sqrt(dist2);
    penetration = reach - dist;
    normal = d / dist;
    contactPoint = b.pos[i1] + (r1 - 0.5 * penetration) * normal;
  }
  else // WallSphere: body 1 is the wall; the contact point lies on the wall plane
  {
    const WallShape& wall = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])];
    const double r = b.radius[i2];
    const double d = b.pos[i2][wall.axis] - b.pos[i1][wall.axis];
    const double side = wall.sense != 0 ? wall.sense : (d >= 0 ? 1.0 : -1.0);
    penetration = r - side * d;
    if (penetration < 0)
    {
      if (c.real)
        c.reset();
      return false;
    }
    normal = Vec3::Zero();
    normal[wall.axis] = side;
    contactPoint = b.pos[i2] - (r - penetration) * normal;
    r1 = r2 = r;
  }

  if (c.real)
  {
    const Vec3 orthonormalAxis = c.normal.cross(normal);
    const Vec3 twistAxis = (0.5 * dt * c.normal.dot(b.angVel[i1] + b.angVel[i2])) * c.normal;
    c.shearForce -= c.shearForce.cross(orthonormalAxis);
    c.shearForce -= c.shearForce.cross(twistAxis);
    c.fresh = false;
  }
  else
  {
    c.real = true;
    c.fresh = true;
    c.shearForce.setZero();
  }
  c.normal = normal;
  c.penetration = penetration;
  c.contactPoint = contactPoint;
  c.refR1 = r1;
  c.refR2 = r2;
  const Vec3 incident = (b.vel[i2] + b.angVel[i2].cross(-r2 * normal)) - (b.vel[i1] + b.angVel[i1].cross(r1 * normal));
  c.shearIncrement = (incident - normal.dot(incident) * normal) * dt;
  return true;
}

/// The relative velocity of body 2 with respect to body 1 at the contact (same arms as above).
inline Vec3 incidentVelocity(const Contact& c, const Bodies& b)
{
  const auto i1 = static_cast<std::size_t>(c.id1);
  const auto i2 = static_cast<std::size_t>(c.id2);
  return (b.vel[i2] + b.angVel[i2].cross(-c.refR2 * c.normal)) - (b.vel[i1] + b.angVel[i1].cross(c.refR1 * c.normal));
}

/// Store the total force on body 2 (`force2`) and the torques it exerts about both centres,
/// applied at the contact point.
inline void setContactForce(Contact& c, const Bodies& b, const Vec3& force2)
{
  c.force = force2;
  c.torque1 = (c.contactPoint - b.pos[static_cast<std::size_t>(c.id1)]).cross(-force2);
  c.torque2 = (c.contactPoint - b.pos[static_cast<std::size_t>(c.id2)]).cross(force2);
}
} // namespace talus::dem
