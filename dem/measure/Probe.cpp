#include "dem/measure/Probe.h"

#include "dem/contact/ContactGeometry.h"

#include <limits>

namespace talus::dem
{
std::vector<BodyId> bodiesInBox(const Scene& scene, const Vec3& lo, const Vec3& hi, double grow)
{
  const Bodies& b = scene.bodies;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<BodyId> found;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
    if (!b.alive[i] || b.shape[i] == ShapeKind::Clump || (b.shape[i] == ShapeKind::Facet && !b.facets[s].bounded))
      continue;
    Vec3 low = b.pos[i], high = b.pos[i];
    switch (b.shape[i])
    {
    case ShapeKind::Sphere: low.array() -= b.radius[i]; high.array() += b.radius[i]; break;
    case ShapeKind::Wall:
      low.setConstant(-inf);
      high.setConstant(inf);
      low[b.walls[s].axis] = high[b.walls[s].axis] = b.pos[i][b.walls[s].axis];
      break;
    case ShapeKind::Facet:
    {
      const std::array<Vec3, 3> v = facetVertices(b, i);
      low = v[0].cwiseMin(v[1]).cwiseMin(v[2]);
      high = v[0].cwiseMax(v[1]).cwiseMax(v[2]);
      break;
    }
    case ShapeKind::Box:
    {
      const Vec3 half = b.ori[i].toRotationMatrix().cwiseAbs() * b.boxes[s].extents;
      low -= half;
      high += half;
      break;
    }
    case ShapeKind::PotentialBlock:
    case ShapeKind::PotentialParticle:
    {
      const double r = b.shape[i] == ShapeKind::PotentialBlock ? b.blocks[s].boundingRadius : b.particles[s].boundingRadius;
      low.array() -= r;
      high.array() += r;
      break;
    }
    case ShapeKind::Clump: break;
    }
    low.array() -= grow;
    high.array() += grow;
    if ((low.array() <= hi.array()).all() && (high.array() >= lo.array()).all())
      found.push_back(static_cast<BodyId>(i));
  }
  return found;
}

std::vector<BodyId> bodiesTouchingSphere(const Scene& scene, const Vec3& c, double r, BodyId except)
{
  const Bodies& b = scene.bodies;
  std::vector<BodyId> touching;
  for (BodyId id : bodiesInBox(scene, c - Vec3::Constant(r), c + Vec3::Constant(r), 0.0))
  {
    const auto i = static_cast<std::size_t>(id);
    const auto s = static_cast<std::size_t>(b.shapeIndex[i]);
    double reach = r; // the largest distance from c to the body's surface that touches
    Vec3 nearest = b.pos[i];
    switch (b.shape[i])
    {
    case ShapeKind::Sphere: reach += b.radius[i]; break;
    case ShapeKind::Wall: nearest = c; nearest[b.walls[s].axis] = b.pos[i][b.walls[s].axis]; break;
    case ShapeKind::Facet:
    {
      const std::array<Vec3, 3> v = facetVertices(b, i);
      nearest = closestPointOnTriangle(c, v[0], v[1], v[2]);
      break;
    }
    case ShapeKind::Box:
    {
      const Vec3 local = b.ori[i].conjugate() * (c - b.pos[i]);
      nearest = b.pos[i] + b.ori[i] * local.cwiseMax(-b.boxes[s].extents).cwiseMin(b.boxes[s].extents);
      break;
    }
    default: nearest = c; break; // Potential Blocks and Particles: within the bounding box
    }
    if (id != except && (c - nearest).squaredNorm() < reach * reach)
      touching.push_back(id);
  }
  return touching;
}
} // namespace talus::dem
