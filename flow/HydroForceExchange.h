#pragma once

// The C++ route of HydroForce into a DEM scene: through the particle exchange interface only.
// Header-only so that talus_flow itself does not depend on talus_dem; a program using it links
// both (Talus::flow and Talus::dem).
#include "dem/interface/Exchange.h"
#include "flow/HydroForce.h"

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace talus::flow
{
static_assert(sizeof(dem::Vec3) == 3 * sizeof(double), "the exchange arrays must be packed triples of doubles");

/// The exchange's arrays as HydroForce reads them (no copies; valid until bodies are added).
/// @param exchange the scene's particle exchange
/// @return positions and velocities as 3 doubles per body, radii one per body
inline ParticleArrays particleArrays(const dem::ParticleExchange& exchange)
{
  const auto pos = exchange.positions();
  const auto vel = exchange.velocities();
  return {{reinterpret_cast<const double*>(pos.data()), 3 * pos.size()},
          {reinterpret_cast<const double*>(vel.data()), 3 * vel.size()},
          exchange.radii()};
}

/// Apply `hydro`'s forces to the particles `ids` every step, from a hook placed right after the
/// ForceResetter (Yade's HydroForceEngine in the engine list). `hydro` and `exchange` must
/// outlive the hook; returns it (set `dead` to stop).
/// @param exchange the scene's particle exchange (kept by reference in the hook)
/// @param hydro the force model (kept by reference in the hook)
/// @param ids the bodies that feel the fluid (copied into the hook)
/// @return the hook, already in the scene's engine list
/// @throws std::logic_error if the engine list has no ForceResetter (ParticleExchange::addHook)
inline std::shared_ptr<dem::CallbackEngine> attachHydroForce(dem::ParticleExchange& exchange, HydroForce& hydro,
                                                               std::vector<std::int64_t> ids)
{
  return exchange.addHook(dem::ParticleExchange::HookPoint::BeforeForces,
                          [&exchange, &hydro, ids = std::move(ids)] {
                            const auto forces = exchange.stepForces();
                            hydro.action(particleArrays(exchange), ids,
                                         {reinterpret_cast<double*>(forces.data()), 3 * forces.size()},
                                         exchange.dt());
                          });
}
} // namespace talus::flow
