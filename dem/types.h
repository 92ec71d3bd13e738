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

/// Loops over fewer bodies or contacts than this run on one thread (OpenMP `if` clause): for
/// small scenes forking the threads costs more than the work, and far more on a loaded machine.
/// Results do not depend on it (sums are per body or per fixed block in any case).
inline constexpr std::int64_t parallelMinimum = 256;

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
