#include "dem/shapes/PotentialParticle.h"
#include "dem/shapes/PlaneSet.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace talus::dem
{
double PlacedPotential::eval(const Vec3& x, Vec3* grad, Mat3* hess) const
{
  const Vec3 y = x - o;
  double sum = 0;
  if (grad)
    *grad = 2 * beta * y;
  if (hess)
    *hess = (2 * beta) * Mat3::Identity();
  for (std::size_t i = 0; i < N.size(); ++i)
  {
    const double g = N[i].dot(x) - D[i];
    if (g <= 0)
      continue;
    sum += g * g;
    if (grad)
      *grad += (2 * alpha * g) * N[i];
    if (hess)
      *hess += (2 * alpha) * N[i] * N[i].transpose();
  }
  return alpha * sum + beta * y.squaredNorm() - 1;
}

namespace
{
/// w1 f1 + w2 f2 - c . x with its gradient and Hessian.
double combined(const PlacedPotential& f1, double w1, const PlacedPotential* f2, double w2, const Vec3& c,
                const Vec3& x, Vec3* g, Mat3* H)
{
  Vec3 g1, g2;
  Mat3 H1, H2;
  double v = w1 * f1.eval(x, g ? &g1 : nullptr, H ? &H1 : nullptr) - c.dot(x);
  if (g)
    *g = w1 * g1 - c;
  if (H)
    *H = w1 * H1;
  if (f2 && w2 != 0)
  {
    v += w2 * f2->eval(x, g ? &g2 : nullptr, H ? &H2 : nullptr);
    if (g)
      *g += w2 * g2;
    if (H)
      *H += w2 * H2;
  }
  return v;
}

/// A potential restricted to the ray x + t u: per plane N_i . x - D_i and N_i . u, so that its
/// value and slope at t cost one multiply-add per plane instead of a 3D gradient (the rays of
/// the contact area are most of a contact's cost).
struct RayRestriction
{
  std::vector<double> a, b;
  double alpha = 0, beta = 0, yu = 0, yy = 0, uu = 0;

  void set(const PlacedPotential& f, const Vec3& x, const Vec3& u)
  {
    a.resize(f.N.size());
    b.resize(f.N.size());
    for (std::size_t i = 0; i < f.N.size(); ++i)
    {
      a[i] = f.N[i].dot(x) - f.D[i];
      b[i] = f.N[i].dot(u);
    }
    const Vec3 y = x - f.o;
    alpha = f.alpha;
    beta = f.beta;
    yu = y.dot(u);
    yy = y.squaredNorm();
    uu = u.squaredNorm();
  }

  double value(double t, double& slope) const
  {
    double sum = 0, dsum = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      const double g = a[i] + b[i] * t;
      if (g > 0)
      {
        sum += g * g;
        dsum += g * b[i];
      }
    }
    slope = 2 * (alpha * dsum + beta * (yu + t * uu));
    return alpha * sum + beta * (yy + t * (2 * yu + t * uu)) - 1;
  }
};

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from Chebyshev guesses).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w)
{
  x.resize(static_cast<std::size_t>(n));
  w.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it)
    {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k)
      {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16)
        break;
    }
    x[static_cast<std::size_t>(i)] = z;
    w[static_cast<std::size_t>(i)] = 2 / ((1 - z * z) * dp * dp);
  }
}

using ShapeKey = std::tuple<std::vector<double>, std::vector<double>, std::vector<double>, std::vector<double>, double,
                            double, double, int>;
} // namespace

void minimisePotentials(const PlacedPotential& f1, double w1, const PlacedPotential* f2, double w2, const Vec3& c,
                        Vec3& x, Mat3* hessian, double tol)
{
  const double stepTol = tol * f1.length;
  Vec3 g;
  Mat3 H;
  double v = combined(f1, w1, f2, w2, c, x, &g, &H);
  for (int iter = 0; iter < 100; ++iter)
  {
    const Vec3 dx = -H.ldlt().solve(g);
    if (!dx.allFinite())
      break;
    const double descent = g.dot(dx);
    if (!(descent < 0) || dx.norm() <= stepTol)
      break;
    // Backtracking (Armijo): a full step is exact once the active planes are right.
    double t = 1, vt = 0;
    Vec3 xt;
    for (int k = 0; k < 60; ++k, t *= 0.5)
    {
      xt = x + t * dx;
      vt = combined(f1, w1, f2, w2, c, xt, nullptr, nullptr);
      if (vt <= v + 1e-4 * t * descent)
        break;
    }
    // No decrease left at working precision: x is the minimum (to rounding, or along a nearly
    // flat direction of a small k, where going on would repeat the same failed search).
    if (!(vt < v))
      break;
    x = xt;
    v = combined(f1, w1, f2, w2, c, x, &g, &H);
    // A full step this short from a converging Newton iteration leaves an error of its
    // square: done (with the default tol, steps of 1e-10 R and gradients of 1e-12 / R).
    if (t == 1 && dx.norm() <= 1e4 * stepTol && g.norm() * f1.length <= 1e2 * tol)
      break;
  }
  if (hessian)
    *hessian = H;
}

double rayExit(const PlacedPotential& f1, const PlacedPotential* f2, const Vec3& x, const Vec3& u, double guess,
               double scale, double tol)
{
  thread_local RayRestriction r1, r2; // their buffers are reused from call to call
  r1.set(f1, x, u);
  if (f2)
    r2.set(*f2, x, u);
  // max(f1, f2) along the ray and the slope of the larger one
  auto rayValue = [&](double t, double& slope) {
    double v = r1.value(t, slope);
    if (f2)
    {
      double s2 = 0;
      const double v2 = r2.value(t, s2);
      if (v2 > v)
      {
        v = v2;
        slope = s2;
      }
    }
    return v;
  };
  double t = guess > 0 ? guess : scale, slope = 0;
  double v = rayValue(t, slope);
  // From inside, a convex function's tangent lies below it: a Newton step lands on or beyond
  // the root (the previous ray's length is usually a close guess). It is capped at doubling t:
  // where the potential is nearly flat (k -> 0, inside the planes) the tangent's root is far
  // out, and Newton from there would only halve the distance per step.
  for (int k = 0; k < 200 && v <= 0; ++k)
  {
    if (v == 0)
      return t;
    t = slope > 0 ? std::min(t - v / slope, 2 * t) : 2 * t;
    v = rayValue(t, slope);
  }
  // Newton from outside: for a convex function the tangent's root lies between the root and t.
  for (int iter = 0; iter < 100 && v > 0 && slope > 0; ++iter)
  {
    const double step = v / slope;
    t -= step;
    if (step <= tol * scale)
      break;
    v = rayValue(t, slope);
  }
  return t;
}

void supportPoint(const PlacedPotential& f, const Vec3& e, Vec3& x, const Vec3* nearby)
{
  if (nearby)
  {
    // Newton on (x, s): grad f(x) - s e = 0, f(x) = 0; quadratic once the active planes are
    // right. Accepted only if it ends on the surface with grad f along +e.
    Vec3 y = *nearby, g;
    Mat3 H;
    double v = f.eval(y, &g, &H), s = std::max(g.dot(e), 0.0);
    for (int iter = 0; iter < 30; ++iter)
    {
      Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
      J.topLeftCorner<3, 3>() = H;
      J.block<3, 1>(0, 3) = -e;
      J.block<1, 3>(3, 0) = g.transpose();
      Eigen::Vector4d F;
      F << g - s * e, v;
      const Eigen::Vector4d step = J.partialPivLu().solve(-F);
      if (!step.allFinite())
        break;
      y += step.head<3>();
      s += step[3];
      v = f.eval(y, &g, &H);
      if (step.head<3>().norm() <= 1e-13 * f.length)
      {
        if (s > 0 && std::abs(v) < 1e-10 && (g - s * e).norm() <= 1e-8 * g.norm())
        {
          x = y;
          return;
        }
        break;
      }
    }
  }
  minimisePotentials(f, 1, nullptr, 0, Vec3::Zero(), x);
  if (!(f.eval(x) < 0))
    return;
  // Bracket the Lagrange multiplier: at the surface |grad f| is between 2 beta R and about 2 / r.
  const Vec3 start = x;
  Vec3 xs = x;
  double hi = 1 / f.length;
  for (int k = 0; k < 200; ++k, hi *= 2)
  {
    xs = start;
    minimisePotentials(f, 1, nullptr, 0, hi * e, xs);
    if (f.eval(xs) > 0)
      break;
  }
  Vec3 xm = xs;
  decreasingRoot(
      [&](double s, double& slope) {
        Mat3 H;
        minimisePotentials(f, 1, nullptr, 0, s * e, xm, &H);
        slope = -s * e.dot(H.ldlt().solve(e));
        return -f.eval(xm);
      },
      0.0, hi, 0.5 * hi, 1e-13, 1e-14 * hi);
  x = xm;
}

PlacedPotential placePotential(const PotentialParticleShape& s, const Vec3& pos, const Quat& ori, const Vec3& origin)
{
  // y = A^T... shape coordinates: y = axes * ori^-1 (x - pos) + centroid = M (x - pos) + centroid.
  const Mat3 M = s.axes * ori.toRotationMatrix().transpose();
  PlacedPotential p;
  p.alpha = (1 - s.k) / (s.r * s.r);
  p.beta = s.k / (s.R * s.R);
  p.length = s.R;
  const Vec3 rel = pos - origin;
  p.o = rel - M.transpose() * s.centroid;
  p.N.resize(s.normals.size());
  p.D.resize(s.normals.size());
  for (std::size_t i = 0; i < s.normals.size(); ++i)
  {
    p.N[i] = M.transpose() * s.normals[i];
    // n . (M (x - pos) + c) - d = N . x - (N . rel - n . c + d)
    p.D[i] = p.N[i].dot(rel) - s.normals[i].dot(s.centroid) + s.d[i];
  }
  return p;
}

PotentialParticleShape makePotentialParticle(const std::vector<double>& a, const std::vector<double>& b,
                                             const std::vector<double>& c, const std::vector<double>& d, double r,
                                             double k, double R, bool isBoundary, const std::string& which,
                                             int quadrature)
{
  const std::vector<Vec3> n = planeNormals(a, b, c, d, which);
  if (!std::isfinite(k) || !(k > 0) || k > 1)
    throw std::invalid_argument(which + ": k (the sphericity fraction) must be in (0, 1], got " + std::to_string(k));
  if (!std::isfinite(r) || !(r > 0))
    throw std::invalid_argument(which + ": r (the rounding) must be finite and > 0, got " + std::to_string(r));
  if (!std::isfinite(R) || !(R > 0))
    throw std::invalid_argument(which + ": R (the shadow sphere's radius) must be finite and > 0, got "
                                + std::to_string(R));
  if (n.size() < 4)
    throw std::invalid_argument(which + ": the planes must bound a finite region: at least 4 are needed, got "
                                + std::to_string(n.size()));
  // The particle lies within the planes expanded by r: they must close a finite region.
  std::vector<double> h(n.size());
  for (std::size_t i = 0; i < n.size(); ++i)
    h[i] = d[i] + r;
  boundedPolyhedronVertices(n, h, which);

  static std::mutex cacheMutex;
  static std::map<ShapeKey, PotentialParticleShape> cache;
  const ShapeKey key{a, b, c, d, r, k, R, quadrature};
  {
    std::lock_guard<std::mutex> lock(cacheMutex);
    auto it = cache.find(key);
    if (it != cache.end())
    {
      PotentialParticleShape s = it->second;
      s.isBoundary = isBoundary;
      return s;
    }
  }

  PotentialParticleShape s;
  s.normals = n;
  s.d = d;
  s.r = r;
  s.k = k;
  s.R = R;
  s.isBoundary = isBoundary;
  const PlacedPotential f = placePotential(s, Vec3::Zero(), Quat::Identity(), Vec3::Zero());
  // An interior point: the potential's minimum.
  Vec3 x0 = Vec3::Zero();
  minimisePotentials(f, 1, nullptr, 0, Vec3::Zero(), x0);
  if (!(f.eval(x0) < -1e-9))
    throw std::invalid_argument(which + ": the potential is nowhere negative: the particle is empty (d too small for r)");

  // Moments about x0 over rays u(theta, phi): integral of rho^(m + 3) / (m + 3) u^m dOmega.
  std::vector<double> ct, wt;
  gaussLegendre(quadrature, ct, wt);
  const int nphi = 2 * quadrature;
  double V = 0, farthest = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  double rho = 0;
  for (int i = 0; i < quadrature; ++i)
  {
    const double cz = ct[static_cast<std::size_t>(i)], sz = std::sqrt(1 - cz * cz);
    for (int j = 0; j < nphi; ++j)
    {
      const double phi = 2 * M_PI * j / nphi;
      const Vec3 u(sz * std::cos(phi), sz * std::sin(phi), cz);
      rho = rayExit(f, nullptr, x0, u, rho, R);
      const double w = wt[static_cast<std::size_t>(i)] * 2 * M_PI / nphi;
      const double r3 = rho * rho * rho;
      V += w * r3 / 3;
      first += (w * r3 * rho / 4) * u;
      second += (w * r3 * rho * rho / 5) * (u * u.transpose());
    }
  }
  const Vec3 centroid = x0 + first / V;
  // Second moment about the centroid: shift from x0 by the parallel-axis rule.
  const Vec3 g = first / V; // centroid relative to x0
  const Mat3 central = second - V * g * g.transpose();
  const Mat3 inertia = central.trace() * Mat3::Identity() - central;
  // Principal axes, kept as the shape's own axes when the tensor is diagonal to the
  // integration's accuracy (a symmetric particle's eigenvectors are otherwise arbitrary).
  Mat3 Q = Mat3::Identity();
  Vec3 moments = inertia.diagonal();
  const Mat3 off = inertia - Mat3(inertia.diagonal().asDiagonal());
  if (off.norm() > 1e-9 * inertia.trace())
  {
    Eigen::SelfAdjointEigenSolver<Mat3> eig(inertia);
    Q = eig.eigenvectors();
    if (Q.determinant() < 0)
      Q.col(2) = -Q.col(2);
    moments = eig.eigenvalues();
  }
  s.axes = Q;
  s.centroid = centroid.norm() > 1e-12 * R ? centroid : Vec3::Zero();
  s.volume = V;
  s.inertiaPerDensity = moments;
  // Bounding radius about the centroid: the largest ray from it, with a margin for the
  // directions between rays.
  const PlacedPotential fc = placePotential(s, Vec3::Zero(), Quat::Identity(), Vec3::Zero());
  Vec3 xc = Vec3::Zero();
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 48; ++j)
    {
      const double cz = std::cos(M_PI * (i + 0.5) / 24), sz = std::sqrt(1 - cz * cz), phi = 2 * M_PI * j / 48;
      farthest = std::max(farthest, rayExit(fc, nullptr, xc, Vec3(sz * std::cos(phi), sz * std::sin(phi), cz), farthest, R));
    }
  s.boundingRadius = 1.05 * farthest;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 24; ++j)
    {
      const double cz = std::cos(M_PI * (i + 0.5) / 12), sz = std::sqrt(1 - cz * cz), phi = 2 * M_PI * j / 24;
      const Vec3 u(sz * std::cos(phi), sz * std::sin(phi), cz);
      s.samples.push_back(rayExit(fc, nullptr, xc, u, 0, R) * u);
    }
  {
    std::lock_guard<std::mutex> lock(cacheMutex);
    cache.emplace(key, s);
  }
  return s;
}
} // namespace talus::dem
