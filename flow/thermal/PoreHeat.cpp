#include "flow/thermal/PoreHeat.h"

#include "flow/pore/PoreGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::flow::thermal
{
namespace
{
/// Yade's cellBarycenter: the plain mean of the four vertices (pores without boundary vertices).
pore::Vec3 vertexCentroid(const pore::PoreNetwork& net, const pore::Pore& p)
{
  pore::Vec3 c = pore::Vec3::Zero();
  for (const int v : p.vertices)
    c += 0.25 * net.vertices[static_cast<std::size_t>(v)].pos;
  return c;
}
} // namespace

void PoreHeat::setBoundary(int k, bool held, double value)
{
  if (k < 0 || k >= pore::kBoundaries)
    throw std::invalid_argument("FlowEngine.bndCondIsTemperature: boundary " + std::to_string(k) + " is not one of 0..5");
  boundaryHeld_[static_cast<std::size_t>(k)] = held;
  boundaryValue_[static_cast<std::size_t>(k)] = value;
  if (mesh_)
    for (const int p : mesh_->boundaryPores[static_cast<std::size_t>(k)])
    {
      held_[static_cast<std::size_t>(p)] = held;
      if (held)
        temperature_[static_cast<std::size_t>(p)] = value;
    }
}

void PoreHeat::sync()
{
  if (!flow_->built())
    throw std::invalid_argument("ThermalEngine.advection: the FlowEngine has no pore network yet (put it before the "
                                "ThermalEngine in O.engines, or call flow.emulateAction() first)");
  const pore::PoreNetwork& net = flow_->network();
  if (net.periodic)
    throw std::invalid_argument("ThermalEngine.advection: pore temperatures on a periodic network are not implemented");
  if (mesh_ && mesh_->triangulation == net.triangulation)
    return;
  std::vector<double> carried(net.pores.size(), initialTemperature);
  if (mesh_)
    for (std::size_t i = 0; i < net.pores.size(); ++i)
    {
      const int old = pore::locatePore(*mesh_, pore::interiorPoint(net, net.pores[i]));
      if (old >= 0)
        carried[i] = temperature_[static_cast<std::size_t>(old)];
    }
  mesh_ = net;
  temperature_ = std::move(carried);
  held_.assign(net.pores.size(), 0);
  for (int k = 0; k < pore::kBoundaries; ++k)
    setBoundary(k, boundaryHeld_[static_cast<std::size_t>(k)], boundaryValue_[static_cast<std::size_t>(k)]);
  computeGeometry();
  poreNusseltK_.clear(); // due again on the new network, as Yade's after a remesh
}

void PoreHeat::computePoreNusselt()
{
  const pore::PoreNetwork& net = *mesh_;
  const std::vector<pore::Vec3> velocity = flow_->poreVelocities();
  if (velocity.size() != net.pores.size())
    throw std::logic_error("PoreHeat: the pore velocities belong to another network");
  const double viscosity = flow_->params.viscosity;
  const double prandtl = params.fluidCp * viscosity / params.fluidK;
  const double phi = params.porosity;
  poreNusseltK_.resize(net.pores.size());
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    double length = 1e-6;
    for (const int n : net.pores[i].neighbours)
      if (n >= 0 && net.pores[static_cast<std::size_t>(n)].nFictitious == 0)
        length = (net.pores[i].centre - net.pores[static_cast<std::size_t>(n)].centre).norm();
    double re = params.fluidRho * velocity[i].norm() * length / viscosity;
    if (!(re >= 0))
      re = 0;
    const double nusselt =
        re > 1000 || phi < 0.35
            ? 2 + 0.6 * std::sqrt(re) * std::pow(prandtl, 0.33333)
            : (7 - 10 * phi + 5 * phi * phi) * (1 + 0.1 * std::pow(re, 0.2) * std::pow(prandtl, 0.333)) +
                  (1.33 - 2.19 * phi + 1.15 * phi * phi) * std::pow(re, 0.7) * std::pow(prandtl, 0.333);
    poreNusseltK_[i] = nusselt * params.fluidK;
  }
}

void PoreHeat::computeGeometry()
{
  const pore::PoreNetwork& net = *mesh_;
  sphereArea_.assign(net.pores.size(), {});
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    const auto& v = net.pores[i].vertices;
    for (int k = 0; k < 4; ++k)
    {
      const pore::Vertex& s = net.vertices[static_cast<std::size_t>(v[static_cast<std::size_t>(k)])];
      if (s.fictitious)
        continue;
      const auto at = [&](int j) { return net.vertices[static_cast<std::size_t>(v[static_cast<std::size_t>((k + j) % 4)])].pos; };
      sphereArea_[i][static_cast<std::size_t>(k)] = s.radius * s.radius * pore::solidAngle(s.pos, at(1), at(2), at(3));
    }
  }
  fluidConductance_.assign(net.throats.size(), 0.0);
  for (std::size_t t = 0; t < net.throats.size(); ++t)
  {
    const pore::Throat& th = net.throats[t];
    const pore::Pore& a = net.pores[static_cast<std::size_t>(th.pores[0])];
    const pore::Pore& b = net.pores[static_cast<std::size_t>(th.pores[1])];
    if (a.nFictitious > 0 || b.nFictitious > 0)
      continue; // Yade conducts between inner pores only
    const double distance = std::max((vertexCentroid(net, a) - vertexCentroid(net, b)).norm(), params.minimumDistance);
    fluidConductance_[t] = th.fluidArea / distance;
  }
}

bool PoreHeat::free(std::size_t pore) const { return mesh_->pores[pore].nFictitious == 0 && !held_[pore]; }

double PoreHeat::heatCapacity(std::size_t pore) const
{
  const double v = mesh_->pores[pore].voidVolume;
  return params.fluidCp * params.fluidRho * (params.thermalPorosity > 0 ? params.thermalPorosity * v : v);
}

void PoreHeat::setTemperature(int pore, double value)
{
  sync();
  temperature_.at(static_cast<std::size_t>(pore)) = value;
}

double PoreHeat::temperatureAt(const pore::Vec3& x)
{
  sync();
  const int p = pore::locatePore(*mesh_, x);
  return p < 0 ? std::numeric_limits<double>::quiet_NaN() : temperature_[static_cast<std::size_t>(p)];
}

void PoreHeat::computeRates()
{
  sync();
  const pore::PoreNetwork& net = *mesh_;
  if (params.poreReynolds && poreNusseltK_.empty())
    computePoreNusselt();
  particles_.computeRates();
  rate_.assign(net.pores.size(), 0.0);
  conductance_.assign(net.pores.size(), 0.0);
  const double rhoCp = params.fluidRho * params.fluidCp;
  if (params.advection)
  {
    const std::vector<double>& p = flow_->pressures();
    for (const pore::Throat& th : net.throats)
    {
      const auto a = static_cast<std::size_t>(th.pores[0]), b = static_cast<std::size_t>(th.pores[1]);
      // Upwind, in advective form: the pore receiving the flux tends to the upstream temperature,
      // rho Cp |q| (T_up - T). For a divergence-free flux (incompressible fluid) it equals the
      // conservative form -sum rho Cp T_up q of every inner pore; with a compressible fluid it
      // keeps a uniform temperature uniform where pores expel or take in fluid (the pore's heat
      // capacity is that of its void volume, whatever fluid mass it stores).
      const double q = th.conductance * (p[a] - p[b]); // from a to b
      const std::size_t from = q > 0 ? a : b, to = q > 0 ? b : a;
      if (free(to))
      {
        rate_[to] += rhoCp * std::abs(q) * (temperature_[from] - temperature_[to]);
        conductance_[to] += rhoCp * std::abs(q); // explicit upwind: inflow bounds the step
      }
    }
  }
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    const bool boundaryPore = net.pores[i].nFictitious > 0;
    if (boundaryPore && (params.ignoreFictitious || !held_[i]))
      continue; // boundary pores exchange only when they hold a temperature (as Yade)
    for (std::size_t k = 0; k < 4; ++k)
    {
      const pore::Vertex& s = net.vertices[static_cast<std::size_t>(net.pores[i].vertices[k])];
      if (s.fictitious)
        continue;
      const auto id = static_cast<dem::BodyId>(s.id);
      const double nusseltK = params.poreReynolds ? poreNusseltK_[i] : params.nusseltK;
      const double g = nusseltK / (2 * s.radius) * sphereArea_[i][k];
      const double q = g * (temperature_[i] - particles_.temperatures()[static_cast<std::size_t>(id)]); // into the sphere
      if (free(i))
      {
        rate_[i] -= q;
        conductance_[i] += g;
      }
      if (particles_.boundary[static_cast<std::size_t>(id)] < 0) // Yade's thermalBndFlux counts contacts only
        particles_.addExchange(id, q, g);
    }
  }
  if (params.fluidConduction)
    for (std::size_t t = 0; t < net.throats.size(); ++t)
      for (const int pore : net.throats[t].pores)
        conductance_[static_cast<std::size_t>(pore)] += params.fluidK * params.areaFactor * fluidConductance_[t];
  particles_.computeStableStep();
  stableStep_ = std::numeric_limits<double>::infinity();
  limitingPore_ = -1;
  for (std::size_t i = 0; i < net.pores.size(); ++i)
    if (free(i) && conductance_[i] > 0 && heatCapacity(i) / conductance_[i] < stableStep_)
    {
      stableStep_ = heatCapacity(i) / conductance_[i];
      limitingPore_ = static_cast<int>(i);
    }
}

void PoreHeat::applyRates(double dt)
{
  const pore::PoreNetwork& net = *mesh_;
  particles_.applyRates(dt);
  for (std::size_t i = 0; i < net.pores.size(); ++i)
    if (free(i))
      temperature_[i] += rate_[i] * dt / heatCapacity(i);
  if (!params.fluidConduction)
    return;
  // With the pore temperatures just advanced (Yade's split), all throats from the same values.
  std::vector<double> heat(net.pores.size(), 0.0);
  for (std::size_t t = 0; t < net.throats.size(); ++t)
  {
    const auto a = static_cast<std::size_t>(net.throats[t].pores[0]), b = static_cast<std::size_t>(net.throats[t].pores[1]);
    const double e = params.fluidK * params.areaFactor * fluidConductance_[t] * (temperature_[a] - temperature_[b]) * dt;
    heat[a] -= e;
    heat[b] += e;
  }
  for (std::size_t i = 0; i < net.pores.size(); ++i)
    if (free(i))
      temperature_[i] += heat[i] / heatCapacity(i);
}

double PoreHeat::stableTimeStep() const { return std::min(stableStep_, particles_.stableTimeStep()); }

std::string PoreHeat::limitingPart() const
{
  if (particles_.stableTimeStep() <= stableStep_)
    return particles_.limitingPart();
  return "pore " + std::to_string(limitingPore_) + ": fluid heat capacity / its exchange, conduction and inflow";
}
} // namespace talus::flow::thermal
