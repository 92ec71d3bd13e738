#pragma once

#include "dem/Scene.h"
#include "dem/types.h"

#include <vector>

namespace talus::dem
{
/// The bodies whose axis-aligned bounding box, grown by `grow` on every side, overlaps the box
/// [lo, hi] (Yade's Collider::probeBoundingVolume, with the collider's skin as `grow`): spheres,
/// facets, boxes, walls (a plane: unbounded along its two other axes), Potential Blocks and
/// Particles (their bounding sphere). Clumps are found through their members; erased bodies
/// never. Particle factories test a new particle's place with it.
[[nodiscard]] std::vector<BodyId> bodiesInBox(const Scene& scene, const Vec3& lo, const Vec3& hi, double grow);
} // namespace talus::dem
