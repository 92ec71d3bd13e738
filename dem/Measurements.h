#pragma once

#include "dem/types.h"

namespace talus::dem
{
class Scene;

/// Yade's unbalancedForce: the mean (or, with useMaxForce, the largest) magnitude of the total
/// force on dynamic bodies, gravity included, divided by the mean magnitude of contact forces.
/// 0 for a scene at equilibrium; NaN when there is no contact force to compare with.
double unbalancedForce(const Scene& scene, const Vec3& gravity, bool useMaxForce = false);

/// Gravity of the scene's (first) NewtonIntegrator, zero without one: what unbalancedForce
/// needs when an engine calls it.
Vec3 sceneGravity(const Scene& scene);

/// Love-Weber homogenised stress -(1/V) sum over real contacts of f (x) l, with f the force on
/// body 2 and l the branch vector from body 1's centre to body 2's (image) centre (for a wall or
/// facet: from the sphere's closest point on it to its centre); compression is negative, as
/// Yade's getStress. `volume` <= 0 means the periodic cell's volume.
Mat3 loveWeberStress(const Scene& scene, double volume = -1);

/// Yade's avgNumInteractions: 2 Nc / N over live spheres (optionally not counting spheres with
/// no contact, `skipFree`).
double coordinationNumber(const Scene& scene, bool skipFree = false);

/// Fabric tensor (1/Nc) sum n (x) n over real sphere-sphere contacts.
Mat3 fabricTensor(const Scene& scene);

/// Total volume of the live spheres.
double sphereVolume(const Scene& scene);
} // namespace talus::dem
