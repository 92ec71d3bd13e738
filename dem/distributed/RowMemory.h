#pragma once

#include "dem/core/EnergyTracker.h"
#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <span>
#include <utility>
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
/// new to a serial scene, so its first step's work is taken over that step alone; its pending growth
/// comes from shareGrowth).
/// @param energy the scene's tracker (nothing to do when it keeps no such memory)
/// @param before the global id of each row before, ascending
/// @param after the global id of each row now, ascending
void followRows(EnergyTracker& energy, std::span<const GlobalId> before, std::span<const GlobalId> after);

/// A growth not yet seen by the contacts, by body: (global id, EnergyTracker::grownBy), ascending.
using PendingGrowth = std::vector<std::pair<GlobalId, double>>;

/// The pending growth of this rank's own bodies (the rows `ownedRows` of `globalId`), before a
/// re-detection moves them: what shareGrowth hands to whichever ranks hold them next.
[[nodiscard]] PendingGrowth ownGrowth(const EnergyTracker& energy, std::span<const GlobalId> globalId,
                                      std::span<const std::int64_t> ownedRows);

/// After a re-detection laid the rows out again, every row's pending growth from its owner's
/// (collective: every rank's `own` gathered, 16 bytes a grown body, once per growParticles). A body
/// new to a rank, migrated or a new ghost, grew before it arrived: followRows alone would give it
/// none, and the contacts it makes there would miss that growth's energy. Rows `replicated` (walls,
/// every rank's alike) keep theirs.
void shareGrowth(MPI_Comm comm, EnergyTracker& energy, const PendingGrowth& own, std::span<const GlobalId> rows,
                 std::span<const std::uint8_t> replicated);
} // namespace talus::dem::distributed
