#pragma once

#include "dem/core/Bodies.h"
#include "dem/core/Cell.h"
#include "dem/core/Contacts.h"
#include "dem/contact/PotentialBlockContact.h"
#include "dem/contact/PotentialParticleContact.h"
#include "dem/contact/SphereTouch.h"

#include <array>
#include <cmath>

namespace talus::dem
{
/// Closest point of triangle (a, b, c) to p, by the Voronoi region of p: a vertex, an edge or
/// the face (Ericson, Real-Time Collision Detection, 5.1.5). `inFace` (optional) tells whether
/// it lies inside the face rather than on an edge or a vertex.
/// @param p the point
/// @param a, b, c the triangle's vertices
/// @param inFace set, when not null, to whether the point lies inside the face
/// @return the closest point of the triangle
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
/// @param i the facet body's id
/// @return the three vertices (m), in the order given to addFacet
inline std::array<Vec3, 3> facetVertices(const Bodies& b, std::size_t i)
{
  const FacetShape& f = b.facets[static_cast<std::size_t>(b.shapeIndex[i])];
  return {b.pos[i] + b.ori[i] * f.vertices[0], b.pos[i] + b.ori[i] * f.vertices[1], b.pos[i] + b.ori[i] * f.vertices[2]};
}

/// Velocity of body 2 relative to body 1 at the contact (geometry already set: c.refR1,
/// c.refR2, c.contactPoint; `normal` the current normal; `shift2` and `shiftVel` the position
/// and velocity of body 2's periodic image relative to body 2). As Yade's
/// ScGeom::getIncidentVel: sphere-sphere and wall-sphere contacts use the lever arms refR1 n
/// and -refR2 n (avoidGranularRatcheting, and a wall's noRatch); facet- and box-sphere contacts
/// the true arms to the contact point, so a boundary turned by a kinematic engine shears its
/// contacts with its velocity there.
/// @param normal the current unit normal, from body 1 to body 2
/// @param shift2, shiftVel body 2's periodic image's offset (m) and velocity (m/s) relative to
///        body 2; zero outside a periodic cell
/// @return the relative velocity (m/s), world frame
inline Vec3 incidentVelocity(const Contact& c, const Bodies& b, const Vec3& normal, const Vec3& shift2, const Vec3& shiftVel)
{
  const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
  if (c.kind == ContactGeometryKind::SphereSphere || c.kind == ContactGeometryKind::WallSphere)
    return (b.vel[i2] + shiftVel + b.angVel[i2].cross(-c.refR2 * normal)) - (b.vel[i1] + b.angVel[i1].cross(c.refR1 * normal));
  return (b.vel[i2] + shiftVel + b.angVel[i2].cross(c.contactPoint - (b.pos[i2] + shift2)))
         - (b.vel[i1] + b.angVel[i1].cross(c.contactPoint - b.pos[i1]));
}

/// Overlap of a pair whose body 1 is not a sphere (wall, facet, box, Potential Block or Particle; the
/// routines of Yade's Ig2 functors, out of line: they are the rarer pairs). Sets the normal
/// (from body 1 to body 2), penetration depth, contact point and reference radii; false if the
/// shapes are apart and `holds` (an unbroken bond) does not keep the contact. `shift2`: where
/// body 2's periodic image is relative to body 2 (a sphere meeting a facet or box across the
/// boundary of a periodic cell; zero otherwise). The overlap section's area of Potential
/// Blocks and Particles goes to `x` when given.
/// @param holds an unbroken bond keeps the contact real when the shapes are apart
/// @param x the contact's extra state (the overlap's area is written there), or null
/// @param shift2 body 2's periodic image's offset (m), zero outside a periodic cell
/// @param normal, penetration, contactPoint, r1, r2 written when the shapes touch (or the bond
///        holds)
/// @return whether the contact is (still) real
bool nonSphereOverlap(const Contact& c, const Bodies& b, bool holds, ContactExtra* x, const Vec3& shift2, Vec3& normal,
                      double& penetration, Vec3& contactPoint, double& r1, double& r2);

/// Contact kinematics of Yade's ScGeom, for one candidate pair.
///
/// Computes normal, penetration depth and contact point; if the shapes do not overlap the
/// contact is reset (history forgotten) and false is returned (two spheres: Yade's tests to the
/// bit, one to begin and one to hold on, see SphereTouch.h). For a contact that was already
/// real, the stored shear force is first rotated with the contact frame: by the change of the
/// normal (n_old x n_new) and by the mean spin about the normal (dt/2 n.(w1 + w2)), to first
/// order as in the seed's "Shear deformation". The shear increment is the tangential part of
/// the incident velocity at the contact times dt, with lever arms refR1 n and -refR2 n (Yade's
/// avoidGranularRatcheting default; for facets, as Yade, the arms to the contact point).
/// `cell` is the periodic cell, or null when space is not periodic. `x`: the contact's extra
/// state, if any: a real contact with an unbroken bond stays real when the shapes separate
/// (with a negative penetration), and its incremental moments turn with the frame as the shear
/// force does.
///
/// `SpheresOnly`: the caller knows the pair is two spheres, in a periodic scene or not — the hot
/// path of dense granular runs, whose code carries no test of other shapes (inlined where the
/// caller passes a null `x`, nor of bonds and moments). Both forms do the same arithmetic in the
/// same order, so they give the same bits.
/// @param c the contact, its geometry and shear force updated (reset when the shapes are apart)
/// @param cell the periodic cell, or null
/// @param dt the time step (s)
/// @param x the contact's extra state, or null
/// @param turnMoments x's moments turn with the frame; false when the law sets them afresh from
///        the rotations (the total form of the cohesive law's, rolling resistance), which spares
///        the read of their cache lines
/// @return whether the contact is real after the update
template <bool SpheresOnly = false>
[[gnu::always_inline]] inline bool contactGeometry(Contact& c, const Bodies& b, const Cell* cell, double dt, ContactExtra* x,
                                                   bool turnMoments = true)
{
  const bool holds = x != nullptr && !x->cohesionBroken && c.real;
  const auto i1 = static_cast<std::size_t>(c.id1);
  const auto i2 = static_cast<std::size_t>(c.id2);
  Vec3 normal;
  double penetration;
  Vec3 contactPoint;
  double r1, r2;
  Vec3 shift2 = Vec3::Zero(), shiftVel = Vec3::Zero();
  // Only a pair across the boundary sees an image: the others (most) skip two matrix products.
  if (cell && c.cellDist != Eigen::Vector3i::Zero())
  {
    shift2 = cell->shift(c.cellDist);
    shiftVel = cell->shiftVelocity(c.cellDist);
  }
  const bool spheres = SpheresOnly || c.kind == ContactGeometryKind::SphereSphere;
  if (spheres)
  {
    const Vec3 d = b.pos[i2] + shift2 - b.pos[i1];
    r1 = b.radius[i1];
    r2 = b.radius[i2];
    const double dist2 = yadeSquaredNorm(d);
    const double reach = r1 + r2;
    if (!c.real && !spheresBegin(dist2, reach))
      return false;
    const double dist = std::sqrt(dist2);
    penetration = reach - dist;
    if (!spheresHold(penetration) && !holds)
    {
      c.reset();
      return false;
    }
    normal = d / dist;
    contactPoint = b.pos[i1] + (r1 - 0.5 * penetration) * normal;
  }
  else if (!nonSphereOverlap(c, b, holds, x, shift2, normal, penetration, contactPoint, r1, r2))
  {
    if (c.real)
      c.reset();
    return false;
  }

  if (c.real)
  {
    const Vec3 orthonormalAxis = c.normal.cross(normal);
    const Vec3 twistAxis = (0.5 * dt * c.normal.dot(b.angVel[i1] + b.angVel[i2])) * c.normal;
    c.shearForce -= c.shearForce.cross(orthonormalAxis);
    c.shearForce -= c.shearForce.cross(twistAxis);
    if (x && turnMoments)
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
  if (spheres || c.kind == ContactGeometryKind::WallSphere)
  {
    const double alpha = (r1 + r2) / (r1 + r2 - penetration);
    incident = alpha * (b.vel[i2] + shiftVel - b.vel[i1]) + b.angVel[i2].cross(-r2 * normal) - b.angVel[i1].cross(r1 * normal);
  }
  else
    incident = incidentVelocity(c, b, normal, shift2, shiftVel);
  c.shearIncrement = (incident - normal.dot(incident) * normal) * dt;
  return true;
}

/// contactGeometry for any pair (out of line where the compiler chooses).
/// @param c the contact, its geometry and shear force updated
/// @param cell the periodic cell, or null
/// @param dt the time step (s)
/// @param x the contact's extra state, or null
/// @param turnMoments x's moments turn with the frame (see contactGeometry)
/// @return whether the contact is real after the update
inline bool updateContactGeometry(Contact& c, const Bodies& b, const Cell* cell, double dt, ContactExtra* x = nullptr,
                                  bool turnMoments = true)
{
  return contactGeometry<false>(c, b, cell, dt, x, turnMoments);
}

/// The same for a contact whose geometry is up to date (`cell`: the periodic cell, or null).
/// @return the relative velocity (m/s), world frame
inline Vec3 incidentVelocity(const Contact& c, const Bodies& b, const Cell* cell)
{
  if (cell && c.cellDist != Eigen::Vector3i::Zero())
    return incidentVelocity(c, b, c.normal, cell->shift(c.cellDist), cell->shiftVelocity(c.cellDist));
  return incidentVelocity(c, b, c.normal, Vec3::Zero(), Vec3::Zero());
}

} // namespace talus::dem
