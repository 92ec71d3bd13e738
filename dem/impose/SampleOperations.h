#pragma once

namespace talus::dem
{
class Scene;

/// Yade's growParticles: multiply the radii of the spheres (only dynamic ones if dynamicOnly)
/// by `multiplier`, their mass by its cube and inertia by its fifth power (updateMass), and
/// scale the stiffness and reference radii of their current contacts accordingly (internal
/// compaction of a sample). A clump (a dynamic one if dynamicOnly) grows homothetically about
/// its centroid: its members' offsets and radii by `multiplier`, its mass and principal moments
/// as above (updateMass), its position, orientation and velocities kept. The contacts'
/// penetrations follow the radii and the members' new places at once. While energy is
/// tracked, the jump of the kinetic and elastic energies is booked as growthWork.
/// @param multiplier the factor on the radii, > 0
/// @param updateMass scale the masses and moments of inertia too
/// @param dynamicOnly grow only the dynamic spheres and clumps
/// @throws std::invalid_argument if the multiplier is not positive and finite
void growParticles(Scene& scene, double multiplier, bool updateMass = true, bool dynamicOnly = true);

/// Yade's setContactFriction: set the friction angle (radians) of the materials of dynamic
/// bodies, and the friction tan(min(phi1, phi2)) of the existing contacts (e.g. frictionless
/// compaction to a dense state, then shear with friction).
/// @param angle the friction angle (rad), in [0, pi/2)
/// @throws std::invalid_argument if the angle is not in [0, pi/2)
void setContactFriction(Scene& scene, double angle);
} // namespace talus::dem
