#pragma once

// The leap-frog step of four free spheres at a time in the lanes of AVX2 where the processor
// has it: NewtonIntegrator's sphere path, the same operations in the same order lane by lane,
// so the same bits.
#include "dem/core/Bodies.h"

#include <cstddef>

namespace talus::dem
{
/// How many bodies integrateSphereBatch takes at once.
inline constexpr int sphereIntegrationWidth = 4;

/// The affine field that velocities carry in a deforming periodic cell (homoDeform): a
/// velocity is L x plus the fluctuation that forces act on, an angular velocity the field's
/// spin plus its own.
struct AffineField
{
  Mat3 velGrad, previousVelGrad; ///< L of this step and of the previous one
  Vec3 spin, previousSpin;       ///< their spins
};

/// What the integrator's spheres share.
struct SphereStepParameters
{
  const Vec3* invMass;    ///< per body, by component (zero along a blocked DOF)
  const Vec3* invInertia; ///< per body, by component
  Vec3 gravity;
  bool dampGravity;
  double damping; ///< Cundall's, for the bodies it damps (State.isDamped)
  double dt;
  const AffineField* field; ///< in a deforming periodic cell, else null
};

/// Whether this processor runs integrateSphereBatch (AVX2), asked once.
bool sphereIntegrationAvailable();

/// Bodies first to first + 3, each a live, dynamic body of NewtonIntegrator's plain path (a
/// sphere or wall, not a clump, member, aspherical or masked body) without blocked DOFs, with
/// a finite force and torque, without energy tracking: velocities from the forces (gravity,
/// Cundall's damping; in a deforming cell on the fluctuations, the field added back), positions,
/// and the orientations turned by the step's rotation where it is under 1e-3 rad (its series; a
/// larger turn is left to the caller).
/// @param first the first body's index
/// @return the lanes whose orientation is left to the caller: bit i for body first + i
unsigned integrateSphereBatch(Bodies& b, std::size_t first, const SphereStepParameters& p);
} // namespace talus::dem
