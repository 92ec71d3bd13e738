#pragma once

#include "dem/core/Bodies.h"

namespace talus::dem
{
/// Place the members of clump body `i` rigidly: position, orientation, velocity (the clump's
/// velocity plus its spin about its centroid) and angular velocity (Yade's Clump::moveMembers).
/// @param b the scene's bodies, the members' state written
/// @param i the clump body's id
inline void moveClumpMembers(Bodies& b, std::size_t i)
{
  const ClumpShape& clump = b.clumps[static_cast<std::size_t>(b.shapeIndex[i])];
  for (std::size_t k = 0; k < clump.members.size(); ++k)
  {
    const auto m = static_cast<std::size_t>(clump.members[k]);
    b.pos[m] = b.pos[i] + b.ori[i] * clump.relPos[k];
    b.ori[m] = b.ori[i] * clump.relOri[k];
    b.vel[m] = b.vel[i] + b.angVel[i].cross(b.pos[m] - b.pos[i]);
    b.angVel[m] = b.angVel[i];
  }
}

/// Add the forces and torques of the members of clump body `i` to `force` and `torque` (about
/// the clump's centroid), member by member in id order (Yade's addForceTorqueFromMembers).
/// @param b the scene's bodies
/// @param i the clump body's id
/// @param force, torque added to (N, N m)
inline void addClumpMemberForces(const Bodies& b, std::size_t i, Vec3& force, Vec3& torque)
{
  for (BodyId id : b.clumps[static_cast<std::size_t>(b.shapeIndex[i])].members)
  {
    const auto m = static_cast<std::size_t>(id);
    force += b.force[m];
    torque += b.torque[m] + (b.pos[m] - b.pos[i]).cross(b.force[m]);
  }
}

/// Mass of the rigid body that body `i` moves with: its clump's for a member.
/// @param b the scene's bodies
/// @param i a body id
/// @return the mass (kg)
inline double rigidMass(const Bodies& b, std::size_t i)
{
  return b.clumpId[i] >= 0 ? b.mass[static_cast<std::size_t>(b.clumpId[i])] : b.mass[i];
}

/// Whether body `i` moves under forces, or with its clump's for a member.
/// @param b the scene's bodies
/// @param i a body id
/// @return the body's dynamic flag, its clump's for a member
inline bool rigidDynamic(const Bodies& b, std::size_t i)
{
  return b.clumpId[i] >= 0 ? b.dynamic[static_cast<std::size_t>(b.clumpId[i])] != 0 : b.dynamic[i] != 0;
}
} // namespace talus::dem
