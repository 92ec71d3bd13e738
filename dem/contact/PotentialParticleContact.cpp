#include "dem/contact/PotentialParticleContact.h"
#include "dem/shapes/PotentialParticle.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace talus::dem
{
namespace
{
const PotentialParticleShape& shapeOf(const Bodies& b, std::size_t i)
{
  return b.particles[static_cast<std::size_t>(b.shapeIndex[i])];
}

PlacedPotential placed(const Bodies& b, std::size_t i, const Vec3& origin)
{
  return placePotential(shapeOf(b, i), b.pos[i], b.ori[i], origin);
}

constexpr int areaRays = 72; // Yade's default areaStep, 5 degrees

/// Area of the section of {f1 <= 0, f2 <= 0} (f2 may be null) through x normal to n, each ray
/// to `tol` scale.
double sectionArea(const PlacedPotential& f1, const PlacedPotential* f2, const Vec3& x, const Vec3& n, double scale,
                   double tol)
{
  // The rays' directions in the section's plane, computed once.
  static const auto circle = [] {
    std::array<std::pair<double, double>, areaRays> cs;
    for (int j = 0; j < areaRays; ++j)
      cs[static_cast<std::size_t>(j)] = {std::cos(2 * M_PI * j / areaRays), std::sin(2 * M_PI * j / areaRays)};
    return cs;
  }();
  const Vec3 t1 = (std::abs(n[0]) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 t2 = n.cross(t1);
  double sum = 0, rho = 0;
  for (const auto& [c, s] : circle)
  {
    rho = rayExit(f1, f2, x, c * t1 + s * t2, rho, scale, tol);
    sum += rho * rho;
  }
  return 0.5 * sum * (2 * M_PI / areaRays);
}

/// The contact area: the section's area, or in 2D mode (b.particleContact) the joint length,
/// the section's chord through x along n x twoDdir, times unitWidth2D. A normal along twoDdir
/// (no chord in the plane of motion) falls back to the section.
double contactArea(const Bodies& b, const PlacedPotential& f1, const PlacedPotential* f2, const Vec3& x, const Vec3& n,
                   double scale, double tol)
{
  const ParticleContactSettings& settings = b.particleContact;
  if (settings.twoDimension)
  {
    const Vec3 along = n.cross(settings.twoDdir);
    if (along.norm() > 1e-9)
    {
      const Vec3 d = along.normalized();
      return settings.unitWidth2D * (rayExit(f1, f2, x, d, 0, scale, tol) + rayExit(f1, f2, x, -d, 0, scale, tol));
    }
  }
  return sectionArea(f1, f2, x, n, scale, tol);
}
} // namespace

/// Support point of particle i along the unit world direction e, relative to b.pos[i], from the
/// stored surface sample farthest along e.
Vec3 support(const Bodies& b, std::size_t i, const PlacedPotential& f, const Vec3& e)
{
  const PotentialParticleShape& s = shapeOf(b, i);
  const Vec3 eb = b.ori[i].conjugate() * e;
  std::size_t best = 0;
  for (std::size_t k = 1; k < s.samples.size(); ++k)
    if (s.samples[k].dot(eb) > s.samples[best].dot(eb))
      best = k;
  const Vec3 start = b.ori[i] * s.samples[best];
  Vec3 x = Vec3::Zero();
  supportPoint(f, e, x, &start);
  return x;
}

void potentialParticleAabb(const Bodies& b, std::size_t i, Vec3& lo, Vec3& hi)
{
  const PlacedPotential f = placed(b, i, b.pos[i]);
  for (int axis = 0; axis < 3; ++axis)
  {
    Vec3 e = Vec3::Zero();
    e[axis] = 1;
    hi[axis] = b.pos[i][axis] + support(b, i, f, e)[axis];
    lo[axis] = b.pos[i][axis] + support(b, i, f, -e)[axis];
  }
}

bool potentialParticleContact(const Bodies& b, std::size_t i1, std::size_t i2, const Vec3* previous,
                              ConvexContactGeometry& out, double accuracyTol)
{
  // Lengths (inner minimisations, rays) to accuracyTol / 10 R, but never coarser than 1e-9 R:
  // Newton converges quadratically there, so a loose accuracyTol would save little and would
  // blur the chord of a shallow overlap.
  const double stepTol = std::min(0.1 * accuracyTol, 1e-9);
  const PotentialParticleShape& s2 = shapeOf(b, i2);
  out.lpSolves = 0;
  if (b.shape[i1] == ShapeKind::Wall)
  {
    // The wall's solid side is behind its plane, seen from the particle: the deepest point is
    // the particle's support point along -normal.
    const WallShape& w = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])];
    const double dpos = b.pos[i2][w.axis] - b.pos[i1][w.axis];
    const double side = w.sense != 0 ? w.sense : (dpos >= 0 ? 1.0 : -1.0);
    Vec3 n = Vec3::Zero();
    n[w.axis] = side;
    const Vec3 origin = b.pos[i2];
    const PlacedPotential f = placePotential(s2, b.pos[i2], b.ori[i2], origin);
    // Cheap rejection: the bounding sphere does not reach the plane.
    if (side * dpos > s2.boundingRadius)
      return false;
    const Vec3 x = support(b, i2, f, -n);
    const double depth = side * (b.pos[i1][w.axis] - origin[w.axis]) - n.dot(x);
    if (!(depth > 0))
      return false;
    out.normal = n;
    out.penetration = depth;
    const Vec3 mid = x + 0.5 * depth * n;
    out.contactPoint = mid + origin;
    out.area = contactArea(b, f, nullptr, mid, n, s2.R, stepTol);
    return true;
  }

  const PotentialParticleShape& s1 = shapeOf(b, i1);
  const Vec3 origin = 0.5 * (b.pos[i1] + b.pos[i2]);
  const PlacedPotential f1 = placed(b, i1, origin), f2 = placed(b, i2, origin);
  const double scale = std::min(s1.R, s2.R);
  // Bounding spheres apart: no contact.
  if ((b.pos[i2] - b.pos[i1]).norm() > s1.boundingRadius + s2.boundingRadius)
    return false;
  Vec3 x = previous ? Vec3(*previous - origin) : Vec3::Zero();
  bool separated = false;
  Vec3 g1, g2;
  double v1 = 0, v2 = 0;
  decreasingRoot(
      [&](double mu, double& slope) {
        Mat3 H;
        minimisePotentials(f1, mu, &f2, 1 - mu, Vec3::Zero(), x, &H, stepTol);
        v1 = f1.eval(x, &g1);
        v2 = f2.eval(x, &g2);
        // Weak duality: min_x mu f1 + (1 - mu) f2 > 0 means no point is inside both.
        if (mu * v1 + (1 - mu) * v2 > 0)
        {
          separated = true;
          slope = 0;
          return 0.0; // stops the search
        }
        const Vec3 dg = g1 - g2;
        slope = -dg.dot(H.ldlt().solve(dg));
        // |f1 - f2| <= accuracyTol ends the search only once the point is inside both (the
        // contact decided): with a loose tolerance a shallow overlap would otherwise be missed
        // (at 0.1, a 1e-3 m vertex into a face). Until then the search goes on with the sign.
        if (!(std::max(v1, v2) < 0) && v1 != v2 && std::abs(v1 - v2) <= accuracyTol)
          return std::copysign(2 * accuracyTol, v1 - v2);
        return v1 - v2;
      },
      0.0, 1.0, 0.5, accuracyTol, stepTol);
  if (separated || !(std::max(v1, v2) < 0))
    return false;

  // The normal: grad f1 and -grad f2 are parallel at x*; their mean is robust when one is tiny.
  Vec3 n = Vec3::Zero();
  const double n1 = g1.norm(), n2 = g2.norm();
  if (n1 > 0)
    n += g1 / n1;
  if (n2 > 0)
    n -= g2 / n2;
  if (!(n.norm() > 1e-12))
    n = b.pos[i2] - b.pos[i1];
  if (!(n.norm() > 0))
    n = Vec3::UnitZ();
  n.normalize();

  const double tPlus = rayExit(f1, &f2, x, n, 0, scale, stepTol), tMinus = rayExit(f1, &f2, x, -n, 0, scale, stepTol);
  const double chord = tPlus + tMinus;
  if (!(chord > 0) || !std::isfinite(chord))
    return false;
  out.normal = n;
  out.penetration = chord;
  const Vec3 mid = x + 0.5 * (tPlus - tMinus) * n;
  out.contactPoint = mid + origin;
  out.area = contactArea(b, f1, &f2, mid, n, scale, stepTol);
  return true;
}
} // namespace talus::dem
