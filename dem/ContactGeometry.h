#pragma once

#include "dem/Bodies.h"
#include "dem/Cell.h"
#include "dem/Contacts.h"
#include "dem/PotentialBlockContact.h"
#include "dem/PotentialParticleContact.h"

#include <array>
#include <cmath>

namespace talus::dem
{
/// Closest point of triangle (a, b, c) to p, by the Voronoi region of p: a vertex, an edge or
/// the face (Ericson, Real-Time Collision Detection, 5.1.5). `inFace` (optional) tells whether
/// it lies inside the face rather than on an edge or a vertex.
inline Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, bool* inFace = nullptr)
{
  if (inFace)
    *inFace = false;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  if (inFace)
    *inFace = true;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// World coordinates of a facet's vertices.
inline std::array<Vec3, 3> facetVertices(const Bodies& b, std::size_t i)
{
  const FacetShape& f = b.facets[static_cast<std::size_t>(b.shapeIndex[i])];
  return {b.pos[i] + b.ori[i] * f.vertices[0], b.pos[i] + b.ori[i] * f.vertices[1], b.pos[i] + b.ori[i] * f.vertices[2]};
}

/// Velocity of body 2 relative to body 1 at the contact (geometry already set: c.refR1,
/// c.refR2, c.contactPoint; `normal` the current normal, `shiftVel` the velocity of body 2's
/// periodic image relative to body 2). As Yade's ScGeom::getIncidentVel: sphere-sphere and
/// wall-sphere contacts use the lever arms refR1 n and -refR2 n (avoidGranularRatcheting, and
/// a wall's noRatch); facet- and box-sphere contacts the true arms to the contact point, so a
/// boundary turned by a kinematic engine shears its contacts with its velocity there.
inline Vec3 incidentVelocity(const Contact& c, const Bodies& b, const Vec3& normal, const Vec3& shiftVel)
{
  const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
  if (c.kind == ContactGeometryKind::SphereSphere || c.kind == ContactGeometryKind::WallSphere)
    return (b.vel[i2] + shiftVel + b.angVel[i2].cross(-c.refR2 * normal)) - (b.vel[i1] + b.angVel[i1].cross(c.refR1 * normal));
  return (b.vel[i2] + b.angVel[i2].cross(c.contactPoint - b.pos[i2]))
         - (b.vel[i1] + b.angVel[i1].cross(c.contactPoint - b.pos[i1]));
}

/// Contact kinematics of Yade's ScGeom, for one candidate pair.
///
/// Computes normal, penetration depth and contact point; if the shapes do not overlap the
/// contact is reset (history forgotten) and false is returned. For a contact that was already
/// real, the stored shear force is first rotated with the contact frame: by the change of the
/// normal (n_old x n_new) and by the mean spin about the normal (dt/2 n.(w1 + w2)), to first
/// order as in the seed's "Shear deformation". The shear increment is the tangential part of
/// the incident velocity at the contact times dt, with lever arms refR1 n and -refR2 n (Yade's
/// avoidGranularRatcheting default; for facets, as Yade, the arms to the contact point).
/// `cell` is the periodic cell, or null when space is not periodic. `x`: the contact's extra
/// state, if any: a real contact with an unbroken bond stays real when the shapes separate
/// (with a negative penetration), and its incremental moments turn with the frame as the shear
/// force does.
inline bool updateContactGeometry(Contact& c, const Bodies& b, const Cell* cell, double dt, ContactExtra* x = nullptr)
{
  const bool holds = x != nullptr && !x->cohesionBroken && c.real;
  const auto i1 = static_cast<std::size_t>(c.id1);
  const auto i2 = static_cast<std::size_t>(c.id2);
  Vec3 normal;
  double penetration;
  Vec3 contactPoint;
  double r1, r2;
  Vec3 shiftVel = Vec3::Zero();
  if (cell)
  {
    c.shift2 = cell->shift(c.cellDist);
    shiftVel = cell->shiftVelocity(c.cellDist);
  }
  if (c.kind == ContactGeometryKind::SphereSphere)
  {
    const Vec3 d = b.pos[i2] + c.shift2 - b.pos[i1];
    r1 = b.radius[i1];
    r2 = b.radius[i2];
    const double dist2 = d.squaredNorm();
    const double reach = r1 + r2;
    if (dist2 > reach * reach && !holds)
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
  else if (c.kind == ContactGeometryKind::FacetSphere)
  {
    // Body 1 is the facet. The normal points from the closest point of the triangle (on its
    // face, an edge or a vertex) to the sphere's centre; as in Yade, the facet's reference
    // radius is the sphere's diameter.
    const std::array<Vec3, 3> v = facetVertices(b, i1);
    const double r = b.radius[i2];
    bool inFace = false;
    const Vec3 d = b.pos[i2] - closestPointOnTriangle(b.pos[i2], v[0], v[1], v[2], &inFace);
    const double dist2 = d.squaredNorm();
    if (dist2 > r * r && !holds)
    {
      if (c.real)
        c.reset();
      return false;
    }
    const double dist = std::sqrt(dist2);
    const Vec3 faceNormal = b.ori[i1] * b.facets[static_cast<std::size_t>(b.shapeIndex[i1])].normal;
    if (inFace) // exactly the face's normal, on the sphere's side (previous side if on the plane)
      normal = (d.dot(faceNormal) > 0 || (d.dot(faceNormal) == 0 && c.real && c.normal.dot(faceNormal) > 0)) ? faceNormal : Vec3(-faceNormal);
    else if (dist > 0)
      normal = d / dist;
    else // centre exactly on an edge or a vertex: take the face's normal
      normal = faceNormal;
    penetration = r - dist;
    contactPoint = b.pos[i2] - (r - 0.5 * penetration) * normal;
    r1 = 2 * r;
    r2 = r;
    // Yade's Ig2_Facet_Sphere_ScGeom takes the arms to the contact point (no ratcheting
    // correction): the same here, so that friction on facet walls is Yade's.
  }
  else if (c.kind == ContactGeometryKind::BoxSphere)
  {
    // Body 1 is the box (Yade's Ig2_Box_Sphere_ScGeom). Outside the box, the normal points from
    // the closest point of the box (on a face, an edge or a corner) to the sphere's centre; with
    // the centre inside, from the nearest face, penetration r + depth below that face.
    const double r = b.radius[i2];
    const Vec3 extents = b.boxes[static_cast<std::size_t>(b.shapeIndex[i1])].extents;
    const Vec3 local = b.ori[i1].conjugate() * (b.pos[i2] - b.pos[i1]);
    const Vec3 clamped = local.cwiseMax(-extents).cwiseMin(extents);
    if (clamped != local)
    {
      const Vec3 d = b.ori[i1] * (local - clamped);
      const double dist2 = d.squaredNorm();
      if (dist2 > r * r)
      {
        if (c.real)
          c.reset();
        return false;
      }
      const double dist = std::sqrt(dist2);
      normal = d / dist;
      penetration = r - dist;
    }
    else
    {
      int axis = 0;
      const Vec3 depth = extents - local.cwiseAbs();
      depth.minCoeff(&axis);
      Vec3 n = Vec3::Zero();
      n[axis] = local[axis] >= 0 ? 1.0 : -1.0;
      normal = b.ori[i1] * n;
      penetration = r + depth[axis];
    }
    contactPoint = b.pos[i2] - (r - 0.5 * penetration) * normal;
    r1 = 2 * r;
    r2 = r;
  }
  else if (c.kind == ContactGeometryKind::BlockBlock || c.kind == ContactGeometryKind::WallBlock
           || c.kind == ContactGeometryKind::ParticleParticle || c.kind == ContactGeometryKind::WallParticle)
  {
    // Potential Blocks and Particles (out of line: see PotentialBlockContact.h and
    // PotentialParticleContact.h); reference radii are their R, the overlap section's area goes
    // to the contact's extra state for the KnKs laws.
    ConvexContactGeometry g;
    const bool blocks = c.kind == ContactGeometryKind::BlockBlock || c.kind == ContactGeometryKind::WallBlock;
    const Vec3* previous = c.real ? &c.contactPoint : nullptr;
    if (!(blocks ? potentialBlockContact(b, i1, i2, previous, g) : potentialParticleContact(b, i1, i2, previous, g)))
    {
      if (c.real)
        c.reset();
      return false;
    }
    normal = g.normal;
    penetration = g.penetration;
    contactPoint = g.contactPoint;
    auto R = [&](std::size_t i) {
      const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
      return blocks ? b.blocks[s].R : b.particles[s].R;
    };
    r2 = R(i2);
    r1 = b.shape[i1] == ShapeKind::Wall ? r2 : R(i1);
    if (x)
      x->contactArea = g.area;
  }
  else // WallSphere: body 1 is the wall
  {
    const WallShape& wall = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])];
    const double r = b.radius[i2];
    const double d = b.pos[i2][wall.axis] - b.pos[i1][wall.axis];
    const double side = wall.sense != 0 ? wall.sense : (d >= 0 ? 1.0 : -1.0);
    penetration = r - side * d;
    if (penetration < 0 && !holds)
    {
      if (c.real)
        c.reset();
      return false;
    }
    normal = Vec3::Zero();
    normal[wall.axis] = side;
    // Mid-overlap, as for the other shapes: the sphere's torque arm r - penetration / 2 is
    // Yade's (its Law2 takes the arms of spheres, not the wall-plane point Ig2 stores).
    contactPoint = b.pos[i2] - (r - 0.5 * penetration) * normal;
    r1 = r2 = r;
  }

  if (c.real)
  {
    const Vec3 orthonormalAxis = c.normal.cross(normal);
    const Vec3 twistAxis = (0.5 * dt * c.normal.dot(b.angVel[i1] + b.angVel[i2])) * c.normal;
    c.shearForce -= c.shearForce.cross(orthonormalAxis);
    c.shearForce -= c.shearForce.cross(twistAxis);
    if (x)
      for (Vec3* moment : {&x->momentBending, &x->momentTwist})
      {
        *moment -= moment->cross(orthonormalAxis);
        *moment -= moment->cross(twistAxis);
      }
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
  // Between two spheres, and between a wall and a sphere (whose "radius" is the sphere's), the
  // translational part is scaled by alpha = (r1 + r2) / (r1 + r2 - u), as Yade's
  // avoidGranularRatcheting and noRatch (McNamara et al.), so that rolling without sliding gives
  // no shear increment.
  Vec3 incident;
  if (c.kind == ContactGeometryKind::SphereSphere || c.kind == ContactGeometryKind::WallSphere)
  {
    const double alpha = (r1 + r2) / (r1 + r2 - penetration);
    incident = alpha * (b.vel[i2] + shiftVel - b.vel[i1]) + b.angVel[i2].cross(-r2 * normal) - b.angVel[i1].cross(r1 * normal);
  }
  else
    incident = incidentVelocity(c, b, normal, shiftVel);
  c.shearIncrement = (incident - normal.dot(incident) * normal) * dt;
  return true;
}

/// The same for a contact whose geometry is up to date.
inline Vec3 incidentVelocity(const Contact& c, const Bodies& b, const Vec3& shiftVel)
{
  return incidentVelocity(c, b, c.normal, shiftVel);
}

} // namespace talus::dem
