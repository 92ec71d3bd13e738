#include "dem/shapes/PlaneSet.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace talus::dem
{
std::vector<Vec3> planeNormals(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
                               const std::vector<double>& d, const std::string& which)
{
  const std::size_t m = a.size();
  if (b.size() != m || c.size() != m || d.size() != m)
    throw std::invalid_argument(which + ": a, b, c, d must have the same length, got " + std::to_string(a.size()) + ", "
                                + std::to_string(b.size()) + ", " + std::to_string(c.size()) + ", "
                                + std::to_string(d.size()));
  std::vector<Vec3> n(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    n[i] = Vec3(a[i], b[i], c[i]);
    const std::string plane = which + ": plane " + std::to_string(i);
    if (!n[i].allFinite() || !std::isfinite(d[i]))
      throw std::invalid_argument(plane + " is not finite");
    if (std::abs(n[i].norm() - 1) > 1e-6)
      throw std::invalid_argument(plane + " has a non-unit normal (" + std::to_string(a[i]) + ", " + std::to_string(b[i])
                                  + ", " + std::to_string(c[i]) + "), norm " + std::to_string(n[i].norm()));
    n[i].normalize();
  }
  return n;
}

std::vector<Vec3> polyhedronVertices(const std::vector<Vec3>& n, const std::vector<double>& h, double tol)
{
  std::vector<Vec3> out;
  const std::size_t m = n.size();
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = i + 1; j < m; ++j)
      for (std::size_t k = j + 1; k < m; ++k)
      {
        Mat3 A;
        A.row(0) = n[i];
        A.row(1) = n[j];
        A.row(2) = n[k];
        if (std::abs(A.determinant()) < 1e-10)
          continue;
        const Vec3 x = A.partialPivLu().solve(Vec3(h[i], h[j], h[k]));
        bool inside = true;
        for (std::size_t q = 0; q < m && inside; ++q)
          inside = n[q].dot(x) <= h[q] + tol;
        if (inside && std::none_of(out.begin(), out.end(), [&](const Vec3& v) { return (v - x).norm() < tol; }))
          out.push_back(x);
      }
  return out;
}

std::vector<Vec3> boundedPolyhedronVertices(const std::vector<Vec3>& n, const std::vector<double>& h,
                                            const std::string& which)
{
  double scale = 0;
  for (double x : h)
    scale = std::max(scale, std::abs(x));
  if (!(scale > 0))
    throw std::invalid_argument(which + ": every face passes through the origin: the planes bound no volume");
  const double far = 1e6 * scale, tol = 1e-9 * scale;
  std::vector<Vec3> nb = n;
  std::vector<double> hb = h;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0})
    {
      Vec3 e = Vec3::Zero();
      e[axis] = sign;
      nb.push_back(e);
      hb.push_back(far);
    }
  std::vector<Vec3> v = polyhedronVertices(nb, hb, tol);
  if (v.empty())
    throw std::invalid_argument(which + ": the planes have an empty intersection (no point satisfies all a x + b y + c z <= d + r)");
  for (const Vec3& x : v)
    if (x.cwiseAbs().maxCoeff() > 0.5 * far)
      throw std::invalid_argument(which + ": the planes do not bound a finite region (it is open towards ("
                                  + std::to_string(x[0] / far) + ", " + std::to_string(x[1] / far) + ", "
                                  + std::to_string(x[2] / far) + "))");
  return v;
}
} // namespace talus::dem
