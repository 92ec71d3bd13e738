#pragma once

#include "dem/core/EnergyTracker.h"
#include "dem/distributed/BodyRows.h"

#include <span>

namespace talus::dem::distributed
{
/// After a rank's rows were laid out again (a re-detection's migration and ghost rebuild), the
/// per-body memory a scene keeps outside Bodies follows its bodies: the energy tracker's last
/// imposed displacement and rotation of each body (EnergyTracker::previousDisplacement,
/// previousRotation), by which the work of a moving wall or of a blocked DOF is taken over two
/// steps; and the radius growth not yet seen by the contacts (EnergyTracker::grownBy), from
/// which the next contacts pass takes the energy a growth put into them (growthWork). The row
/// of global id g takes what g's row held; a body new to the rank starts afresh (NaN, as a body
/// new to a serial scene, so its first step's work is taken over that step alone; no growth).
/// @param energy the scene's tracker (nothing to do when it keeps no such memory)
/// @param before the global id of each row before, ascending
/// @param after the global id of each row now, ascending
void followRows(EnergyTracker& energy, std::span<const GlobalId> before, std::span<const GlobalId> after);
} // namespace talus::dem::distributed
