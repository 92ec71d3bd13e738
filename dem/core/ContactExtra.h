#pragma once

#include "dem/base/types.h"

#include <cstdint>

namespace talus::dem
{
/// Per-contact state of the richer contact models, kept beside the contact list (same index,
/// `Contacts::extra`) only while a law that needs it is in use: plain sphere contacts (linear,
/// visco-elastic) neither store nor copy it.
///
/// Groups named as Yade's classes: the constants of MindlinPhys, the relative rotation of
/// ScGeom6D, the bond and moment state of CohFrictPhys, the rolling resistance of ViscElPhys.
struct ContactExtra
{
  // MindlinPhys: F_n = kno u^1.5, k_s = kso u^0.5; betan, betas: damping ratios (fractions of
  // the critical damping 2 sqrt(m kn), Thornton's model).
  double kno = 0, kso = 0, betan = 0, betas = 0;

  // ScGeom6D: orientations when the contact was created; twist (rotation about the normal) and
  // bending (rotation vector normal to it) of body 1 relative to body 2 since then.
  Quat initialOrientation1 = Quat::Identity(), initialOrientation2 = Quat::Identity();
  Vec3 bending = Vec3::Zero();
  double twist = 0;

  // CohFrictPhys: bond strengths (forces), rolling/twisting stiffnesses and plastic limits
  // (moments per unit normal force, negative: no limit), plastic normal displacement (unp,
  // with its limit unpMax, negative: none) and the moments (incremental form: history).
  double normalAdhesion = 0, shearAdhesion = 0, kr = 0, ktw = 0, maxRollPl = -1, maxTwistPl = -1, unp = 0,
         unpMax = -1;
  Vec3 momentBending = Vec3::Zero(), momentTwist = Vec3::Zero();
  std::uint8_t cohesionBroken = 1; ///< no bond (bodies interact only by contact)
  std::uint8_t fragile = 1;        ///< the bond breaks for good at its first failure
  std::uint8_t momentRotationLaw = 0;
  std::uint8_t cohesionDisablesFriction = 0;

  // ViscElPhys with rolling resistance: its coefficient and type (Yade's mR, mRtype); the
  // moment itself, recomputed every step, is momentBending above.
  double mR = 0;
  std::uint8_t mRtype = 1;

  // KnKsPBPhys: area of the overlap region's section (Potential Block contacts).
  double contactArea = 0;
  // KnKsPBPhys with useFaceProperties: a bond across two intact-rock faces (a rock bridge or a
  // cemented joint); its strengths, the faces' cohesion and tension times the contact area when
  // it formed, are shearAdhesion and normalAdhesion above; broken flags as Yade's (1: no
  // cohesion, resp. no tension, any more).
  std::uint8_t intactRock = 0;
  std::uint8_t tensionBroken = 1;
};
} // namespace talus::dem
