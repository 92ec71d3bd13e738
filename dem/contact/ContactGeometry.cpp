#include "dem/contact/ContactGeometry.h"

namespace talus::dem
{
bool nonSphereOverlap(const Contact& c, const Bodies& b, bool holds, ContactExtra* x, const Vec3& shift2, Vec3& normal,
                      double& penetration, Vec3& contactPoint, double& r1, double& r2)
{
  const auto i1 = static_cast<std::size_t>(c.id1);
  const auto i2 = static_cast<std::size_t>(c.id2);
  if (c.kind == ContactGeometryKind::FacetSphere)
  {
    // Body 1 is the facet. The normal points from the closest point of the triangle (on its
    // face, an edge or a vertex) to the sphere's centre; as in Yade, the facet's reference
    // radius is the sphere's diameter. Yade's Ig2_Facet_Sphere_ScGeom takes the arms to the
    // contact point (no ratcheting correction): the same here, so that friction on facet walls
    // is Yade's.
    const std::array<Vec3, 3> v = facetVertices(b, i1);
    const double r = b.radius[i2];
    const Vec3 centre = b.pos[i2] + shift2;
    bool inFace = false;
    const Vec3 d = centre - closestPointOnTriangle(centre, v[0], v[1], v[2], &inFace);
    const double dist2 = d.squaredNorm();
    if (dist2 > r * r && !holds)
      return false;
    const double dist = std::sqrt(dist2);
    const Vec3 faceNormal = b.ori[i1] * b.facets[static_cast<std::size_t>(b.shapeIndex[i1])].normal;
    if (inFace) // exactly the face's normal, on the sphere's side (previous side if on the plane)
      normal = (d.dot(faceNormal) > 0 || (d.dot(faceNormal) == 0 && c.real && c.normal.dot(faceNormal) > 0)) ? faceNormal : Vec3(-faceNormal);
    else if (dist > 0)
      normal = d / dist;
    else // centre exactly on an edge or a vertex: take the face's normal
      normal = faceNormal;
    penetration = r - dist;
    contactPoint = centre - (r - 0.5 * penetration) * normal;
    r1 = 2 * r;
    r2 = r;
    return true;
  }
  if (c.kind == ContactGeometryKind::BoxSphere)
  {
    // Body 1 is the box (Yade's Ig2_Box_Sphere_ScGeom). Outside the box, the normal points from
    // the closest point of the box (on a face, an edge or a corner) to the sphere's centre; with
    // the centre inside, from the nearest face, penetration r + depth below that face.
    const double r = b.radius[i2];
    const Vec3 extents = b.boxes[static_cast<std::size_t>(b.shapeIndex[i1])].extents;
    const Vec3 centre = b.pos[i2] + shift2;
    const Vec3 local = b.ori[i1].conjugate() * (centre - b.pos[i1]);
    const Vec3 clamped = local.cwiseMax(-extents).cwiseMin(extents);
    if (clamped != local)
    {
      const Vec3 d = b.ori[i1] * (local - clamped);
      const double dist2 = d.squaredNorm();
      if (dist2 > r * r)
        return false;
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
    contactPoint = centre - (r - 0.5 * penetration) * normal;
    r1 = r; // Yade's Ig2_Box_Sphere_ScGeom gives both sides the sphere's radius (a facet, 2r)
    r2 = r;
    return true;
  }
  if (c.kind == ContactGeometryKind::BlockBlock || c.kind == ContactGeometryKind::WallBlock
      || c.kind == ContactGeometryKind::ParticleParticle || c.kind == ContactGeometryKind::WallParticle)
  {
    // Potential Blocks and Particles (see PotentialBlockContact.h and
    // PotentialParticleContact.h); reference radii are their R, the overlap section's area goes
    // to the contact's extra state for the KnKs laws.
    ConvexContactGeometry g;
    const bool blocks = c.kind == ContactGeometryKind::BlockBlock || c.kind == ContactGeometryKind::WallBlock;
    const Vec3* previous = c.real ? &c.contactPoint : nullptr;
    if (!(blocks ? potentialBlockContact(b, i1, i2, previous, g, b.blockContact.accuracyTol)
                 : potentialParticleContact(b, i1, i2, previous, g)))
      return false;
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
    return true;
  }
  // WallSphere: body 1 is the wall.
  const WallShape& wall = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])];
  const double r = b.radius[i2];
  const double d = b.pos[i2][wall.axis] - b.pos[i1][wall.axis];
  const double side = wall.sense != 0 ? wall.sense : (d >= 0 ? 1.0 : -1.0);
  penetration = r - side * d;
  if (penetration < 0 && !holds)
    return false;
  normal = Vec3::Zero();
  normal[wall.axis] = side;
  // Mid-overlap, as for the other shapes: the sphere's torque arm r - penetration / 2 is Yade's
  // (its Law2 takes the arms of spheres, not the wall-plane point Ig2 stores).
  contactPoint = b.pos[i2] - (r - 0.5 * penetration) * normal;
  r1 = r2 = r;
  return true;
}
} // namespace talus::dem
