#include "dem/shapes/PotentialBlock.h"
#include "dem/shapes/PlaneSet.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::dem
{

PotentialBlockShape makePotentialBlock(const std::vector<double>& a, const std::vector<double>& b,
                                       const std::vector<double>& c, const std::vector<double>& d, double r,
                                       double R, bool isBoundary, const std::string& which,
                                       PotentialBlockPlacement* placement)
{
  const std::vector<Vec3> n = planeNormals(a, b, c, d, which);
  const std::size_t m = n.size();
  if (m < 4)
    throw std::invalid_argument(which + ": a closed block needs at least 4 planes, got " + std::to_string(m));
  if (!std::isfinite(r) || r < 0)
    throw std::invalid_argument(which + ": r must be finite and >= 0, got " + std::to_string(r));
  if (!std::isfinite(R) || R < 0)
    throw std::invalid_argument(which + ": R must be finite and >= 0 (0: automatic), got " + std::to_string(R));
  PotentialBlockShape s;
  s.r = r;
  s.isBoundary = isBoundary;
  std::vector<double> h(m);
  double scale = 0;
  for (std::size_t i = 0; i < m; ++i)
  {
    h[i] = d[i] + r;
    scale = std::max(scale, std::abs(h[i]));
  }
  const std::vector<Vec3> v = boundedPolyhedronVertices(n, h, which);
  const double tol = 1e-9 * scale;

  // Faces: the vertices on each plane, sorted by angle around their mean.
  Vec3 inside = Vec3::Zero();
  for (const Vec3& x : v)
    inside += x;
  inside /= static_cast<double>(v.size());
  for (std::size_t i = 0; i < m; ++i)
  {
    std::vector<int> on;
    for (std::size_t k = 0; k < v.size(); ++k)
      if (std::abs(n[i].dot(v[k]) - h[i]) <= 10 * tol)
        on.push_back(static_cast<int>(k));
    if (on.size() < 3)
      continue; // a plane touching the block at an edge or a vertex, or not at all
    Vec3 mid = Vec3::Zero();
    for (int k : on)
      mid += v[static_cast<std::size_t>(k)];
    mid /= static_cast<double>(on.size());
    const Vec3 t1 = (v[static_cast<std::size_t>(on[0])] - mid).normalized();
    const Vec3 t2 = n[i].cross(t1);
    std::sort(on.begin(), on.end(), [&](int p, int q) {
      const Vec3 dp = v[static_cast<std::size_t>(p)] - mid, dq = v[static_cast<std::size_t>(q)] - mid;
      return std::atan2(dp.dot(t2), dp.dot(t1)) < std::atan2(dq.dot(t2), dq.dot(t1));
    });
    s.faces.push_back(on);
    s.facePlane.push_back(static_cast<int>(i));
  }

  // Edges: two faces sharing two vertices meet along the cross product of their normals.
  std::vector<Vec3> edges;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (std::size_t g = f + 1; g < s.faces.size(); ++g)
    {
      int shared = 0;
      for (int p : s.faces[f])
        shared += static_cast<int>(std::count(s.faces[g].begin(), s.faces[g].end(), p));
      const Vec3 e = n[static_cast<std::size_t>(s.facePlane[f])].cross(n[static_cast<std::size_t>(s.facePlane[g])]);
      if (shared >= 2 && e.norm() > 1e-9
          && std::none_of(edges.begin(), edges.end(), [&](const Vec3& o) { return o.cross(e.normalized()).norm() < 1e-9; }))
        edges.push_back(e.normalized());
    }

  // Volume, centroid and second moments: tetrahedra from an inner point to each face triangle
  // (integral of x x^T over a tetrahedron p0..p3: V/20 (sum p p^T + (sum p)(sum p)^T)).
  double volume = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const auto& face : s.faces)
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
    {
      const Vec3 p[4] = {inside, v[static_cast<std::size_t>(face[0])], v[static_cast<std::size_t>(face[k])],
                         v[static_cast<std::size_t>(face[k + 1])]};
      const double vt = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6;
      const Vec3 sum = p[0] + p[1] + p[2] + p[3];
      volume += vt;
      first += vt * sum / 4;
      Mat3 pp = sum * sum.transpose();
      for (const Vec3& q : p)
        pp += q * q.transpose();
      second += vt / 20 * pp;
    }
  const double extent = 2 * std::max(scale, 1e-300);
  if (!(volume > 1e-12 * extent * extent * extent))
    throw std::invalid_argument(which + ": the planes bound no volume (flat or degenerate region, volume "
                                + std::to_string(volume) + ")");
  const Vec3 centroid = first / volume;
  const Mat3 central = second - volume * centroid * centroid.transpose();
  const Mat3 inertia = central.trace() * Mat3::Identity() - central;
  Eigen::SelfAdjointEigenSolver<Mat3> eig(inertia);
  Mat3 Q = eig.eigenvectors();
  if (Q.determinant() < 0)
    Q.col(2) = -Q.col(2);

  // Into the principal frame: y = Q^T (x - centroid).
  s.volume = volume;
  s.normals.resize(m);
  s.d.resize(m);
  // Frictional faces unless the caller (BlockGen) says otherwise.
  s.cohesion.assign(m, 0.0);
  s.tension.assign(m, 0.0);
  s.intactRock.assign(m, 0);
  s.jointType.assign(m, 0);
  for (std::size_t i = 0; i < m; ++i)
  {
    s.normals[i] = Q.transpose() * n[i];
    s.d[i] = d[i] - n[i].dot(centroid);
  }
  for (const Vec3& e : edges)
    s.edgeDirections.push_back(Q.transpose() * e);
  double diameter = 0;
  for (const Vec3& x : v)
  {
    s.vertices.push_back(Q.transpose() * (x - centroid));
    s.boundingRadius = std::max(s.boundingRadius, s.vertices.back().norm());
    for (const Vec3& y : v)
      diameter = std::max(diameter, (x - y).norm());
  }
  s.R = R > 0 ? R : 0.5 * diameter;
  if (placement)
  {
    placement->centroid = centroid;
    placement->principalAxes = Quat(Q);
    placement->inertiaPerDensity = eig.eigenvalues();
  }
  return s;
}

Vec3 potentialBlockNormal(const PotentialBlockShape& s, const Vec3& y, int* active)
{
  Vec3 g = Vec3::Zero();
  int count = 0;
  std::size_t nearest = 0;
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.normals.size(); ++i)
  {
    const double f = s.normals[i].dot(y) - s.d[i];
    if (f > 0)
    {
      g += f * s.normals[i];
      ++count;
    }
    if (f > best)
    {
      best = f;
      nearest = i;
    }
  }
  if (active)
    *active = count;
  const double norm = g.norm();
  return norm > 0 ? Vec3(g / norm) : s.normals[nearest];
}
void setBlockFaceProperties(PotentialBlockShape& s, const std::vector<double>& cohesion,
                            const std::vector<double>& tension, const std::vector<bool>& intactRock,
                            const std::vector<int>& jointType, const std::string& which)
{
  const std::size_t m = s.normals.size();
  auto check = [&](std::size_t size, const char* name) {
    if (size != 0 && size != m)
      throw std::invalid_argument(which + ": " + name + " has " + std::to_string(size) + " entries for "
                                  + std::to_string(m) + " planes");
  };
  check(cohesion.size(), "cohesion");
  check(tension.size(), "tension");
  check(intactRock.size(), "intactRock");
  check(jointType.size(), "jointType");
  for (const auto* list : {&cohesion, &tension})
    for (std::size_t i = 0; i < list->size(); ++i)
      if (!std::isfinite((*list)[i]) || (*list)[i] < 0)
        throw std::invalid_argument(which + ": " + (list == &cohesion ? "cohesion" : "tension") + " of plane "
                                    + std::to_string(i) + " must be finite and >= 0, got " + std::to_string((*list)[i]));
  if (!cohesion.empty())
    s.cohesion = cohesion;
  if (!tension.empty())
    s.tension = tension;
  if (!intactRock.empty())
    s.intactRock.assign(intactRock.begin(), intactRock.end());
  if (!jointType.empty())
    s.jointType.assign(jointType.begin(), jointType.end());
}
} // namespace talus::dem
