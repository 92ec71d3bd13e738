#include "dem/contact/PotentialBlockContact.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#ifdef TALUS_HAVE_CLP
#include <ClpSimplex.hpp>
#endif

namespace talus::dem
{
namespace
{
/// Half-spaces n . x <= h (world frame, relative to an origin near the pair).
struct HalfSpaces
{
  std::vector<Vec3> n;
  std::vector<double> h;
  void add(const Vec3& normal, double offset)
  {
    n.push_back(normal);
    h.push_back(offset);
  }
  [[nodiscard]] double minSlack(const Vec3& x) const
  {
    double s = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n.size(); ++j)
      s = std::min(s, h[j] - n[j].dot(x));
    return s;
  }
};

const PotentialBlockShape& shapeOf(const Bodies& b, std::size_t i)
{
  return b.blocks[static_cast<std::size_t>(b.shapeIndex[i])];
}

/// The faces of block i as half-spaces relative to `origin`.
void addBlock(const Bodies& b, std::size_t i, const Vec3& origin, HalfSpaces& out)
{
  const PotentialBlockShape& s = shapeOf(b, i);
  const Mat3 R = b.ori[i].toRotationMatrix();
  const Vec3 p = b.pos[i] - origin;
  for (std::size_t k = 0; k < s.normals.size(); ++k)
  {
    const Vec3 n = R * s.normals[k];
    out.add(n, n.dot(p) + s.d[k] + s.r);
  }
}

/// World vertices of block i relative to `origin`.
std::vector<Vec3> worldVertices(const Bodies& b, std::size_t i, const Vec3& origin)
{
  const PotentialBlockShape& s = shapeOf(b, i);
  const Mat3 R = b.ori[i].toRotationMatrix();
  std::vector<Vec3> v(s.vertices.size());
  for (std::size_t k = 0; k < v.size(); ++k)
    v[k] = R * s.vertices[k] + (b.pos[i] - origin);
  return v;
}

/// A face plane of block i (as half-spaces `own`, entries [first, first + count)) with every
/// vertex of the other body outside it separates the two.
bool separatedByFace(const HalfSpaces& own, std::size_t first, std::size_t count, const std::vector<Vec3>& other)
{
  for (std::size_t j = first; j < first + count; ++j)
  {
    bool allOutside = true;
    for (const Vec3& v : other)
      if (own.n[j].dot(v) <= own.h[j])
      {
        allOutside = false;
        break;
      }
    if (allOutside)
      return true;
  }
  return false;
}

/// Separating axes between two polyhedra besides their face normals: the cross products of
/// an edge of each (the face normals are tested with the planes themselves).
bool separatedByEdges(const Bodies& b, std::size_t i1, std::size_t i2, const std::vector<Vec3>& v1,
                      const std::vector<Vec3>& v2)
{
  const Mat3 R1 = b.ori[i1].toRotationMatrix(), R2 = b.ori[i2].toRotationMatrix();
  for (const Vec3& e1 : shapeOf(b, i1).edgeDirections)
    for (const Vec3& e2 : shapeOf(b, i2).edgeDirections)
    {
      const Vec3 axis = (R1 * e1).cross(R2 * e2);
      if (axis.squaredNorm() < 1e-18)
        continue;
      double lo1 = std::numeric_limits<double>::infinity(), hi1 = -lo1, lo2 = lo1, hi2 = hi1;
      for (const Vec3& v : v1)
      {
        const double p = axis.dot(v);
        lo1 = std::min(lo1, p);
        hi1 = std::max(hi1, p);
      }
      for (const Vec3& v : v2)
      {
        const double p = axis.dot(v);
        lo2 = std::min(lo2, p);
        hi2 = std::max(hi2, p);
      }
      if (hi1 < lo2 || hi2 < lo1)
        return true;
    }
  return false;
}

/// The shorter translation of body 2 (vertices v2), along +u or -u, that ends its overlap with
/// body 1 (vertices v1) along the unit axis u, and its sense (+1: along +u).
double overlapAlong(const Vec3& u, const std::vector<Vec3>& v1, const std::vector<Vec3>& v2, double* sense = nullptr)
{
  double lo1 = std::numeric_limits<double>::infinity(), hi1 = -lo1, lo2 = lo1, hi2 = hi1;
  for (const Vec3& v : v1)
  {
    lo1 = std::min(lo1, u.dot(v));
    hi1 = std::max(hi1, u.dot(v));
  }
  for (const Vec3& v : v2)
  {
    lo2 = std::min(lo2, u.dot(v));
    hi2 = std::max(hi2, u.dot(v));
  }
  const double plus = hi1 - lo2, minus = hi2 - lo1;
  if (sense)
    *sense = plus <= minus ? 1.0 : -1.0;
  return std::min(plus, minus);
}

/// The contact normal of two overlapping polyhedra from their separating-axis candidates (the
/// faces' normals of both and the cross products of their edges): along each axis, the shorter
/// translation of body 2 that ends the overlap; the least of these (`least`) is the exact
/// polyhedral normal (the penetration depth's direction). The axes within a few `smoothing` of
/// the least are averaged with weights exp(-(depth - least) / smoothing), so that the normal
/// turns smoothly between axes that (nearly) tie, as the two faces beside parallel edges do,
/// instead of jumping between them.
Vec3 leastOverlapNormal(const Bodies& b, std::size_t i1, std::size_t i2, const std::vector<Vec3>& v1,
                        const std::vector<Vec3>& v2, double smoothing, double& least)
{
  std::vector<std::pair<double, Vec3>> axes; // depth, unit direction from body 1 to body 2
  auto consider = [&](Vec3 u) {
    const double length = u.norm();
    if (!(length > 1e-9))
      return;
    u /= length;
    for (const auto& [depth, w] : axes)
      if (std::abs(w.dot(u)) > 1 - 1e-12)
        return; // the same axis (opposite faces, or a face and an edge pair)
    double sense = 1;
    const double depth = overlapAlong(u, v1, v2, &sense);
    axes.emplace_back(depth, sense * u);
  };
  const Mat3 R1 = b.ori[i1].toRotationMatrix(), R2 = b.ori[i2].toRotationMatrix();
  for (const Vec3& n : shapeOf(b, i1).normals)
    consider(R1 * n);
  for (const Vec3& n : shapeOf(b, i2).normals)
    consider(R2 * n);
  for (const Vec3& e1 : shapeOf(b, i1).edgeDirections)
    for (const Vec3& e2 : shapeOf(b, i2).edgeDirections)
      consider((R1 * e1).cross(R2 * e2));
  least = std::numeric_limits<double>::infinity();
  Vec3 leastAxis = Vec3::UnitZ();
  for (const auto& [depth, u] : axes)
    if (depth < least)
    {
      least = depth;
      leastAxis = u;
    }
  Vec3 n = Vec3::Zero();
  for (const auto& [depth, u] : axes)
    if (depth - least < 30 * smoothing) // beyond, a weight below 1e-13
      n += std::exp(-(depth - least) / smoothing) * u;
  return n.norm() > 1e-12 ? Vec3(n.normalized()) : leastAxis;
}

/// The mean of the points of `candidates` inside every half-space (within `tol`) is in their
/// intersection's closure; added to `sum` and counted.
void addContained(const HalfSpaces& hs, std::size_t first, std::size_t count, const std::vector<Vec3>& candidates,
                  double tol, Vec3& sum, int& n)
{
  for (const Vec3& v : candidates)
  {
    bool inside = true;
    for (std::size_t j = first; j < first + count && inside; ++j)
      inside = hs.n[j].dot(v) <= hs.h[j] + tol;
    if (inside)
    {
      sum += v;
      ++n;
    }
  }
}


/// Analytic centre of the half-spaces (minimum of -sum log(h_j - n_j . x)) by damped Newton
/// steps from the strictly interior point x: steps of 1 / (1 + lambda) keep every slack
/// positive (self-concordance), full steps once the Newton decrement lambda is small; stops
/// once lambda <= `tol` (lambda bounds the distance to the centre in the slacks' own metric).
void analyticCentre(const HalfSpaces& hs, double tol, Vec3& x)
{
  for (int iter = 0; iter < 60; ++iter)
  {
    Vec3 g = Vec3::Zero();
    Mat3 H = Mat3::Zero();
    for (std::size_t j = 0; j < hs.n.size(); ++j)
    {
      const double inv = 1.0 / (hs.h[j] - hs.n[j].dot(x));
      g += inv * hs.n[j];
      H += (inv * inv) * hs.n[j] * hs.n[j].transpose();
    }
    const Vec3 dx = -H.ldlt().solve(g);
    const double lambda2 = -g.dot(dx);
    if (!(lambda2 > tol * tol) || !dx.allFinite())
      return;
    const double lambda = std::sqrt(lambda2);
    x += (lambda < 0.25 ? 1.0 : 1.0 / (1.0 + lambda)) * dx;
  }
}

/// The chord of the half-spaces along the unit direction u through x (inside): the parameters
/// [tmin, tmax] of x + t u, clipped exactly against every plane. False if it is empty or open.
bool chord(const HalfSpaces& hs, const Vec3& x, const Vec3& u, double& tmin, double& tmax)
{
  tmin = -std::numeric_limits<double>::infinity();
  tmax = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < hs.n.size(); ++j)
  {
    const double a = hs.n[j].dot(u), slack = hs.h[j] - hs.n[j].dot(x);
    if (a > 1e-14)
      tmax = std::min(tmax, slack / a);
    else if (a < -1e-14)
      tmin = std::max(tmin, slack / a);
  }
  return tmax > tmin && std::isfinite(tmax - tmin);
}

/// Area of the section of the half-spaces by the plane through x normal to n (a polygon
/// clipped from a square of half-size `half`).
double sectionArea(const HalfSpaces& hs, const Vec3& x, const Vec3& n, double half)
{
  const Vec3 t1 = (std::abs(n[0]) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 t2 = n.cross(t1);
  std::vector<Eigen::Vector2d> poly{{-half, -half}, {half, -half}, {half, half}, {-half, half}}, next;
  for (std::size_t j = 0; j < hs.n.size() && !poly.empty(); ++j)
  {
    const Eigen::Vector2d a(hs.n[j].dot(t1), hs.n[j].dot(t2));
    if (a.norm() < 1e-12)
      continue; // parallel to the section: x is inside it
    const double gamma = hs.h[j] - hs.n[j].dot(x);
    next.clear();
    for (std::size_t k = 0; k < poly.size(); ++k)
    {
      const Eigen::Vector2d& p = poly[k];
      const Eigen::Vector2d& q = poly[(k + 1) % poly.size()];
      const double fp = a.dot(p) - gamma, fq = a.dot(q) - gamma;
      if (fp <= 0)
        next.push_back(p);
      if ((fp < 0) != (fq < 0) && fp != fq)
        next.push_back(p + (fp / (fp - fq)) * (q - p));
    }
    poly.swap(next);
  }
  double area = 0;
  for (std::size_t k = 0; k < poly.size(); ++k)
  {
    const Eigen::Vector2d& p = poly[k];
    const Eigen::Vector2d& q = poly[(k + 1) % poly.size()];
    area += p[0] * q[1] - p[1] * q[0];
  }
  return 0.5 * std::abs(area);
}
} // namespace

#ifdef TALUS_HAVE_CLP
double deepestPoint(const std::vector<Vec3>& normals, const std::vector<double>& h, double bound, Vec3& x)
{
  const int rows = static_cast<int>(normals.size());
  std::vector<double> value(static_cast<std::size_t>(4 * rows));
  std::vector<int> index(static_cast<std::size_t>(4 * rows));
  std::array<CoinBigIndex, 5> start{};
  for (int col = 0; col < 4; ++col)
  {
    start[static_cast<std::size_t>(col)] = col * rows;
    for (int j = 0; j < rows; ++j)
    {
      const auto e = static_cast<std::size_t>(col * rows + j);
      index[e] = j;
      value[e] = col < 3 ? normals[static_cast<std::size_t>(j)][col] : 1.0;
    }
  }
  start[4] = 4 * rows;
  const double inf = COIN_DBL_MAX;
  // The region lies within the blocks: bounding x by `bound` only keeps the LP well posed.
  const std::array<double, 4> collb{-bound, -bound, -bound, -inf}, colub{bound, bound, bound, bound};
  const std::array<double, 4> objective{0, 0, 0, -1};
  std::vector<double> rowlb(static_cast<std::size_t>(rows), -inf);
  // No scaling and a dense factorisation: CLP's defaults suit large problems; on these 4-column
  // ones they were slower in every back-to-back measurement (docs/dem.md, "Measurements behind
  // the code").
  ClpSimplex model;
  model.setLogLevel(0);
  model.scaling(0);
  model.setSparseFactorization(false);
  // CLP's default feasibility tolerances (1e-7) let it call shallow overlaps (a vertex on a
  // vertex 5e-8 m deep) empty: these problems are small and well scaled (unit normals).
  model.setPrimalTolerance(1e-11);
  model.setDualTolerance(1e-11);
  model.loadProblem(4, rows, start.data(), index.data(), value.data(), collb.data(), colub.data(), objective.data(),
                    rowlb.data(), h.data());
  model.dual(0);
  if (model.status() != 0)
    return -1;
  const double* sol = model.getColSolution();
  x = Vec3(sol[0], sol[1], sol[2]);
  return sol[3];
}
#else
// Without CLP no block can be added (Scene::addPotentialBlock refuses), nor pruned by size.
double deepestPoint(const std::vector<Vec3>& /*normals*/, const std::vector<double>& /*h*/, double /*bound*/, Vec3& /*x*/)
{
  throw std::logic_error("Potential Blocks need CLP, which this build of Talus does not have");
}
#endif

void potentialBlockAabb(const Bodies& b, std::size_t i, Vec3& lo, Vec3& hi)
{
  const std::vector<Vec3> v = worldVertices(b, i, Vec3::Zero());
  lo = hi = v.front();
  for (const Vec3& x : v)
  {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
}

bool potentialBlockContact(const Bodies& b, std::size_t i1, std::size_t i2, const Vec3* previous,
                           ConvexContactGeometry& out, double accuracyTol)
{
  const PotentialBlockShape& s2 = shapeOf(b, i2);
  const bool wall = b.shape[i1] == ShapeKind::Wall;
  const Vec3 origin = wall ? b.pos[i2] : Vec3(0.5 * (b.pos[i1] + b.pos[i2]));
  HalfSpaces hs;
  const std::vector<Vec3> v2 = worldVertices(b, i2, origin);
  Vec3 wallNormal = Vec3::Zero();
  double reach = s2.boundingRadius;
  // A cheap interior point to try before a linear program: the mean of the corners of each
  // body inside the other (for a wall, the block's corners behind it and their projections on
  // its plane).
  Vec3 cornerSum = Vec3::Zero();
  int corners = 0;
  if (wall)
  {
    // The wall's solid side is the half-space behind it, seen from the block.
    const WallShape& w = b.walls[static_cast<std::size_t>(b.shapeIndex[i1])];
    const double d = b.pos[i2][w.axis] - b.pos[i1][w.axis];
    const double side = w.sense != 0 ? w.sense : (d >= 0 ? 1.0 : -1.0);
    wallNormal[w.axis] = side;
    hs.add(wallNormal, side * (b.pos[i1][w.axis] - origin[w.axis]));
    if (separatedByFace(hs, 0, 1, v2))
      return false;
    for (const Vec3& v : v2)
      if (wallNormal.dot(v) < hs.h[0])
      {
        cornerSum += 2 * v - (wallNormal.dot(v) - hs.h[0]) * wallNormal;
        corners += 2;
      }
    addBlock(b, i2, origin, hs);
  }
  else
  {
    addBlock(b, i1, origin, hs);
    const std::size_t m1 = hs.n.size();
    addBlock(b, i2, origin, hs);
    reach += shapeOf(b, i1).boundingRadius;
    const std::vector<Vec3> v1 = worldVertices(b, i1, origin);
    // Separating-axis theorem: no separating face plane nor edge-edge axis means they overlap.
    if (separatedByFace(hs, 0, m1, v2) || separatedByFace(hs, m1, hs.n.size() - m1, v1)
        || separatedByEdges(b, i1, i2, v1, v2))
      return false;
    addContained(hs, 0, m1, v2, 1e-12 * reach, cornerSum, corners);
    addContained(hs, m1, hs.n.size() - m1, v1, 1e-12 * reach, cornerSum, corners);
  }

  // A strictly interior point: the previous contact point if still inside, else the corners'
  // mean if inside, else the linear program's deepest point.
  const double tiny = 1e-12 * reach;
  Vec3 x = Vec3::Zero();
  out.lpSolves = 0;
  if (previous && hs.minSlack(*previous - origin) > tiny)
    x = *previous - origin;
  else if (corners > 0 && hs.minSlack(cornerSum / corners) > tiny)
    x = cornerSum / corners;
  else
  {
    out.lpSolves = 1;
    if (deepestPoint(hs.n, hs.h, 2 * reach, x) <= tiny)
      return false;
  }
  analyticCentre(hs, accuracyTol, x);

  const BlockContactSettings& settings = b.blockContact;
  Vec3 n;
  double depth = 0; // the exact penetration depth along n (settings.exactDepth)
  if (wall)
  {
    n = wallNormal;
    for (const Vec3& v : v2)
      depth = std::max(depth, hs.h[0] - wallNormal.dot(v));
  }
  else
  {
    const std::vector<Vec3> v1 = worldVertices(b, i1, origin);
    double least = 0;
    if (settings.exactDepth)
    {
      // The polyhedra's least-overlap axis, averaged only over ties to the rounding (exactly
      // parallel edges): where two axes nearly tie, the depth's direction jumps from one to
      // the other, and so does this normal (smoothing over 1e-3 (r1 + r2), as below, put the
      // depth 20 % off between faces 1e-3 rad from parallel, 1e-4 m deep).
      n = leastOverlapNormal(b, i1, i2, v1, v2, 1e-9 * reach, least);
      depth = least;
    }
    else
    {
      // Yade's normal, from the inner potentials' gradients. A point in the face region of one
      // block (at most one plane active) and near an edge or a corner of the other takes that
      // face's normal; in both face regions both gradients (the two faces' normals) are
      // averaged. Near edges or corners of both, the gradients of the rounded potentials lean
      // towards the side faces (by 20 degrees and more for nearly parallel edges of nearly
      // parallel faces): the polyhedra's least-overlap axis instead, smoothed over a
      // thousandth of the roundings. So too when the face taken is not (within that
      // smoothing) a least-overlap axis: the analytic centre of a deep edge-edge overlap can
      // lie in a face region of one block (9 degrees off in the accuracy case).
      int a1 = 0, a2 = 0;
      const Vec3 xw = x + origin;
      const Vec3 g1 = b.ori[i1] * potentialBlockNormal(shapeOf(b, i1), b.ori[i1].conjugate() * (xw - b.pos[i1]), &a1);
      const Vec3 g2 = b.ori[i2] * potentialBlockNormal(s2, b.ori[i2].conjugate() * (xw - b.pos[i2]), &a2);
      const bool faceRule = (a1 <= 1) != (a2 <= 1);
      if (a1 <= 1 && a2 > 1)
        n = g1;
      else if (a2 <= 1 && a1 > 1)
        n = -g2;
      else if (a1 <= 1 && a2 <= 1)
      {
        n = g1 - g2;
        n = n.norm() > 1e-12 ? Vec3(n.normalized()) : g1;
      }
      if (a1 > 1 || a2 > 1)
      {
        const double smoothing = std::max(1e-3 * (shapeOf(b, i1).r + s2.r), 1e-9 * reach);
        const Vec3 axis = leastOverlapNormal(b, i1, i2, v1, v2, smoothing, least);
        if (!faceRule || overlapAlong(n, v1, v2) > least + smoothing)
          n = axis;
      }
    }
  }

  // The chord of the overlap region along n through x: the seed's overlap, and the contact
  // point at its middle.
  double tmin = 0, tmax = 0;
  if (!chord(hs, x, n, tmin, tmax))
    return false;
  out.normal = n;
  out.penetration = settings.exactDepth ? depth : tmax - tmin;
  const Vec3 mid = x + 0.5 * (tmin + tmax) * n;
  out.contactPoint = mid + origin;
  if (settings.twoDimension)
  {
    // The joint: the chord through the contact point across the normal, in the plane of motion.
    Vec3 across = n.cross(settings.twoDdir);
    if (across.squaredNorm() < 1e-14)
      across = Vec3::UnitX().cross(settings.twoDdir);
    double lo = 0, hi = 0;
    out.area = chord(hs, mid, across.normalized(), lo, hi) ? settings.unitWidth2D * (hi - lo) : 0.0;
  }
  else
    out.area = sectionArea(hs, mid, n, 2 * reach);
  return true;
}
} // namespace talus::dem
