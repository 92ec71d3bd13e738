#pragma once

#include "dem/base/types.h"

#include <cmath>
#include <string>
#include <vector>

namespace talus::dem
{
/// A Potential Particle (Houlsby 2009, Boon et al. 2013; Yade's PotentialParticle): the region
/// f <= 0 of the normalised potential
///   f(y) = (1 - k) (sum_i <n_i . y - d_i>^2 / r^2 - 1) + k (|y|^2 / R^2 - 1)
/// in the shape frame of the user's planes (Macaulay brackets <x> = max(x, 0)). Both terms are
/// convex and the second strictly so (k > 0), so the particle is strictly convex and f has a
/// unique minimum: every solver below relies on that.
///
/// The body frame is the principal frame at the centroid: y = axes * y_body + centroid.
struct PotentialParticleShape
{
  std::vector<Vec3> normals; ///< unit outward normals n_i (shape frame)
  std::vector<double> d;     ///< plane offsets (the surface lies about r outside them)
  double r = 0, k = 0, R = 0;
  bool isBoundary = false;   ///< boundary particles interact only with non-boundary ones
  Mat3 axes = Mat3::Identity(); ///< principal axes (columns) in the shape frame
  Vec3 centroid = Vec3::Zero(); ///< in the shape frame
  double volume = 0;
  Vec3 inertiaPerDensity = Vec3::Zero(); ///< principal moments / density
  double boundingRadius = 0; ///< largest distance of the surface from the centroid
  std::vector<Vec3> samples; ///< surface points on rays from the centroid (body frame): starting points for support points
};

/// The potential placed in a frame (world, or relative to an origin near a pair): for each
/// plane N_i . x - D_i, and the sphere term's centre o, so that
///   f(x) = alpha sum_i <N_i . x - D_i>^2 + beta |x - o|^2 - 1
/// with alpha = (1 - k) / r^2, beta = k / R^2.
struct PlacedPotential
{
  std::vector<Vec3> N;
  std::vector<double> D;
  Vec3 o = Vec3::Zero();
  double alpha = 0, beta = 0;
  double length = 1; ///< R: the scale of lengths for tolerances

  /// Value of f at x; gradient and Hessian if asked.
  /// @param x the point, in this potential's frame (relative to its origin)
  /// @param grad set to the gradient when not null
  /// @param hess set to the Hessian when not null (piecewise constant: active planes and sphere)
  /// @return f(x): negative inside, 0 on the surface
  double eval(const Vec3& x, Vec3* grad = nullptr, Mat3* hess = nullptr) const;
};

/// Build a particle from Yade's arguments. Volume, centroid and principal inertia are
/// integrated in spherical coordinates about an interior point (the surface distance rho(u)
/// found along each ray): V = sum w rho^3 / 3, first and second moments likewise with rho^4 / 4
/// and rho^5 / 5, on a Gauss-Legendre (cos theta) x uniform (phi) grid of `quadrature` x
/// 2 `quadrature` rays. Identical arguments reuse the previous result.
/// @param a, b, c, d the planes a x + b y + c z = d (unit normals (a, b, c)), Yade's arguments
/// @param r the rounding, > 0
/// @param k the weight of the sphere term |y|^2 / R^2 in the potential, in (0, 1]
/// @param R the reference length, > 0
/// @param isBoundary a boundary particle (interacts with non-boundary ones only)
/// @param which how errors name the particle
/// @param quadrature rays per polar angle of the integration
/// @return the shape with its mass properties per unit density
/// @throws std::invalid_argument starting with `which` (e.g. "PotentialParticle #3") if the
///         arrays differ in length, a value is not finite, a normal is not unit, k is outside
///         (0, 1], r or R is not positive, or the planes expanded by r do not bound a finite
///         non-empty region
PotentialParticleShape makePotentialParticle(const std::vector<double>& a, const std::vector<double>& b,
                                             const std::vector<double>& c, const std::vector<double>& d, double r,
                                             double k, double R, bool isBoundary, const std::string& which,
                                             int quadrature = 96);

/// The particle's potential in world coordinates relative to `origin`, for a body at `pos`
/// turned by `ori` (the body frame is the principal frame).
/// @param s the particle's shape
/// @param pos, ori the body's position (m) and orientation
/// @param origin the frame's origin (m): a point near the pair, so coordinates stay small
/// @return the potential, evaluated with eval() at points relative to `origin`
PlacedPotential placePotential(const PotentialParticleShape& s, const Vec3& pos, const Quat& ori, const Vec3& origin);

/// The minimum over x of w1 f1(x) + w2 f2(x) - c . x (f2 may be null), by Newton steps with a
/// backtracking line search from x (updated in place): f is piecewise quadratic and strongly
/// convex, so this converges, and in one step once the active planes are right.
/// `hessian` (optional): the Hessian there. Stops once a step is below `tol` f1.length.
/// @param f1, w1 the first potential and its weight
/// @param f2, w2 the second potential (null: none) and its weight
/// @param c the linear term (a Lagrange multiplier times a direction)
/// @param x the starting point, replaced by the minimiser
/// @param hessian set, when not null, to the weighted Hessian at the minimiser
/// @param tol the step below which it stops, relative to f1.length
void minimisePotentials(const PlacedPotential& f1, double w1, const PlacedPotential* f2, double w2, const Vec3& c,
                        Vec3& x, Mat3* hessian = nullptr, double tol = 1e-14);

/// Where the ray x + t u (t > 0) leaves {max(f1, f2) <= 0}, from x inside (f2 may be null):
/// Newton steps from outside, which for a convex function approach the root monotonically.
/// `guess`: a length to try first (<= 0: `scale`); stops once a step is below `tol` scale.
/// @param f1, f2 the potentials (f2 null: f1 alone)
/// @param x the ray's origin, inside
/// @param u the ray's unit direction
/// @param guess a first t to try (m); <= 0: scale
/// @param scale the length scale of the tolerance (m)
/// @param tol the step below which it stops, relative to scale
/// @return t at the exit
double rayExit(const PlacedPotential& f1, const PlacedPotential* f2, const Vec3& x, const Vec3& u, double guess,
               double scale, double tol = 1e-14);

/// The point of the particle farthest along the unit direction e (its support point), from
/// the Lagrange condition grad f = s e: for s >= 0, x(s) minimises f - s e . x and f(x(s))
/// grows with s (derivative s e . H^-1 e); s is found by Newton steps kept inside a bracket.
/// `x`: a starting point inside, replaced by the support point. With `nearby` (a surface point
/// whose outward normal is close to e), Newton steps on the Lagrange system
/// (grad f = s e, f = 0) are tried first, kept if they converge to a valid support point.
/// @param f the particle's placed potential
/// @param e the unit direction
/// @param x a point inside on entry; the support point on return
/// @param nearby a surface point whose normal is close to e, or null
void supportPoint(const PlacedPotential& f, const Vec3& e, Vec3& x, const Vec3* nearby = nullptr);

/// A root of a decreasing function g on [lo, hi] by Newton steps (g returns the value and its
/// derivative), falling back to bisection whenever a step leaves the bracket; stops when
/// |g| <= tol, or the bracket or a step is below `width` (Newton converges from one side, so
/// the bracket alone need not shrink).
/// @param g g(x, slope) returns g(x) and sets slope to g'(x)
/// @param lo, hi the bracket: g(lo) >= 0 >= g(hi)
/// @param start the first point, inside the bracket
/// @param tol the |g| at which x is a root
/// @param width the bracket or step width at which it stops
/// @param maxIter evaluations at most
/// @return the last point evaluated, whose state the callers read
template <class G>
double decreasingRoot(G&& g, double lo, double hi, double start, double tol, double width, int maxIter = 100)
{
  double x = start;
  for (int it = 0; it < maxIter; ++it)
  {
    double slope = 0;
    const double v = g(x, slope);
    if (std::abs(v) <= tol)
      return x;
    (v > 0 ? lo : hi) = x;
    if (hi - lo <= width)
      return x;
    double next = slope < 0 ? x - v / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi))
      next = 0.5 * (lo + hi);
    const bool last = std::abs(next - x) <= width || it + 1 == maxIter;
    x = next;
    if (last)
    {
      g(x, slope);
      return x;
    }
  }
  return x;
}
} // namespace talus::dem
