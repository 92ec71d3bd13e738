#pragma once

// The shape lookup, the contact probe and the 2D-mode check that the Potential Block and
// Potential Particle bindings share (blocks_wrappers.cpp, particles_wrappers.cpp).
#include "dem/shapes/ConvexContact.h"
#include "dem/core/Scene.h"

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::dem
{
/// The shape of body `id`, one of `list` (Bodies::blocks or Bodies::particles: the shapes of
/// kind `kind`, called `name` in the error).
/// @throws std::invalid_argument naming the body unless it exists and is of that kind
template <class Shape>
const Shape& convexShapeOf(const Scene& s, BodyId id, ShapeKind kind, std::vector<Shape> Bodies::*list,
                           const char* name)
{
  s.checkBody(id);
  const auto i = static_cast<std::size_t>(id);
  if (s.bodies.shape[i] != kind)
    throw std::invalid_argument("body " + std::to_string(id) + " is not a " + name);
  return (s.bodies.*list)[static_cast<std::size_t>(s.bodies.shapeIndex[i])];
}

/// The 2D mode's settings of a geometry functor (`functor`, e.g. "Ig2_PP_PP_ScGeom"): twoDdir a
/// finite non-zero vector, unitWidth2D finite and > 0.
/// @throws std::invalid_argument naming the functor's attribute otherwise
inline void checkTwoDimension(const std::string& functor, const Vec3& twoDdir, double unitWidth2D)
{
  if (!twoDdir.allFinite() || !(twoDdir.norm() > 0))
    throw std::invalid_argument(functor + ".twoDdir must be a finite non-zero vector, got (" + std::to_string(twoDdir[0])
                                + ", " + std::to_string(twoDdir[1]) + ", " + std::to_string(twoDdir[2]) + ")");
  if (!std::isfinite(unitWidth2D) || !(unitWidth2D > 0))
    throw std::invalid_argument(functor + ".unitWidth2D must be finite and > 0, got " + std::to_string(unitWidth2D));
}

/// The contact geometry of a pair as it stands (no history), with the solver's mean wall time over
/// `repeats` calls: `seconds` from a cold start (a new contact's cost), `secondsWarm` starting from
/// the contact point found (a persistent contact's cost). `check(scene, id)` throws unless the body
/// has the shape; body 1 may be a wall. `solve(bodies, i1, i2, previous, g, accuracyTol)` is the
/// shape's contact routine.
/// @throws std::invalid_argument unless accuracyTol is finite and > 0
template <class Check, class Solve>
pybind11::dict probeConvexContact(const Scene& s, BodyId id1, BodyId id2, int repeats, double accuracyTol, Check check,
                                  Solve solve)
{
  if (!std::isfinite(accuracyTol) || !(accuracyTol > 0))
    throw std::invalid_argument("accuracyTol (the contact solver's tolerance) must be finite and > 0, got "
                                + std::to_string(accuracyTol));
  s.checkBody(id1);
  check(s, id2);
  const auto i1 = static_cast<std::size_t>(id1), i2 = static_cast<std::size_t>(id2);
  if (s.bodies.shape[i1] != ShapeKind::Wall)
    check(s, id1);
  ConvexContactGeometry g;
  bool touching = false;
  const int n = std::max(repeats, 1);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < n; ++k)
    touching = solve(s.bodies, i1, i2, nullptr, g, accuracyTol);
  const auto t1 = std::chrono::steady_clock::now();
  pybind11::dict out;
  out["touching"] = touching;
  out["lpSolves"] = g.lpSolves;
  out["seconds"] = std::chrono::duration<double>(t1 - t0).count() / n;
  if (touching)
  {
    const Vec3 previous = g.contactPoint;
    for (int k = 0; k < n; ++k)
      solve(s.bodies, i1, i2, &previous, g, accuracyTol);
    out["secondsWarm"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count() / n;
    out["normal"] = g.normal;
    out["contactPoint"] = g.contactPoint;
    out["penetrationDepth"] = g.penetration;
    out["contactArea"] = g.area;
  }
  return out;
}
} // namespace talus::dem
