#include "flow/VansFluid.h"

#include "flow/EffectiveViscosity.h"
#include "flow/InputChecks.h"
#include "flow/MixingLength.h"
#include "flow/WallFriction.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace talus::flow
{
namespace
{
using checks::str;

void checkProfile(const char* name, std::span<const double> values, std::size_t expected, bool isFraction)
{
  checks::checkProfile("VansFluid", name, values, expected, isFraction);
}

void requireTime(bool ok, const char* name, double value, const char* what)
{
  if (!ok)
    throw std::invalid_argument(std::string("VansFluid.fluidResolution: ") + name + " " + what + ", got "
                                + str(value));
}
/// The staggered grid. Mesh nodes z_j (stresses, viscosities) are accumulated as Yade does so
/// that threshold tests on z (viscous sub-layer) fall on the same nodes; velocity nodes sit at
/// the wall, half-way between mesh nodes, and at the top. spacing[j] is the distance between the
/// two velocity nodes around mesh node j (half a cell at the ends); epsNode the fluid fraction at
/// the mesh nodes, the mean of the cells around them.
struct Grid
{
  std::vector<double> z, eps, epsNode, spacing;
};

Grid staggeredGrid(const VansParameters& p, const std::vector<double>& phi)
{
  const auto n = static_cast<std::size_t>(p.nCell);
  const double dz = p.deltaZ;
  Grid g{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n), std::vector<double>(n, dz)};
  g.z[0] = 0.0;
  for (std::size_t j = 1; j < n; ++j)
    g.z[j] = g.z[j - 1] + dz;
  g.spacing[0] = 0.5 * dz;
  g.spacing[n - 1] = 0.5 * dz;
  for (std::size_t j = 0; j < n; ++j)
    g.eps[j] = 1.0 - phi[j];
  g.epsNode[0] = g.eps[0];
  for (std::size_t j = 1; j + 1 < n; ++j)
    g.epsNode[j] = 0.5 * (g.eps[j - 1] + g.eps[j]);
  g.epsNode[n - 1] = g.eps[n - 2];
  return g;
}

/// Drag exchange coefficient taufsi = n <f_D> / (rho |u - v_p|) from the current profiles,
/// frozen for a whole fluidResolution call. |u - v_p| is bounded below to avoid dividing by
/// zero, and taufsi capped at 1/(10 dt) (Yade's choice): `clipped` counts the capped cells.
std::vector<double> dragCoefficients(const VansParameters& p, const std::vector<double>& phi, const std::vector<double>& vp,
                                     const std::vector<double>& averageDrag, const std::vector<double>& vxFluid, double dt,
                                     std::size_t& clipped)
{
  const auto n = static_cast<std::size_t>(p.nCell);
  std::vector<double> taufsi(n, 0.0);
  clipped = 0;
  const double particleVolume = 4. / 3. * std::numbers::pi * std::pow(p.radiusPart, 3);
  const double cap = 1.0 / (10.0 * dt);
  for (std::size_t i = 1; i < n; ++i)
  {
    if (phi[i] == 0.0 || averageDrag[i] == 0.0)
      continue;
    // vxFluid[i + 1] is the velocity node at the centre of cell i.
    const double relative = std::max(std::fabs(vxFluid[i + 1] - vp[i]), 1e-5);
    const double t = phi[i] / particleVolume * averageDrag[i] / relative / p.densFluid;
    if (t > cap)
      ++clipped;
    taufsi[i] = std::max(0.0, std::min(t, cap));
  }
  return taufsi;
}

/// Where the eddy viscosity acts and its factor: nu_t = lm^2 |du/dz| enters row j as
/// dt/dz epsNode nu_t / spacing, so each step only needs factor[j] |u_{j+1} - u_j|.
/// Viscous sub-layer: no eddy viscosity below z+ = 11.3, with the friction velocity of a
/// clear-water gravity-driven flow u* = sqrt(|g_x| h) (Yade's choice, valid without a bed).
struct Turbulence
{
  std::vector<char> node;
  std::vector<double> factor;
};

Turbulence turbulence(const VansParameters& p, const Grid& g, const std::vector<double>& lm, double nu, double dt)
{
  const auto n = static_cast<std::size_t>(p.nCell);
  const double ustar = std::sqrt(std::fabs(p.gravityX) * g.z[n - 1]);
  Turbulence t{std::vector<char>(n, p.turbulence ? 1 : 0), std::vector<double>(n, 0.0)};
  if (p.turbulence && p.viscousSubLayer)
    for (std::size_t j = 1; j < n; ++j)
      t.node[j] = g.z[j] * ustar / nu < 11.3 ? 0 : 1;
  for (std::size_t j = 0; j < n; ++j)
    if (t.node[j])
      t.factor[j] = dt / p.deltaZ * g.epsNode[j] * lm[j] * lm[j] / g.spacing[j] / g.spacing[j];
  return t;
}

/// The parts of rows 1 .. n-1 of the tridiagonal system that stay constant during a call. Row
/// r = j + 1 is the balance of the velocity node at the centre of cell j:
/// a u_{r-1} + b u_r + c u_{r+1} = s. The viscous flux acts on the mixture velocity
/// eps u + phi v_p; its particle part goes to the right-hand side.
struct Rows
{
  std::vector<double> a, b, c, s, wall;
};

Rows constantRows(const VansParameters& p, const Grid& g, const std::vector<double>& nuEff, const std::vector<double>& phi,
                  const std::vector<double>& vp, const std::vector<double>& taufsi, double dt)
{
  const auto n = static_cast<std::size_t>(p.nCell);
  const std::vector<double>& eps = g.eps;
  const std::vector<double>& spacing = g.spacing;
  const double dz = p.deltaZ;
  Rows rows;
  for (std::vector<double>* row : {&rows.a, &rows.b, &rows.c, &rows.s, &rows.wall})
    row->assign(n + 1, 0.0);
  const double gx = std::fabs(p.gravityX);
  for (std::size_t j = 0; j + 1 < n; ++j)
  {
    const std::size_t jm = j == 0 ? 0 : j - 1;  // below the first cell: the first cell again
    const double viscousBelow = dt * eps[j] / dz * nuEff[j] / spacing[j];
    const double viscousAbove = dt * eps[j] / dz * nuEff[j + 1] / spacing[j + 1];
    const double solidFlux = dt * eps[j] / dz
                             * (nuEff[j + 1] / spacing[j + 1] * (phi[j + 1] * vp[j + 1] - phi[j] * vp[j])
                                - nuEff[j] / spacing[j] * (phi[j] * vp[j] - phi[jm] * vp[jm]));
    rows.a[j + 1] = -viscousBelow * eps[jm];
    rows.b[j + 1] = viscousAbove * eps[j] + viscousBelow * eps[j] + eps[j] + dt * taufsi[j];
    rows.c[j + 1] = -viscousAbove * eps[j + 1];
    rows.s[j + 1] = eps[j] * dt * gx + dt * taufsi[j] * vp[j] + solidFlux - eps[j] * p.dpdx / p.densFluid * dt;
    rows.wall[j + 1] = dt * eps[j] * 2. / p.channelWidth * 0.125 * p.fluidFrictionCoef;
  }
  return rows;
}

/// Flip-flop detection. With the eddy viscosity lagged, a step much longer than the turbulent
/// time scale overshoots, and the profile settles into a period-2 oscillation around the steady
/// state instead of reaching it: the last two changes then point in opposite directions.
/// Returns the last change relative to the profile's scale; sets `oscillating`.
double lastChange(const std::vector<double>& u, const std::vector<double>& previous, const std::vector<double>& beforePrevious,
                  std::size_t steps, bool& oscillating)
{
  double change = 0, changeDot = 0, lastNorm = 0, beforeNorm = 0, scale = 0;
  for (std::size_t i = 0; i < u.size(); ++i)
  {
    const double d1 = u[i] - previous[i];
    const double d0 = previous[i] - beforePrevious[i];
    change = std::max(change, std::fabs(d1));
    scale = std::max(scale, std::fabs(u[i]));
    changeDot += d1 * d0;
    lastNorm += d1 * d1;
    beforeNorm += d0 * d0;
  }
  const double relativeChange = scale > 0 ? change / scale : change;
  oscillating = steps >= 2 && relativeChange > VansFluid::oscillationThreshold
                && changeDot < -0.5 * std::sqrt(lastNorm * beforeNorm);
  return relativeChange;
}
} // namespace

VansFluid::VansFluid(const VansParameters& parameters) : m_parameters(parameters)
{
  m_parameters.validate();
  initialization();
}

void VansFluid::setParameters(const VansParameters& parameters)
{
  parameters.validate();
  const bool resized = parameters.nCell != m_parameters.nCell;
  m_parameters = parameters;
  if (resized)
    initialization();
}

void VansFluid::initialization()
{
  const auto n = static_cast<std::size_t>(m_parameters.nCell);
  for (std::vector<double>* profile : {&m_phiPart, &m_vxPart, &m_averageDrag, &m_reynoldStresses,
                                       &m_turbulentViscosity, &m_taufsi, &m_mixingLength})
    profile->assign(n, 0.0);
  m_vxFluid.assign(n + 1, 0.0);
  m_clippedDragCells = 0;
  m_lastStepCount = 0;
  m_lastStepChange = 0;
  m_oscillating = false;
}

void VansFluid::setPhiPart(std::span<const double> phiPart)
{
  checkProfile("phiPart", phiPart, m_phiPart.size(), true);
  m_phiPart.assign(phiPart.begin(), phiPart.end());
}

void VansFluid::setVxPart(std::span<const double> vxPart)
{
  checkProfile("vxPart", vxPart, m_vxPart.size(), false);
  m_vxPart.assign(vxPart.begin(), vxPart.end());
}

void VansFluid::setAverageDrag(std::span<const double> averageDrag)
{
  checkProfile("averageDrag", averageDrag, m_averageDrag.size(), false);
  m_averageDrag.assign(averageDrag.begin(), averageDrag.end());
}

void VansFluid::setVxFluid(std::span<const double> vxFluid)
{
  checkProfile("vxFluid", vxFluid, m_vxFluid.size(), false);
  m_vxFluid.assign(vxFluid.begin(), vxFluid.end());
}

std::vector<double> VansFluid::velocityNodeElevations() const
{
  const int n = m_parameters.nCell;
  std::vector<double> z(static_cast<std::size_t>(n) + 1);
  z[0] = 0.0;
  for (int j = 0; j + 1 < n; ++j)
    z[static_cast<std::size_t>(j) + 1] = (j + 0.5) * m_parameters.deltaZ;
  z[static_cast<std::size_t>(n)] = m_parameters.fluidHeight();
  return z;
}

std::vector<double> VansFluid::meshNodeElevations() const
{
  std::vector<double> z(static_cast<std::size_t>(m_parameters.nCell));
  for (std::size_t j = 0; j < z.size(); ++j)
    z[j] = static_cast<double>(j) * m_parameters.deltaZ;
  return z;
}

void VansFluid::fluidResolution(double tfin, double dt)
{
  requireTime(std::isfinite(tfin) && tfin >= 0, "tfin", tfin, "must be finite and >= 0");
  requireTime(std::isfinite(dt) && dt > 0, "dt", dt, "must be finite and positive");
  const VansParameters& p = m_parameters;
  if (p.nCell < 2)
    throw std::invalid_argument("VansFluid.fluidResolution: nCell must be at least 2 (the fluid column is (nCell - 1) "
                                "deltaZ high), got " + std::to_string(p.nCell));
  const auto n = static_cast<std::size_t>(p.nCell);
  const std::vector<double>& phi = m_phiPart;
  const std::vector<double>& vp = m_vxPart;
  if (p.radiusPart <= 0)
    for (std::size_t i = 1; i < n; ++i)
      if (phi[i] != 0.0 && m_averageDrag[i] != 0.0)
        throw std::invalid_argument("VansFluid: radiusPart must be positive when averageDrag is non-zero (cell "
                                    + std::to_string(i) + ")");
  const double nu = p.viscoDyn / p.densFluid;

  // What stays constant during the call: the grid, the drag coefficients, the closures that do
  // not depend on the velocity (effective viscosity, mixing length) and the rows built on them.
  const Grid grid = staggeredGrid(p, phi);
  std::size_t clipped = 0;
  std::vector<double> taufsi = dragCoefficients(p, phi, vp, m_averageDrag, m_vxFluid, dt, clipped);
  std::vector<double> nuEff(n), lm(n);
  flow::effectiveViscosity(p.effectiveViscosity, nu, phi, nuEff);
  flow::mixingLength(p.mixingLength, p.kappa, p.phiMax, grid.z, p.deltaZ, phi, lm);
  const Turbulence eddy = turbulence(p, grid, lm, nu, dt);
  const Rows rows = constantRows(p, grid, nuEff, phi, vp, taufsi, dt);

  // Time loop: lagged eddy viscosity, then one tridiagonal solve (Thomas algorithm) whose rows
  // are assembled inside the forward sweep, so each step is a single pass up and down. Three
  // profiles rotate: `u` (current), `previous` (one step back) and `next` (the solve's output,
  // afterwards two steps back), so the last two changes can be compared at the end.
  std::vector<double> u = m_vxFluid, previous = m_vxFluid, next = m_vxFluid;
  std::vector<double> turbulent(n), cp(n + 1), dp(n + 1);
  const bool freeSurface = p.topBoundary == TopBoundary::FreeSurface;
  std::size_t steps = 0;
  double time = 0;
  while (time < tfin)
  {
    // The time is summed as Yade does, so both take the same number of steps. A dt below the
    // rounding of the summed time would never reach tfin: refuse it rather than hang.
    const double advanced = time + dt;
    if (advanced == time)
      throw std::invalid_argument("VansFluid.fluidResolution: dt = " + str(dt) + " is too small to advance the time "
                                  + str(time) + " in floating point (tfin = " + str(tfin) + ")");
    time = advanced;
    ++steps;
    for (std::size_t j = 0; j < n; ++j)
      turbulent[j] = eddy.factor[j] * std::fabs(u[j + 1] - u[j]);

    cp[0] = 0.0;  // row 0: u_0 = 0, no-slip bottom wall
    dp[0] = 0.0;
    for (std::size_t r = 1; r < n; ++r)
    {
      const std::size_t j = r - 1;
      const double a = rows.a[r] - turbulent[j];
      const double c = rows.c[r] - turbulent[j + 1];
      double b = rows.b[r] + turbulent[j] + turbulent[j + 1];
      double s = rows.s[r] + u[r] * grid.eps[j];
      if (p.fluidWallFriction)
      {
        const double f = wallFrictionFactor(std::fabs(u[r]) * p.channelWidth / nu);
        const double w = rows.wall[r] * f * u[r] * u[r];
        b += 0.5 * w;  // half implicit, half explicit, as in Yade
        s -= 0.5 * w;
      }
      const double inversePivot = 1.0 / (b - a * cp[r - 1]);
      cp[r] = c * inversePivot;
      dp[r] = (s - a * dp[r - 1]) * inversePivot;
    }
    // Top row: u_n = uTop, or u_n - u_{n-1} = 0 (zero flux through the free surface).
    next[n] = freeSurface ? dp[n - 1] / (1.0 + cp[n - 1]) : p.uTop;
    for (std::size_t r = n; r-- > 0;)
      next[r] = dp[r] - cp[r] * next[r + 1];
    // A non-finite value anywhere reaches u_0 through both sweeps: one test per step suffices.
    if (!std::isfinite(next[0]))
      throw std::runtime_error("VansFluid.fluidResolution: the fluid velocity became non-finite at step "
                               + std::to_string(steps) + " (t = " + str(time)
                               + "); the profiles were left unchanged. Check the inputs' magnitudes.");
    std::swap(previous, u);
    std::swap(u, next);
  }
  bool oscillating = false;
  const double relativeChange = lastChange(u, previous, next, steps, oscillating);

  // Outputs: eddy viscosity of the last step (from the profile it started with, now in
  // `previous`), and the Reynolds stress it gives with the final profile.
  std::vector<double> viscoft(n, 0.0), stress(n, 0.0);
  if (steps > 0)
    for (std::size_t j = 0; j < n; ++j)
      if (eddy.node[j])
        viscoft[j] = lm[j] * lm[j] * std::fabs((previous[j + 1] - previous[j]) / grid.spacing[j]);
  for (std::size_t j = 0; j < n; ++j)
    stress[j] = p.densFluid * grid.epsNode[j] * viscoft[j] * (u[j + 1] - u[j]) / grid.spacing[j];

  m_vxFluid = std::move(u);
  m_taufsi = std::move(taufsi);
  m_mixingLength = std::move(lm);
  m_turbulentViscosity = std::move(viscoft);
  m_reynoldStresses = std::move(stress);
  m_clippedDragCells = clipped;
  m_lastStepCount = steps;
  m_lastStepChange = relativeChange;
  m_oscillating = oscillating;
}
} // namespace talus::flow
