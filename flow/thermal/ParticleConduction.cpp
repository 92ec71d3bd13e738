#include "flow/thermal/ParticleConduction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace talus::flow::thermal
{
void ParticleConduction::resize()
{
  const std::size_t n = exchange_.radii().size();
  if (boundary.size() >= n)
    return;
  for (const auto& [field, value] : {std::pair{exchange_.temperatures(), initialTemperature},
                                     std::pair{exchange_.conductivities(), defaultConductivity},
                                     std::pair{exchange_.heatCapacities(), defaultHeatCapacity}})
    for (std::size_t i = boundary.size(); i < n; ++i)
      if (std::isnan(field[i]))
        field[i] = value;
  boundary.resize(n, -1);
}

void ParticleConduction::imposeTemperature(int k, const std::vector<dem::BodyId>& ids, double value)
{
  if (k < 0 || k >= kBoundaries)
    throw std::invalid_argument("ThermalEngine: boundary " + std::to_string(k) + " is not one of 0..5");
  resize();
  for (const dem::BodyId id : ids)
  {
    if (!exchange_.isSphere(id))
      throw std::invalid_argument("ThermalEngine: body " + std::to_string(id) + " of boundary " + std::to_string(k) +
                                  " is not a live sphere");
    const auto i = static_cast<std::size_t>(id);
    boundary[i] = static_cast<std::int8_t>(k);
    exchange_.temperatures()[i] = value;
  }
}

void ParticleConduction::imposeHeatFlux(int k, const std::vector<dem::BodyId>& ids, const std::vector<double>& rates)
{
  if (k < 0 || k >= kBoundaries)
    throw std::invalid_argument("ThermalEngine: boundary " + std::to_string(k) + " is not one of 0..5");
  if (ids.size() != rates.size())
    throw std::invalid_argument("ThermalEngine: heat flux of boundary " + std::to_string(k) + ": " +
                                std::to_string(ids.size()) + " spheres but " + std::to_string(rates.size()) + " rates");
  resize();
  auto& flux = heatFlux_[static_cast<std::size_t>(k)];
  flux.clear();
  for (std::size_t j = 0; j < ids.size(); ++j)
  {
    if (!exchange_.isSphere(ids[j]))
      throw std::invalid_argument("ThermalEngine: body " + std::to_string(ids[j]) + " of boundary " +
                                  std::to_string(k) + " is not a live sphere");
    if (!std::isfinite(rates[j]))
      throw std::invalid_argument("ThermalEngine.thermalBndCondValue[" + std::to_string(k) +
                                  "]: the heat flux must be finite");
    flux.emplace_back(ids[j], rates[j]);
  }
}

void ParticleConduction::clearBoundaries()
{
  std::fill(boundary.begin(), boundary.end(), std::int8_t{-1});
  for (auto& flux : heatFlux_)
    flux.clear();
}

bool ParticleConduction::conducts(const dem::Contact& c) const
{
  return c.real && c.kind == dem::ContactGeometryKind::SphereSphere && exchange_.isSphere(c.id1) &&
         exchange_.isSphere(c.id2);
}

double ParticleConduction::contactConductance(const dem::Contact& c) const
{
  const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
  const auto radii = exchange_.radii();
  const double r1 = radii[i1], r2 = radii[i2];
  const auto conductivity = exchange_.conductivities();
  const double k = conductivity[i1] + conductivity[i2];
  const double d = r1 + r2 - c.penetration; // distance between the centres
  if (d <= 0)
    return 0; // concentric spheres: no direction to conduct along (Yade skips them too)
  if (conductance == ContactConductance::Radii)
    return 2 * k * r1 * r2 / d;
  // Radius of the intersection circle of two spheres (Kern & Bland, Solid Mensuration, 1948):
  // rc^2 = (r1+r2-d)(d+r1-r2)(d-r1+r2)(d+r1+r2) / (4 d^2), zero once they no longer overlap.
  const double product = (r1 + r2 - d) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
  const double rc2 = std::max(product, 0.0) / (4 * d * d);
  return 2 * k * rc2 / d;
}

double ParticleConduction::heatCapacityOf(dem::BodyId id) const
{
  const auto i = static_cast<std::size_t>(id);
  const double r = exchange_.radii()[i];
  const double mass = particleDensity > 0 ? particleDensity * 4.0 / 3.0 * std::numbers::pi * r * r * r
                                          : exchange_.masses()[i];
  return mass * exchange_.heatCapacities()[i];
}

void ParticleConduction::computeRates()
{
  resize();
  const auto temperature = exchange_.temperatures();
  rate_.assign(boundary.size(), 0.0);
  conductance_.assign(boundary.size(), 0.0);
  // Serial over the contact list (sorted by pair): the sums do not depend on threads.
  for (const dem::Contact& c : exchange_.contacts().list)
  {
    if (!conducts(c))
      continue;
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const double g = contactConductance(c);
    const double q = g * (temperature[i1] - temperature[i2]); // from 1 to 2
    rate_[i1] -= q;
    rate_[i2] += q;
    conductance_[i1] += g;
    conductance_[i2] += g;
  }
  for (const auto& flux : heatFlux_)
    for (const auto& [id, rate] : flux)
      if (boundary[static_cast<std::size_t>(id)] < 0) // a held sphere keeps its temperature
        rate_[static_cast<std::size_t>(id)] += rate;
  computeStableStep();
}

void ParticleConduction::addExchange(dem::BodyId id, double rate, double g)
{
  const auto i = static_cast<std::size_t>(id);
  rate_[i] += rate;
  conductance_[i] += g;
}

void ParticleConduction::computeStableStep()
{
  stableStep_ = std::numeric_limits<double>::infinity();
  limitingBody_ = -1;
  for (std::size_t i = 0; i < boundary.size(); ++i)
  {
    if (conductance_[i] <= 0 || boundary[i] >= 0)
      continue;
    const double capacity = heatCapacityOf(static_cast<dem::BodyId>(i));
    if (!(capacity > 0))
      throw std::invalid_argument("ThermalEngine: sphere " + std::to_string(i) + " has no heat capacity (mass " +
                                  std::to_string(exchange_.masses()[i]) + " kg, particleCp " +
                                  std::to_string(exchange_.heatCapacities()[i]) + " J/(kg K)): give it a mass or set particleDensity");
    if (capacity / conductance_[i] < stableStep_)
    {
      stableStep_ = capacity / conductance_[i];
      limitingBody_ = static_cast<dem::BodyId>(i);
    }
  }
}

void ParticleConduction::applyRates(double dt)
{
  boundaryFlux_.fill(0.0);
  for (std::size_t k = 0; k < kBoundaries; ++k)
    for (const auto& [id, rate] : heatFlux_[k])
      if (boundary[static_cast<std::size_t>(id)] < 0)
        boundaryFlux_[k] += rate; // the heat given through a flux boundary (W, into the packing)
  const auto temperature = exchange_.temperatures();
  for (std::size_t i = 0; i < rate_.size(); ++i)
  {
    if (conductance_[i] <= 0 && rate_[i] == 0)
      continue; // no conducting contact nor flux (not a live sphere, or isolated)
    if (boundary[i] >= 0)
      boundaryFlux_[static_cast<std::size_t>(boundary[i])] += rate_[i];
    else
      temperature[i] += rate_[i] * dt / heatCapacityOf(static_cast<dem::BodyId>(i));
  }
  for (std::size_t k = 0; k < kBoundaries; ++k)
    boundaryHeat_[k] += boundaryFlux_[k] * dt;
}
} // namespace talus::flow::thermal
