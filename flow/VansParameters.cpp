#include "flow/VansParameters.h"

#include "flow/InputChecks.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::flow
{
namespace
{
constexpr const char* owner = "VansFluid";
using checks::str;

void require(bool ok, const char* name, const std::string& what) { checks::require(ok, owner, name, what); }
void requireFinite(double value, const char* name) { checks::requireFinite(value, owner, name); }
} // namespace

void VansParameters::validate() const
{
  require(nCell >= 1, "nCell", "must be at least 1, got " + std::to_string(nCell));
  requireFinite(deltaZ, "deltaZ");
  require(deltaZ > 0, "deltaZ", "must be positive, got " + str(deltaZ));
  requireFinite(densFluid, "densFluid");
  require(densFluid > 0, "densFluid", "must be positive, got " + str(densFluid));
  requireFinite(viscoDyn, "viscoDyn");
  require(viscoDyn >= 0, "viscoDyn", "must not be negative, got " + str(viscoDyn));
  requireFinite(gravityX, "gravity");
  requireFinite(dpdx, "dpdx");
  requireFinite(kappa, "kappa");
  require(kappa >= 0, "kappa", "must not be negative, got " + str(kappa));
  requireFinite(phiMax, "phiMax");
  require(phiMax > 0 && phiMax <= 1, "phiMax", "must be in (0, 1], got " + str(phiMax));
  requireFinite(uTop, "uTop");
  requireFinite(channelWidth, "channelWidth");
  require(channelWidth > 0, "channelWidth", "must be positive, got " + str(channelWidth));
  requireFinite(fluidFrictionCoef, "fluidFrictionCoef");
  require(fluidFrictionCoef >= 0, "fluidFrictionCoef",
          "must not be negative, got " + str(fluidFrictionCoef));
  requireFinite(radiusPart, "radiusPart");
  require(radiusPart >= 0, "radiusPart", "must not be negative, got " + str(radiusPart));
  const int ilm = static_cast<int>(mixingLength);
  require(ilm >= 0 && ilm <= 2, "ilm", "(mixing length) must be 0, 1 or 2, got " + std::to_string(ilm));
  const int irheolf = static_cast<int>(effectiveViscosity);
  require(irheolf >= 0 && irheolf <= 2, "irheolf",
          "(effective viscosity) must be 0, 1 or 2, got " + std::to_string(irheolf));
  const int iusl = static_cast<int>(topBoundary);
  require(iusl == 0 || iusl == 1, "iusl", "(top boundary) must be 0 or 1, got " + std::to_string(iusl));
}
} // namespace talus::flow
