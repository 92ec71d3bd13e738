#pragma once

#include "dem/core/Bodies.h"
#include "dem/shapes/ConvexContact.h"

namespace talus::dem
{
/// The Potential Particles' default solver tolerance (see potentialParticleContact): the
/// overlap is then as accurate as at 1e-13 (cases/dem/dem_potential_accuracy.py), while tighter
/// values cost many more iterations where a small k leaves the potentials nearly flat.
constexpr double defaultParticleAccuracyTol = 1e-8;

/// Overlap of two Potential Particles i1, i2, or of wall i1 and particle i2 (Yade's
/// Ig2_PP_PP_ScGeom; see docs/blocks.md).
///
/// Two particles: the point x* minimising max(f1, f2) (both potentials convex, the second
/// strictly): they overlap iff max(f1, f2)(x*) < 0. It is found through the concave dual
/// phi(mu) = min_x mu f1 + (1 - mu) f2 over mu in [0, 1], whose slope f1 - f2 at the inner
/// minimiser x(mu) decreases with mu: Newton steps on mu kept inside a bracket (so it always
/// converges), each inner minimisation by Newton steps with a line search. A positive dual
/// value proves separation early. The normal is grad f1 (= -grad f2 at x*, both averaged),
/// the penetration the chord of {f1 <= 0, f2 <= 0} through x* along it, the contact point its
/// middle. A wall: the particle's support point against it gives depth and contact point.
/// The contact area: the section of the overlap region through the contact point normal to
/// the normal, area 1/2 sum rho(theta)^2 dtheta over 72 rays (trapezoidal rule on a periodic
/// function).
/// `previous` (may be null): last step's contact point, a warm start.
/// `accuracyTol` (Yade's name): the dual iteration stops once |f1 - f2| <= accuracyTol at x*
/// (f is dimensionless, -1 at the centre; its gradient at the surface is about 2 / r, so the
/// point is then within about accuracyTol r / 2 of the equal-potential surface), the inner
/// minimisations and the chord's ends once their steps are below min(accuracyTol / 10, 1e-9) R;
/// a contact is reported only once its point is inside both (however loose the tolerance).
/// @param b the scene's bodies
/// @param i1, i2 the bodies' ids (i1 may be a wall)
/// @param previous the last step's contact point (world, m), or null
/// @param out the contact's normal, penetration, point and area when they overlap
/// @param accuracyTol the dual iteration's tolerance on |f1 - f2| (dimensionless)
/// @return false if the shapes do not overlap
bool potentialParticleContact(const Bodies& b, std::size_t i1, std::size_t i2, const Vec3* previous,
                              ConvexContactGeometry& out, double accuracyTol = defaultParticleAccuracyTol);

/// World-frame axis-aligned bounding box of particle i: its support points along +-x, y, z
/// (exact for any orientation).
/// @param i the particle's body id
/// @param lo, hi set to the box's corners
void potentialParticleAabb(const Bodies& b, std::size_t i, Vec3& lo, Vec3& hi);
} // namespace talus::dem
