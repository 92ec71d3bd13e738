#include "flow/thermal/ThermalExpansion.h"

#include "flow/pore/PoreGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace talus::flow::thermal
{
void ThermalExpansion::resize()
{
  particles_.resize();
  const std::size_t n = particles_.boundary.size();
  if (sphereMark.size() < n)
  {
    const auto alpha = exchange_.thermalExpansions();
    for (std::size_t i = sphereMark.size(); i < n; ++i)
      if (std::isnan(alpha[i]))
        alpha[i] = defaultAlpha;
    sphereMark.resize(n, std::numeric_limits<double>::quiet_NaN());
  }
  const auto temperature = particles_.temperatures();
  for (std::size_t i = 0; i < n; ++i)
    if (std::isnan(sphereMark[i]))
      sphereMark[i] = temperature[i];
}

void ThermalExpansion::mark(const PoreHeat* fluid)
{
  resize();
  const auto temperature = particles_.temperatures();
  sphereMark.assign(temperature.begin(), temperature.begin() + static_cast<std::ptrdiff_t>(sphereMark.size()));
  poreMark_ = fluid ? fluid->temperatures() : std::vector<double>{};
  markedMesh_ = fluid ? fluid->mesh() : nullptr;
}

void ThermalExpansion::computeFractions(const pore::PoreNetwork& net)
{
  fractions_.assign(net.pores.size(), {});
  for (std::size_t i = 0; i < net.pores.size(); ++i)
  {
    const auto& v = net.pores[i].vertices;
    const auto at = [&](std::size_t k) { return net.vertices[static_cast<std::size_t>(v[k % 4])]; };
    for (std::size_t k = 0; k < 4; ++k)
      if (!at(k).fictitious)
        fractions_[i][k] = pore::solidAngle(at(k).pos, at(k + 1).pos, at(k + 2).pos, at(k + 3).pos) / (4 * std::numbers::pi);
  }
  fractionMesh_ = net.triangulation.get();
}

void ThermalExpansion::apply(double span, const PoreHeat* fluid, pore::PoreFlow* flow)
{
  if (!(span > 0))
    throw std::invalid_argument("ThermalEngine: thermal expansion over a non-positive time " + std::to_string(span));
  resize();
  const auto radii = exchange_.radii();
  std::vector<double> change(radii.size(), 0.0);
  if (params.particles)
  {
    const auto temperature = particles_.temperatures();
    const auto alpha = exchange_.thermalExpansions();
    for (std::size_t i = 0; i < change.size() && i < sphereMark.size(); ++i)
      if (exchange_.isSphere(static_cast<dem::BodyId>(i)) && particles_.boundary[i] < 0)
        change[i] = alpha[i] * radii[i] * (temperature[i] - sphereMark[i]);
  }
  // the volumes the spheres take before they grow (solid angles of the network's corners)
  rates_.clear();
  if (flow && flow->built() && (params.solidVolume || params.fluid))
  {
    const pore::PoreNetwork& net = flow->network();
    rates_.assign(net.pores.size(), 0.0);
    if (params.solidVolume && params.particles)
    {
      if (fractionMesh_ != net.triangulation.get())
        computeFractions(net);
      for (std::size_t p = 0; p < net.pores.size(); ++p)
        for (std::size_t k = 0; k < 4; ++k)
        {
          const pore::Vertex& s = net.vertices[static_cast<std::size_t>(net.pores[p].vertices[k])];
          if (s.fictitious)
            continue;
          const double r = radii[static_cast<std::size_t>(s.id)], dr = change[static_cast<std::size_t>(s.id)];
          rates_[p] -= fractions_[p][k] * 4.0 / 3.0 * std::numbers::pi * ((r + dr) * (r + dr) * (r + dr) - r * r * r) / span;
        }
    }
    // the fluid's expansion, when the pore temperatures belong to this network (a remesh since
    // the mark loses that run's expansion, as Yade's new cells start with no volume change)
    if (params.fluid && fluid && fluid->mesh() == net.triangulation.get() && markedMesh_ == fluid->mesh())
    {
      const std::vector<double>& t = fluid->temperatures();
      for (std::size_t p = 0; p < net.pores.size(); ++p)
      {
        // a pore whose spheres overlap past its volume has no fluid (and no storage in the flow)
        const double v = params.porosityFactor > 0 ? params.porosityFactor * std::abs(net.pores[p].volume)
                                                   : std::max(net.pores[p].voidVolume, 0.0);
        rates_[p] -= v * params.fluidBeta * (t[p] - poreMark_[p]) / span;
      }
    }
    flow->setExtraVolumeRates(rates_);
  }
  exchange_.growSpheres(change);
  mark(fluid);
}
} // namespace talus::flow::thermal
