#pragma once

#include "dem/core/Bodies.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

/// The DEM over MPI ranks: partition of the bodies (Zoltan), their migration and ghosts.
namespace talus::dem::distributed
{
/// A body's identity across ranks: its id in the scene the user built, kept when it migrates
/// (the local row of a body changes at every migration, its global id never).
using GlobalId = std::int64_t;

/// The bodies one rank holds: rows of a Bodies structure-of-arrays, and each row's global id.
struct RankBodies
{
  Bodies bodies;
  std::vector<GlobalId> globalId; ///< entry k: the global id of row k

  /// The number of rows (bodies held by the rank).
  [[nodiscard]] std::size_t size() const { return globalId.size(); }
};

/// Visit every per-body array of `bodies` (the ones indexed by BodyId), as f(vector&). The one
/// list of them: packing, unpacking and compacting rows all go through it, so a field added to
/// Bodies and not listed here is caught at compile time (BodyRows.cpp) instead of being lost
/// silently when a body changes rank.
/// @param bodies a Bodies, const or not
/// @param f called once per per-body vector, in a fixed order (the packed row's)
template <class B, class F>
void forEachBodyField(B& bodies, F&& f)
{
  f(bodies.pos);
  f(bodies.vel);
  f(bodies.angVel);
  f(bodies.ori);
  f(bodies.angMom);
  f(bodies.force);
  f(bodies.torque);
  f(bodies.extForce);
  f(bodies.extTorque);
  f(bodies.mass);
  f(bodies.inertia);
  f(bodies.radius);
  f(bodies.shape);
  f(bodies.shapeIndex);
  f(bodies.material);
  f(bodies.blockedDofs);
  f(bodies.dynamic);
  f(bodies.damped);
  f(bodies.alive);
  f(bodies.clumpId);
  f(bodies.groupMask);
  f(bodies.temperature);
  f(bodies.heatCapacity);
  f(bodies.conductivity);
  f(bodies.thermalExpansion);
}

/// Bytes of one packed row: every per-body field, then the global id.
/// @return the size (bytes), the same on every rank of one build
std::size_t rowBytes();

/// Append the rows `rows` of `from` to `out`, packed (rowBytes() each).
/// @param from the rank's bodies
/// @param rows the rows packed, in this order
/// @param out appended to
void packRows(const RankBodies& from, std::span<const std::int64_t> rows, std::vector<std::byte>& out);

/// Append the packed rows in `in` (a multiple of rowBytes()) to `into`.
/// @param in packed rows (from packRows, possibly of another rank)
/// @param into the rank's bodies, grown
/// @throws std::invalid_argument if the size of `in` is not a whole number of rows
void unpackRows(std::span<const std::byte> in, RankBodies& into);

/// Keep the rows whose `keep` entry is nonzero, in order, dropping the others.
/// @param bodies compacted in place (rows renumbered)
/// @param keep one flag per row
/// @throws std::invalid_argument if `keep` does not have one entry per row
void keepRows(RankBodies& bodies, std::span<const std::uint8_t> keep);

/// The first row of `bodies` the partition cannot place (not a sphere or a clump, or a clump
/// member: members go with their clump, which is placed), or -1 when all can be.
/// @param bodies a rank's bodies
/// @return the row, or -1
[[nodiscard]] std::int64_t firstUndistributable(const RankBodies& bodies);
} // namespace talus::dem::distributed
