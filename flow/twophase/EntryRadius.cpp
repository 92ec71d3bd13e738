#include "flow/twophase/EntryRadius.h"

#include <Eigen/Geometry> // cross products
#include <Eigen/LU>       // determinant

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace talus::flow::twophase
{
EntryPressureMethod entryPressureMethod(int number)
{
  if (number < 1 || number > 3)
    throw std::invalid_argument("TwoPhaseFlowEngine: entryPressureMethod must be 1 (MS-P, Yuan & Chareyre 2017), "
                                "2 (inscribed circle) or 3 (circle of the throat's fluid area), got " +
                                std::to_string(number));
  return static_cast<EntryPressureMethod>(number);
}

double inscribedRadius(const Vec3& a, double ra, const Vec3& b, double rb, const Vec3& c, double rc)
{
  // In the plane of the centres, sphere a at the origin: the tangent circle (X, Y, R) satisfies
  // |(X, Y) - P_k| = r_k + R for the three spheres. Subtracting a's equation from b's and c's
  // leaves two linear equations giving X = x0 + x1 R, Y = y0 + y1 R; a's equation is then a
  // quadratic in R, of which the larger root is the circle between the spheres.
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ex = ab.normalized();
  const Vec3 ey = ex.cross(ex.cross(ac)).normalized();
  const double b0 = ab.dot(ex), b1 = ab.dot(ey);
  const double c0 = ac.dot(ex), c1 = ac.dot(ey);
  // 2 b0 X + 2 b1 Y = |b|^2 + ra^2 - rb^2 + 2 R (ra - rb), the same for c
  const double det = 2 * (b0 * c1 - b1 * c0);
  const double kb = b0 * b0 + b1 * b1 + ra * ra - rb * rb, lb = 2 * (ra - rb);
  const double kc = c0 * c0 + c1 * c1 + ra * ra - rc * rc, lc = 2 * (ra - rc);
  const double x0 = (kb * c1 - kc * b1) / det, x1 = (lb * c1 - lc * b1) / det;
  const double y0 = (kc * b0 - kb * c0) / det, y1 = (lc * b0 - lb * c0) / det;
  // (ra + R)^2 - X^2 - Y^2 = 0, as qa R^2 + qb R + qc = 0
  const double qa = 1 - x1 * x1 - y1 * y1;
  const double qb = 2 * ra - 2 * (x0 * x1 + y0 * y1);
  const double qc = ra * ra - x0 * x0 - y0 * y0;
  return (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
}

namespace
{
/// Angle opposite side `opposite` in the triangle of sides (opposite, s1, s2), law of cosines.
double angleOpposite(double opposite, double s1, double s2)
{
  const double cosine = (s1 * s1 + s2 * s2 - opposite * opposite) / (2 * s1 * s2);
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

/// The MS-P balance for a meniscus of radius r in the plane of the three centres: interface
/// length (wetting menisci plus the dry arcs of the spheres) minus the non-wetting area over r.
/// Positive: the front cannot pass at this radius (Yuan & Chareyre 2017, Yade's computeDeltaForce).
double forceBalance(const std::array<Vec3, 3>& p, const std::array<double, 3>& rad, double r)
{
  // side k of the triangle is opposite vertex k
  std::array<double, 3> side{};
  std::array<double, 3> corner{}; // the triangle's angle at each vertex
  for (std::size_t k = 0; k < 3; ++k)
  {
    const Vec3& i = p[(k + 1) % 3];
    const Vec3& j = p[(k + 2) % 3];
    side[k] = (i - j).norm();
    const Vec3 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
    corner[k] = std::acos(u.dot(v) / (u.norm() * v.norm()));
  }
  double meniscusLength = 0, wettedArea = 0;
  std::array<double, 3> wettedAngle{}; // angle of each sphere taken by its two menisci
  for (std::size_t k = 0; k < 3; ++k)
  {
    // the meniscus between spheres i and j (opposite vertex k): its centre is at r_i + r from i
    // and r_j + r from j
    const std::size_t i = (k + 1) % 3, j = (k + 2) % 3;
    const double di = rad[i] + r, dj = rad[j] + r;
    const double atMeniscus = angleOpposite(side[k], di, dj);
    const double atI = angleOpposite(dj, side[k], di);
    const double atJ = angleOpposite(di, dj, side[k]);
    meniscusLength += atMeniscus * r;
    wettedAngle[i] += atI;
    wettedAngle[j] += atJ;
    wettedArea += 0.5 * di * dj * std::sin(atMeniscus) - 0.5 * atMeniscus * r * r - 0.5 * atI * rad[i] * rad[i] -
                  0.5 * atJ * rad[j] * rad[j];
  }
  double dryLength = 0, solidArea = 0;
  for (std::size_t k = 0; k < 3; ++k)
  {
    dryLength += (corner[k] - wettedAngle[k]) * rad[k];
    solidArea += 0.5 * corner[k] * rad[k] * rad[k];
  }
  const double triangle = 0.5 * (p[0] - p[2]).cross(p[1] - p[2]).norm();
  const double nonWettingArea = triangle - solidArea - wettedArea;
  return meniscusLength + dryLength - nonWettingArea / r;
}
} // namespace

double mspRadius(const Vec3& a, double ra, const Vec3& b, double rb, const Vec3& c, double rc)
{
  const std::array<Vec3, 3> p{a, b, c};
  const std::array<double, 3> rad{ra, rb, rc};
  // the widest gap between two spheres (a meniscus smaller than it cannot span the throat) and
  // the inscribed circle (larger cannot fit) bracket the root
  double gap = 0;
  for (std::size_t k = 0; k < 3; ++k)
    gap = std::max(gap, 0.5 * ((p[(k + 1) % 3] - p[(k + 2) % 3]).norm() - rad[(k + 1) % 3] - rad[(k + 2) % 3]));
  double lo = gap > 0 ? gap : 1e-11;
  const double inscribed = inscribedRadius(a, ra, b, rb, c, rc);
  double hi = inscribed < 0 ? 1e-10 : inscribed;
  const double fLo = forceBalance(p, rad, lo), fHi = forceBalance(p, rad, hi);
  if (fLo > fHi || fHi < 0)
    return hi;
  if (fLo > 0)
    return lo;
  const double tolerance = 1e-6 * hi;
  double mid = 0.5 * (lo + hi);
  while (std::abs(hi - lo) > tolerance)
  {
    if (forceBalance(p, rad, mid) * forceBalance(p, rad, lo) < 0)
      hi = mid;
    else
      lo = mid;
    mid = 0.5 * (lo + hi);
  }
  return mid;
}

std::vector<double> throatEntryRadii(const pore::PoreNetwork& net, EntryPressureMethod method, bool invadeBoundary)
{
  std::vector<double> radii(net.throats.size());
  for (std::size_t t = 0; t < net.throats.size(); ++t)
  {
    const pore::Throat& throat = net.throats[t];
    if (method == EntryPressureMethod::EquivalentArea)
    {
      radii[t] = std::sqrt(throat.fluidArea / std::numbers::pi);
      continue;
    }
    std::array<Vec3, 3> p;
    std::array<double, 3> r{};
    int walls = 0;
    for (std::size_t k = 0; k < 3; ++k)
    {
      const pore::Vertex& v = net.vertices[static_cast<std::size_t>(throat.vertices[k])];
      p[k] = v.pos;
      r[k] = v.radius;
      walls += v.fictitious ? 1 : 0;
    }
    if (method == EntryPressureMethod::MSP && walls == 0)
      radii[t] = mspRadius(p[0], r[0], p[1], r[1], p[2], r[2]);
    else
    {
      // a negative radius (a wall facet where the tangent circle falls outside) closes the throat
      const double inscribed = inscribedRadius(p[0], r[0], p[1], r[1], p[2], r[2]);
      radii[t] = inscribed < 0 ? 0.0 : inscribed;
    }
    if (method == EntryPressureMethod::MSP && !invadeBoundary &&
        net.pores[static_cast<std::size_t>(throat.pores[0])].nFictitious > 0 &&
        net.pores[static_cast<std::size_t>(throat.pores[1])].nFictitious > 0)
      radii[t] = -1;
  }
  return radii;
}

namespace
{
/// About where Yade's pore-body search stops growing (a step adding 0.1 %).
constexpr int kGrowthSteps = 1000;

/// The step at which a step of `step` adds less than 0.1 % to the radius accumulated step by
/// step from `step`, as Yade's search sums it: 1000 or 1001 by the round-off of the sum.
int growthLimit(double step)
{
  double R = step;
  for (int k = 2;; ++k)
  {
    const double previous = R;
    R += step;
    if (std::abs(previous - R) / R < 0.001)
      return k;
  }
}
} // namespace

std::vector<double> poreBodyRadii(const pore::PoreNetwork& net)
{
  std::vector<double> radii(net.pores.size());
  for (std::size_t c = 0; c < net.pores.size(); ++c)
  {
    std::array<const pore::Vertex*, 4> v{};
    for (std::size_t k = 0; k < 4; ++k)
      v[k] = &net.vertices[static_cast<std::size_t>(net.pores[c].vertices[k])];
    // The sphere of radius R tangent to the four makes this Cayley-Menger-type determinant
    // vanish: its sign flips as R passes the inscribed radius.
    Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        m(i, j) = (v[static_cast<std::size_t>(i)]->pos - v[static_cast<std::size_t>(j)]->pos).squaredNorm();
    for (int i = 0; i < 5; ++i)
      m(5, i) = m(i, 5) = 1;
    const auto determinant = [&](double R) {
      for (int i = 0; i < 4; ++i)
      {
        const double d = v[static_cast<std::size_t>(i)]->radius + R;
        m(4, i) = m(i, 4) = d * d;
      }
      return m.determinant();
    };
    double rMin = v[0]->radius;
    for (const pore::Vertex* x : v)
      rMin = std::min(rMin, x->radius);
    // Yade's search: steps of rMin/50 from 2 steps on; the radius is the last step before the
    // sign changes or, if it does not, where a step adds less than 0.1 % (20 rMin: a pore wide
    // open to a wall). Yade tries every step; here strides of 16 steps find the bracket, then
    // bisection the step (the same step unless the sign changes twice within a stride).
    const double step = rMin / 50;
    constexpr int kStride = 16;
    const bool positive = determinant(2 * step) > 0;
    const auto flipped = [&](int k) {
      const double d = determinant(k * step);
      return positive ? d < 0 : d > 0;
    };
    int last = 0; // the step Yade's search stops at without a flip, found when needed
    int k = 2;    // the last step known not to flip
    while (true)
    {
      if (last == 0 && k + kStride >= kGrowthSteps)
        last = growthLimit(step);
      const int next = last > 0 ? std::min(k + kStride, last) : k + kStride;
      if (next == k)
        break;
      if (!flipped(next))
      {
        k = next;
        continue;
      }
      int bad = next; // flips at `bad`, not at `k`
      while (bad - k > 1)
      {
        const int mid = (k + bad) / 2;
        (flipped(mid) ? bad : k) = mid;
      }
      break;
    }
    const double R = k * step;
    radii[c] = R;
  }
  return radii;
}
} // namespace talus::flow::twophase
