#pragma once

#include "dem/core/Scene.h"
#include "dem/base/types.h"

#include <vector>

namespace talus::dem
{
/// The bodies whose axis-aligned bounding box, grown by `grow` on every side, overlaps the box
/// [lo, hi] (Yade's Collider::probeBoundingVolume, with the collider's skin as `grow`): spheres,
/// facets, boxes, walls (a plane: unbounded along its two other axes), Potential Blocks and
/// Particles (their bounding sphere). Clumps are found through their members; erased bodies
/// and facets without bound (Yade's noBound) never. Particle factories test a new particle's place with it.
/// @param lo, hi the box's corners (m)
/// @param grow added to every body's bounding box on each side (m)
/// @return the ids, in id order
[[nodiscard]] std::vector<BodyId> bodiesInBox(const Scene& scene, const Vec3& lo, const Vec3& hi, double grow);

/// The bodies bodiesInBox finds around a sphere of centre `c` and radius `r` that a sphere
/// there would touch (Yade's geometry functors called on them): spheres closer than the radii,
/// facets, boxes and walls closer than r; Potential Blocks and Particles by their bounding
/// sphere. Body `except` (a body being moved) is left out.
/// @param c, r the sphere's centre and radius (m)
/// @param except a body id left out, or -1
/// @return the ids, in id order
[[nodiscard]] std::vector<BodyId> bodiesTouchingSphere(const Scene& scene, const Vec3& c, double r, BodyId except = -1);
} // namespace talus::dem
