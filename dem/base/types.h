#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>

/// The DEM core: bodies, materials, contacts, engines and the scene that runs them.
namespace talus::dem
{
using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

/// Body identifier: the index of the body in the scene's arrays; stable for the body's life.
using BodyId = std::int32_t;

/// Degrees of freedom that can be blocked (Yade's blockedDOFs letters x, y, z, X, Y, Z).
enum Dof : std::uint8_t
{
  DofX = 1,
  DofY = 2,
  DofZ = 4,
  DofRX = 8,
  DofRY = 16,
  DofRZ = 32,
  DofAll = 63
};
} // namespace talus::dem
