#include "flow/HydroForce.h"

#include "flow/InputChecks.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace talus::flow
{
namespace
{
constexpr const char* owner = "HydroForceEngine";
using checks::str;

void require(bool ok, const char* name, const std::string& what) { checks::require(ok, owner, name, what); }
void requireFinite(double value, const char* name) { checks::requireFinite(value, owner, name); }
void checkProfile(const char* name, std::span<const double> values, std::size_t expected, bool isFraction)
{
  checks::checkProfile(owner, name, values, expected, isFraction);
}

int layerOf(double height, double deltaZ)
{
  const double p = std::floor(height / deltaZ);
  // Far outside the grid: any value outside [0, nCell) will do, without overflowing int.
  return p < -1.0 ? -1 : (p > 2e9 ? 2000000000 : static_cast<int>(p));
}

/// Whether a particle centred in `layer` gets fluid forces: the grid's nCell layers, as in Yade
/// (whose fluid resolution ends at the top velocity node, (nCell - 1) deltaZ: the top layer sees
/// that surface velocity).
bool inGrid(int layer, int nCell)
{
  return layer >= 0 && layer < nCell;
}
} // namespace

void HydroForceParameters::validate() const
{
  require(nCell >= 1, "nCell", "must be at least 1, got " + std::to_string(nCell));
  requireFinite(deltaZ, "deltaZ");
  require(deltaZ > 0, "deltaZ", "must be positive, got " + str(deltaZ));
  requireFinite(zRef, "zRef");
  requireFinite(densFluid, "densFluid");
  require(densFluid > 0, "densFluid", "must be positive, got " + str(densFluid));
  requireFinite(viscoDyn, "viscoDyn");
  require(viscoDyn >= 0, "viscoDyn", "must not be negative, got " + str(viscoDyn));
  requireFinite(expoRZ, "expoRZ");
  require(expoRZ >= 0, "expoRZ", "must not be negative, got " + str(expoRZ));
  requireFinite(Cl, "Cl");
  for (double g : gravity)
    requireFinite(g, "gravity");
  requireFinite(vCell, "vCell");
  require(vCell >= 0, "vCell", "must not be negative, got " + str(vCell));
  requireFinite(periodZ, "periodZ");
  require(periodZ >= 0, "periodZ", "must not be negative, got " + str(periodZ));
  requireFinite(bedElevation, "bedElevation");
  requireFinite(kappa, "kappa");
  require(kappa > 0, "kappa", "must be positive, got " + str(kappa));
}

HydroForce::HydroForce(const HydroForceParameters& parameters) : m_parameters(parameters)
{
  m_parameters.validate();
  const auto n = static_cast<std::size_t>(m_parameters.nCell);
  m_vxFluid.assign(n + 1, 0.0);
  m_phiPart.assign(n, 0.0);
  m_reynoldStresses.assign(n, 0.0);
  updateHindrance();
}

void HydroForce::updateHindrance()
{
  m_hindrance.resize(m_phiPart.size());
  for (std::size_t c = 0; c < m_phiPart.size(); ++c)
    m_hindrance[c] = std::pow(1 - m_phiPart[c], -m_parameters.expoRZ);
}

void HydroForce::setParameters(const HydroForceParameters& parameters)
{
  parameters.validate();
  const bool resized = parameters.nCell != m_parameters.nCell;
  m_parameters = parameters;
  if (resized)
  {
    const auto n = static_cast<std::size_t>(m_parameters.nCell);
    m_vxFluid.assign(n + 1, 0.0);
    m_phiPart.assign(n, 0.0);
    m_reynoldStresses.assign(n, 0.0);
  }
  updateHindrance();
}

void HydroForce::setVxFluid(std::span<const double> vxFluid)
{
  checkProfile("vxFluid", vxFluid, m_vxFluid.size(), false);
  m_vxFluid.assign(vxFluid.begin(), vxFluid.end());
}

void HydroForce::setPhiPart(std::span<const double> phiPart)
{
  checkProfile("phiPart", phiPart, m_phiPart.size(), true);
  m_phiPart.assign(phiPart.begin(), phiPart.end());
  updateHindrance();
}

void HydroForce::setReynoldStresses(std::span<const double> stresses)
{
  checkProfile("ReynoldStresses", stresses, m_reynoldStresses.size(), false);
  m_reynoldStresses.assign(stresses.begin(), stresses.end());
}

double HydroForce::sliceVolume(double r, double a, double b)
{
  a = std::max(a, -r);
  b = std::min(b, r);
  if (b <= a)
    return 0.0;
  // Factored so that the value stays >= 0 in floating point (r^2 >= (a^2 + ab + b^2)/3 on [-r, r]).
  return std::numbers::pi * (b - a) * std::max(0.0, r * r - (a * a + a * b + b * b) / 3.0);
}

double HydroForce::elevation(double z) const
{
  const double h = z - m_parameters.zRef;
  if (m_parameters.periodZ <= 0)
    return h;
  return h - std::floor(h / m_parameters.periodZ) * m_parameters.periodZ;
}

void HydroForce::checkId(const ParticleArrays& particles, std::int64_t id, const char* what) const
{
  const std::size_t bodies = particles.radii.size();
  if (id < 0 || static_cast<std::size_t>(id) >= bodies)
    throw std::invalid_argument(std::string("HydroForceEngine.") + what + ": id " + std::to_string(id)
                                + " is not a body (the scene has " + std::to_string(bodies) + ")");
  if (!(particles.radii[static_cast<std::size_t>(id)] > 0))
    throw std::invalid_argument(std::string("HydroForceEngine.") + what + ": body " + std::to_string(id)
                                + " is not a sphere (no positive radius)");
}

std::array<double, 3> HydroForce::dragForce(double radius, int layer, const double* vel, std::size_t id) const
{
  const HydroForceParameters& p = m_parameters;
  const auto cell = static_cast<std::size_t>(layer);
  const bool fluct = id < m_fluct.size() / 3;
  const double ur[3] = {m_vxFluid[cell + 1] + (fluct ? m_fluct[3 * id] : 0.0) - vel[0],
                        (fluct ? m_fluct[3 * id + 1] : 0.0) - vel[1], (fluct ? m_fluct[3 * id + 2] : 0.0) - vel[2]};
  const double norm = std::sqrt(ur[0] * ur[0] + ur[1] * ur[1] + ur[2] * ur[2]);
  // The grouping follows Yade's expression so that both agree to round-off.
  const double coefficient = 0.5 * p.densFluid * std::numbers::pi * (radius * radius)
                             * (0.44 * norm + 24.4 * p.viscoDyn / (p.densFluid * radius * 2)) * m_hindrance[cell];
  return {coefficient * ur[0], coefficient * ur[1], coefficient * ur[2]};
}

std::array<double, 3> HydroForce::force(const ParticleArrays& particles, std::int64_t id) const
{
  checkId(particles, id, "force");
  const auto i = static_cast<std::size_t>(id);
  const int layer = layerOf(elevation(particles.positions[3 * i + 2]), m_parameters.deltaZ);
  if (!inGrid(layer, m_parameters.nCell))
    return {0.0, 0.0, 0.0};
  return forceInLayer(particles, i, layer);
}

std::array<double, 3> HydroForce::forceInLayer(const ParticleArrays& particles, std::size_t i, int layer) const
{
  const HydroForceParameters& p = m_parameters;
  const double r = particles.radii[i];
  const double* vel = &particles.velocities[3 * i];
  std::array<double, 3> f = dragForce(r, layer, vel, i);
  if (p.lift)
  {
    const int intRadius = static_cast<int>(std::floor(r / p.deltaZ));
    if (layer + intRadius < p.nCell && layer - intRadius > 0)
    {
      const double top = m_vxFluid[static_cast<std::size_t>(layer + 1 + intRadius)] - vel[0];
      const double bottom = m_vxFluid[static_cast<std::size_t>(layer + 1 - intRadius)] - vel[0];
      f[2] += 0.5 * p.densFluid * std::numbers::pi * (r * r) * p.Cl * (top * top - bottom * bottom);
    }
  }
  const double volume = -4.0 / 3.0 * std::numbers::pi * (r * r * r) * p.densFluid;
  f[0] += p.steadyFlow ? 0.0 : volume * p.gravity[0];
  f[1] += volume * p.gravity[1];
  f[2] += volume * p.gravity[2];
  return f;
}

void HydroForce::resizeFluctuations(std::size_t bodies)
{
  if (m_fluct.size() < 3 * bodies)
  {
    m_fluct.resize(3 * bodies, 0.0);
    m_life.resize(bodies, 0.0);
  }
}

void HydroForce::drawFluctuation(std::size_t id, double height)
{
  // Discrete random walk (Yade's turbulentFluctuationZDep): a Gaussian velocity scaled by the
  // local friction velocity u* = sqrt(R_xz / rho), kept for an eddy life 0.33 kappa z / u*
  // (z above the bed, at least the viscous sub-layer 11.6 nu / u*), at most 10 s. With
  // correlated fluctuations u'_x = u* (-n1 + n3), u'_z = u* n1, so <u'_x u'_z> = -u*^2.
  const HydroForceParameters& p = m_parameters;
  const int layer = layerOf(height, p.deltaZ);
  double* u = &m_fluct[3 * id];
  u[0] = u[1] = u[2] = 0.0;
  m_life[id] = 0.0;
  if (!inGrid(layer, p.nCell) || height <= p.bedElevation)
    return;
  const double stress = m_reynoldStresses[static_cast<std::size_t>(layer)];
  if (!(stress > 0))
    return;
  const double uStar = std::sqrt(stress / p.densFluid);
  const double n1 = m_normal(m_random);
  const double n2 = m_normal(m_random);
  double n3 = m_normal(m_random);
  if (!p.unCorrelatedFluctuations)
    n3 = -n1 + m_normal(m_random);
  u[0] = n3 * uStar;
  u[1] = n2 * uStar;
  u[2] = n1 * uStar;
  const double z = std::max(height - p.bedElevation, 11.6 * p.viscoDyn / p.densFluid / uStar);
  m_life[id] = std::min(0.33 * p.kappa * z / uStar, 10.0);
}

void HydroForce::turbulentFluctuation(const ParticleArrays& particles, std::span<const std::int64_t> ids)
{
  for (std::int64_t id : ids)
    checkId(particles, id, "turbulentFluctuation");
  resizeFluctuations(particles.radii.size());
  for (std::int64_t id : ids)
  {
    const auto i = static_cast<std::size_t>(id);
    drawFluctuation(i, elevation(particles.positions[3 * i + 2]));
  }
}

void HydroForce::action(const ParticleArrays& particles, std::span<const std::int64_t> ids, std::span<double> forces,
                        double dt)
{
  const HydroForceParameters& p = m_parameters;
  if (forces.size() != particles.radii.size() * 3)
    throw std::invalid_argument("HydroForceEngine.action: the force array has " + std::to_string(forces.size() / 3)
                                + " rows for " + std::to_string(particles.radii.size()) + " bodies");
  // Validate everything first, so that an error leaves the forces untouched.
  m_layers.resize(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    const std::int64_t id = ids[k];
    checkId(particles, id, "action");
    const double z = particles.positions[3 * static_cast<std::size_t>(id) + 2];
    const int layer = layerOf(elevation(z), p.deltaZ);
    const bool outside = !std::isfinite(z) || !inGrid(layer, p.nCell);
    if (outside && !p.ignoreOutside)
      throw std::invalid_argument("HydroForceEngine.action: body " + std::to_string(id) + " at z = " + str(z)
                                  + " is outside the fluid grid [zRef, zRef + nCell deltaZ) = [" + str(p.zRef)
                                  + ", " + str(p.zRef + p.nCell * p.deltaZ) + ")"
                                  + (layer >= p.nCell ? ", above its top" : ", below zRef")
                                  + "; extend the grid, or set ignoreOutside to leave such particles without "
                                    "fluid force");
    m_layers[k] = outside ? -1 : layer;
  }
  if (p.velFluct)
  {
    resizeFluctuations(particles.radii.size());
    for (std::int64_t id : ids)
    {
      const auto i = static_cast<std::size_t>(id);
      m_life[i] -= dt;
      if (m_life[i] <= 0)
        drawFluctuation(i, elevation(particles.positions[3 * i + 2]));
    }
  }
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    if (m_layers[k] < 0)
      continue;
    const auto i = static_cast<std::size_t>(ids[k]);
    const std::array<double, 3> f = forceInLayer(particles, i, m_layers[k]);
    double* out = &forces[3 * i];
    out[0] += f[0];
    out[1] += f[1];
    out[2] += f[2];
  }
}

SolidProfile HydroForce::averageProfile(const ParticleArrays& particles, std::span<const std::int64_t> ids) const
{
  const HydroForceParameters& p = m_parameters;
  require(p.vCell > 0, "vCell", "(volume of a layer) must be positive to average, got " + str(p.vCell));
  for (std::int64_t id : ids)
    checkId(particles, id, "averageProfile");
  const auto n = static_cast<std::size_t>(p.nCell);
  SolidProfile out;
  for (std::vector<double>* v : {&out.phiPart, &out.vxPart, &out.vyPart, &out.vzPart, &out.averageDrag})
    v->assign(n, 0.0);
  for (std::int64_t id : ids)
  {
    const auto i = static_cast<std::size_t>(id);
    const double r = particles.radii[i];
    const double* vel = &particles.velocities[3 * i];
    const double height = elevation(particles.positions[3 * i + 2]);
    const int layer = layerOf(height, p.deltaZ);
    // The drag is the one action() applies (fluctuations included), zero outside the grid.
    const double drag = inGrid(layer, p.nCell) ? dragForce(r, layer, vel, i)[0] : 0.0;
    const int first = std::max(0, layerOf(height - r, p.deltaZ));
    const int last = std::min(p.nCell - 1, layerOf(height + r, p.deltaZ));
    for (int k = first; k <= last; ++k)
    {
      const double volume = sliceVolume(r, k * p.deltaZ - height, (k + 1) * p.deltaZ - height);
      const auto c = static_cast<std::size_t>(k);
      out.phiPart[c] += volume;
      out.vxPart[c] += volume * vel[0];
      out.vyPart[c] += volume * vel[1];
      out.vzPart[c] += volume * vel[2];
      out.averageDrag[c] += volume * drag;
    }
  }
  for (std::size_t c = 0; c < n; ++c)
  {
    const double volume = out.phiPart[c];
    if (volume > 0)
      for (std::vector<double>* v : {&out.vxPart, &out.vyPart, &out.vzPart, &out.averageDrag})
        (*v)[c] /= volume;
    out.phiPart[c] = volume / p.vCell;
  }
  return out;
}
} // namespace talus::flow
