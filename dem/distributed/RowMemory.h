#pragma once

#include "dem/core/EnergyTracker.h"
#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <array>
#include <span>
#include <type_traits>
#include <vector>

namespace talus::dem::distributed
{
/// After a rank's rows were laid out again (a re-detection's migration and ghost rebuild), the
/// per-body memory a scene keeps outside Bodies follows its bodies: the energy tracker's last
/// imposed displacement and rotation of each body (EnergyTracker::previousDisplacement,
/// previousRotation), by which the work of a moving wall or of a blocked DOF is taken over two
/// steps; and the radius growth not yet seen by the contacts (EnergyTracker::grownBy), from
/// which the next contacts pass takes the energy a growth put into them (growthWork). The row
/// of global id g takes what g's row held; a body new to the rank starts afresh (NaN, as a body
/// new to a serial scene; no growth) until shareMemory hands it its owner's memory.
/// @param energy the scene's tracker (nothing to do when it keeps no such memory)
/// @param before the global id of each row before, ascending
/// @param after the global id of each row now, ascending
void followRows(EnergyTracker& energy, std::span<const GlobalId> before, std::span<const GlobalId> after);

/// What the energy tracker remembers of one body, by global id, as it travels to the ranks that
/// hold the body next.
struct Remembered
{
  GlobalId id;
  double grownBy; ///< EnergyTracker::grownBy (0: none)
  /// EnergyTracker::previousDisplacement and previousRotation (NaN: none), as plain doubles: the
  /// record travels as bytes.
  std::array<double, 3> displacement, rotation;
};
static_assert(std::is_trivially_copyable_v<Remembered>);

/// The memory of this rank's own bodies (the rows `ownedRows` of `globalId`) that a body new to a
/// rank would otherwise lose, before a re-detection moves them: a growth not yet seen by the
/// contacts (every grown body), and when `imposed`, the last imposed motion of each body moved by
/// velocities or with blocked DOFs (what kinematicWork averages over two steps).
[[nodiscard]] std::vector<Remembered> ownMemory(const EnergyTracker& energy, const Bodies& bodies,
                                                std::span<const GlobalId> globalId,
                                                std::span<const std::int64_t> ownedRows, bool imposed);

/// After a re-detection laid the rows out again (and followRows ran), every row's memory from its
/// owner's (collective: every rank's `own` gathered, 64 bytes a body listed). A body new to a
/// rank, migrated or a new ghost, grew or moved before it arrived: followRows alone would give it
/// no growth (its contacts there would miss the growth's energy) and no last motion. Called when
/// a growth is pending (after growParticles: once) or the ranks partitioned again (bodies may then
/// land where no copy of them was). Rows `replicated` (walls, every rank's alike) keep theirs.
void shareMemory(MPI_Comm comm, EnergyTracker& energy, const std::vector<Remembered>& own,
                 std::span<const GlobalId> rows, std::span<const std::uint8_t> replicated);
} // namespace talus::dem::distributed
