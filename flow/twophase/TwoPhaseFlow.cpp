#include "flow/twophase/TwoPhaseFlow.h"

#include "flow/InputChecks.h"
#include "flow/pore/PoreFlow.h"
#include "flow/twophase/CapillaryForce.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace talus::flow::twophase
{
namespace
{
constexpr const char* kOwner = "TwoPhaseFlowEngine";
constexpr std::size_t kWetting = 2;    // boundary of the wetting reservoir (ymin)
constexpr std::size_t kNonWetting = 3; // boundary of the non-wetting reservoir (ymax)

void checkSurfaceTension(double gamma)
{
  checks::requireFinite(gamma, kOwner, "surfaceTension");
  checks::require(gamma >= 0, kOwner, "surfaceTension", "must be >= 0, got " + checks::str(gamma));
}

void checkValues(const std::array<double, kBoundaries>& values)
{
  for (double v : values)
    checks::requireFinite(v, kOwner, "bndCondValue");
}
} // namespace

void TwoPhaseFlow::setParameters(const TwoPhaseParameters& params)
{
  checkSurfaceTension(params.surfaceTension);
  entryPressureMethod(params.entryPressureMethod);
  params_ = params;
}

void TwoPhaseFlow::initialize(const pore::PoreNetwork& net, const TwoPhaseParameters& params,
                              const std::array<bool, kBoundaries>& bndCondIsPressure,
                              const std::array<double, kBoundaries>& bndCondValue)
{
  setParameters(params);
  const EntryPressureMethod method = entryPressureMethod(params.entryPressureMethod);
  // the clusters' dynamics needs only the wetting reservoir imposed (Yade's injection example)
  checks::require(bndCondIsPressure[kWetting] && (bndCondIsPressure[kNonWetting] || params.isCellLabelActivated),
                  kOwner, "bndCondIsPressure",
                  "must impose the pressure on boundaries 2 (ymin, the wetting reservoir) and 3 (ymax, the "
                  "non-wetting reservoir; optional with isCellLabelActivated), as Yade's TwoPhaseFlowEngine assumes");
  checkValues(bndCondValue);
  if (net.periodic)
    throw std::invalid_argument("TwoPhaseFlowEngine: periodic networks are not supported");
  isPressure_ = bndCondIsPressure;
  bnd_ = bndCondValue;

  throatRadius_ = throatEntryRadii(net, method, params.isInvadeBoundary);
  bodyRadius_ = poreBodyRadii(net);
  const std::size_t n = net.pores.size();
  bodyVolume_.resize(n);
  conductance_.resize(net.throats.size());
  fluidArea_.resize(net.throats.size());
  for (std::size_t t = 0; t < net.throats.size(); ++t)
  {
    conductance_[t] = net.throats[t].conductance;
    fluidArea_[t] = net.throats[t].fluidArea;
  }
  neighbours_.resize(n);
  throats_.resize(n);
  boundaryPore_.resize(n);
  for (std::size_t c = 0; c < n; ++c)
  {
    const pore::Pore& p = net.pores[c];
    // Yade's pore-body volume: |cell volume| - |solid volume in the cell|
    bodyVolume_[c] = std::abs(p.volume) - std::abs(p.volume - p.voidVolume);
    neighbours_[c] = p.neighbours;
    throats_[c] = p.throats;
    boundaryPore_[c] = p.nFictitious > 0 ? 1 : 0;
  }
  boundaryPores_ = net.boundaryPores;
  poreVertices_.resize(n);
  barycentre_.assign(n, pore::Vec3::Zero());
  for (std::size_t c = 0; c < n; ++c)
  {
    poreVertices_[c] = net.pores[c].vertices;
    for (int v : poreVertices_[c])
      barycentre_[c] += 0.25 * net.vertices[static_cast<std::size_t>(v)].pos;
  }
  nVertices_ = net.vertices.size();
  unitForces_ = pore::unitForceVectors(net, solidLineShares(net));

  pores_.assign(n, PoreState{});
  for (std::size_t k = 0; k < kBoundaries; ++k)
    if (bndCondIsPressure[k])
      for (int c : boundaryPores_[k])
      {
        pores_[static_cast<std::size_t>(c)].imposed = true;
        pores_[static_cast<std::size_t>(c)].pressure = bndCondValue[k];
      }
  // the reservoirs' pores keep their phase where their pressure is imposed; the others take the
  // initial phase below, as in Yade
  for (int c : boundaryPores_[kWetting])
  {
    PoreState& s = pores_[static_cast<std::size_t>(c)];
    s.saturation = 1;
    s.wReservoir = true;
    s.nwReservoir = false;
  }
  for (int c : boundaryPores_[kNonWetting])
  {
    PoreState& s = pores_[static_cast<std::size_t>(c)];
    s.saturation = 0;
    s.wReservoir = false;
    s.nwReservoir = true;
  }
  for (PoreState& s : pores_)
    if (!s.imposed)
    {
      s.saturation = params.drainageFirst ? 1 : 0;
      s.pressure = bndCondValue[params.drainageFirst ? kWetting : kNonWetting];
      s.wReservoir = params.drainageFirst;
      s.nwReservoir = !params.drainageFirst;
    }
  label_.assign(n, -1);
  clusters_.clear();
  systems_.clear();
  if (params.isCellLabelActivated)
    updateCellLabels();
}

void TwoPhaseFlow::applyPressures()
{
  for (std::size_t k = 0; k < kBoundaries; ++k)
    if (isPressure_[k])
      for (int c : boundaryPores_[k])
        pores_[static_cast<std::size_t>(c)].pressure = bnd_[k];
  for (PoreState& s : pores_)
  {
    if (s.wReservoir)
      s.pressure = bnd_[kWetting];
    if (s.nwReservoir)
      s.pressure = bnd_[kNonWetting];
    if (params_.isPhaseTrapped)
    {
      if (s.trappedW)
        s.pressure = bnd_[kNonWetting] - s.trapCapillaryPressure;
      if (s.trappedNW)
        s.pressure = bnd_[kWetting] + s.trapCapillaryPressure;
    }
  }
}

void TwoPhaseFlow::invadeFrom(int start)
{
  // depth first in Yade's order (its recursion: a pore invaded is visited at once, before the
  // next facet of the pore that invaded it), which the clusters kept by useFastInvasion follow;
  // a frame is a pore, its next facet and the phase and pressure it spreads
  struct Frame
  {
    std::size_t pore;
    std::size_t facet;
    double pressure;
    double saturation;
  };
  const double gamma = params_.surfaceTension;
  std::vector<Frame> stack;
  const auto enter = [&](int pore) {
    const auto c = static_cast<std::size_t>(pore);
    stack.push_back({c, 0, pores_[c].pressure, pores_[c].saturation});
    if (params_.useFastInvasion && label_[c] > 0) // a pore of a wetting cluster
      invadePoreFast(pore);
  };
  enter(start);
  while (!stack.empty())
  {
    Frame& frame = stack.back();
    if (frame.facet == 4)
    {
      stack.pop_back();
      continue;
    }
    const std::size_t c = frame.pore;
    const std::size_t f = frame.facet++;
    const double p = frame.pressure;
    const double s = frame.saturation;
    const int j = neighbours_[c][f];
    if (j < 0)
      continue;
    PoreState& other = pores_[static_cast<std::size_t>(j)];
    const double r = throatRadius_[static_cast<std::size_t>(throats_[c][f])];
    if (other.imposed || r < 0)
      continue;
    const double throatPc = gamma / r;
    const double bodyPc = gamma / bodyRadius_[static_cast<std::size_t>(j)];
    if (other.saturation == s)
    {
      // a trapped pocket of the same phase joins the invading one
      if (other.pressure != p && (other.trappedW || other.trappedNW))
      {
        other.pressure = p;
        enter(j);
      }
      continue;
    }
    const bool drainage = other.saturation > s;
    const bool invaded = drainage ? p - other.pressure > throatPc && p - other.pressure > bodyPc // past both entry pressures
                                  : other.pressure - p < bodyPc && other.pressure - p < throatPc; // imbibition: below both
    if (invaded)
    {
      other.pressure = p;
      other.saturation = s;
      if (drainage)
        other.hasInterface = false;
      if (params_.recursiveInvasion)
        enter(j);
    }
  }
}

void TwoPhaseFlow::floodReservoir(int k, double phase)
{
  const bool wetting = phase == 1;
  std::vector<int> stack(boundaryPores_[static_cast<std::size_t>(k)]);
  while (!stack.empty())
  {
    const auto c = static_cast<std::size_t>(stack.back());
    stack.pop_back();
    for (int j : neighbours_[c])
    {
      if (j < 0)
        continue;
      PoreState& s = pores_[static_cast<std::size_t>(j)];
      if (s.imposed || s.saturation != phase || (wetting ? s.wReservoir : s.nwReservoir))
        continue;
      s.wReservoir = wetting;
      s.nwReservoir = !wetting;
      (wetting ? s.trappedW : s.trappedNW) = false;
      s.trapCapillaryPressure = 0;
      stack.push_back(j);
    }
  }
}

void TwoPhaseFlow::updateReservoirs(double pc)
{
  if (!params_.isPhaseTrapped)
  {
    // every pore stays connected to the reservoir whose pressure it has
    for (PoreState& s : pores_)
      if (s.pressure == bnd_[kWetting] || s.pressure == bnd_[kNonWetting])
      {
        s.wReservoir = s.pressure == bnd_[kWetting];
        s.nwReservoir = !s.wReservoir;
      }
    return;
  }
  for (PoreState& s : pores_)
    if (!s.imposed)
      s.wReservoir = s.nwReservoir = false;
  floodReservoir(kWetting, 1.0);
  floodReservoir(kNonWetting, 0.0);
  for (PoreState& s : pores_)
  {
    if (s.wReservoir || s.nwReservoir || s.trappedW || s.trappedNW)
      continue;
    s.trapCapillaryPressure = pc;
    s.trappedW = s.saturation == 1;
    s.trappedNW = s.saturation == 0;
  }
  for (PoreState& s : pores_)
  {
    if (s.trappedW)
      s.pressure = bnd_[kNonWetting] - s.trapCapillaryPressure;
    if (s.trappedNW)
      s.pressure = bnd_[kWetting] + s.trapCapillaryPressure;
  }
}

void TwoPhaseFlow::invasion(const std::array<double, kBoundaries>& bndCondValue)
{
  if (!initialized())
    throw std::logic_error("TwoPhaseFlowEngine.invasion: call initialization() first");
  checkValues(bndCondValue);
  checks::require(isPressure_[kWetting] && isPressure_[kNonWetting], kOwner, "bndCondIsPressure",
                  "invasion() needs the pressure imposed on boundaries 2 and 3 (the two reservoirs)");
  checks::require(!(params_.useFastInvasion && params_.isImbibitionActivated), kOwner, "useFastInvasion",
                  "keeps the clusters through drainage only: switch isImbibitionActivated off (Yade's fast "
                  "cluster update would drain the wetting reservoir's pores)");
  bnd_ = bndCondValue;
  for (auto& system : systems_)
    system.reset(); // the phases change: the clusters' pressure systems too
  applyPressures();
  if (params_.isDrainageActivated)
    for (std::size_t c = 0; c < pores_.size(); ++c)
      if (pores_[c].nwReservoir)
        invadeFrom(static_cast<int>(c));
  if (params_.isImbibitionActivated)
    for (std::size_t c = 0; c < pores_.size(); ++c)
      if (pores_[c].wReservoir)
        invadeFrom(static_cast<int>(c));
  updateReservoirs(bnd_[kNonWetting] - bnd_[kWetting]);
  if (params_.isCellLabelActivated && !params_.useFastInvasion)
    updateCellLabels();
}

void TwoPhaseFlow::updatePressure(const std::array<double, kBoundaries>& bndCondValue)
{
  if (!initialized())
    throw std::logic_error("TwoPhaseFlowEngine.updatePressure: call initialization() first");
  checkValues(bndCondValue);
  bnd_ = bndCondValue;
  for (auto& system : systems_)
    system.reset(); // the conditions of the clusters' pressures change
  applyPressures();
}

PoreState& TwoPhaseFlow::checkedPore(int pore, const char* function)
{
  if (pore < 0 || static_cast<std::size_t>(pore) >= pores_.size())
    throw std::out_of_range(std::string(kOwner) + "." + function + ": cell id " + std::to_string(pore)
                            + " out of range (0.." + std::to_string(static_cast<int>(pores_.size()) - 1) + ")");
  return pores_[static_cast<std::size_t>(pore)];
}

void TwoPhaseFlow::setSaturation(int pore, double saturation)
{
  PoreState& s = checkedPore(pore, "setCellSaturation");
  checks::require(saturation >= 0 && saturation <= 1, kOwner, "setCellSaturation",
                  "the saturation must be in [0, 1], got " + checks::str(saturation));
  s.saturation = saturation;
  for (auto& system : systems_)
    system.reset();
}

void TwoPhaseFlow::setReservoir(int pore, bool wetting, bool value)
{
  PoreState& s = checkedPore(pore, wetting ? "setCellIsWRes" : "setCellIsNWRes");
  (wetting ? s.wReservoir : s.nwReservoir) = value;
}

void TwoPhaseFlow::setHasInterface(int pore, bool value)
{
  checkedPore(pore, "setCellHasInterface").hasInterface = value;
}

void TwoPhaseFlow::setBodyRadius(int pore, double radius)
{
  checkedPore(pore, "setPoreBodyRadius");
  checks::require(std::isfinite(radius) && radius > 0, kOwner, "setPoreBodyRadius",
                  "the radius must be finite and > 0, got " + checks::str(radius));
  bodyRadius_[static_cast<std::size_t>(pore)] = radius;
}

void TwoPhaseFlow::setThroatRadius(int throat, double radius)
{
  if (throat < 0 || static_cast<std::size_t>(throat) >= throatRadius_.size())
    throw std::out_of_range(std::string(kOwner) + ".setPoreThroatRadius: throat " + std::to_string(throat)
                            + " out of range (0.." + std::to_string(static_cast<int>(throatRadius_.size()) - 1) + ")");
  checks::require(std::isfinite(radius), kOwner, "setPoreThroatRadius",
                  "the radius must be finite (negative: closed), got " + checks::str(radius));
  throatRadius_[static_cast<std::size_t>(throat)] = radius;
}

double TwoPhaseFlow::saturation(bool sideBoundaryIncluded) const
{
  double pores = 0, wetting = 0;
  for (std::size_t c = 0; c < pores_.size(); ++c)
  {
    if (pores_[c].imposed || (boundaryPore_[c] && !sideBoundaryIncluded))
      continue;
    pores += bodyVolume_[c];
    if (pores_[c].saturation > 0)
      wetting += bodyVolume_[c] * pores_[c].saturation;
  }
  return wetting / pores;
}

double TwoPhaseFlow::minDrainagePc() const
{
  const double gamma = params_.surfaceTension;
  double next = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < pores_.size(); ++c)
  {
    if (!pores_[c].nwReservoir)
      continue;
    for (std::size_t f = 0; f < 4; ++f)
    {
      const int j = neighbours_[c][f];
      if (j < 0 || pores_[static_cast<std::size_t>(j)].imposed || !pores_[static_cast<std::size_t>(j)].wReservoir)
        continue;
      const double r = throatRadius_[static_cast<std::size_t>(throats_[c][f])];
      if (r > 0)
        next = std::min(next, std::max(gamma / r, gamma / bodyRadius_[static_cast<std::size_t>(j)]));
    }
  }
  return std::isinf(next) ? 0.0 : next;
}

double TwoPhaseFlow::maxImbibitionPc() const
{
  const double gamma = params_.surfaceTension;
  double next = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < pores_.size(); ++c)
  {
    if (!pores_[c].wReservoir)
      continue;
    for (std::size_t f = 0; f < 4; ++f)
    {
      const int j = neighbours_[c][f];
      if (j < 0 || pores_[static_cast<std::size_t>(j)].imposed || !pores_[static_cast<std::size_t>(j)].nwReservoir)
        continue;
      const double r = throatRadius_[static_cast<std::size_t>(throats_[c][f])];
      if (r > 0)
        next = std::max(next, std::min(gamma / bodyRadius_[static_cast<std::size_t>(j)], gamma / r));
    }
  }
  return std::isinf(next) ? 0.0 : next;
}

std::vector<double> TwoPhaseFlow::pressures() const
{
  std::vector<double> p(pores_.size());
  std::transform(pores_.begin(), pores_.end(), p.begin(), [](const PoreState& s) { return s.pressure; });
  return p;
}
std::vector<pore::Vec3> TwoPhaseFlow::capillaryForces() const
{
  std::vector<pore::Vec3> f(nVertices_, pore::Vec3::Zero());
  for (std::size_t c = 0; c < pores_.size(); ++c)
    for (std::size_t k = 0; k < 4; ++k)
      f[static_cast<std::size_t>(poreVertices_[c][k])] += pores_[c].pressure * unitForces_[c][k];
  return f;
}
} // namespace talus::flow::twophase
