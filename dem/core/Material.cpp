#include "dem/core/Material.h"

#include <cmath>
#include <stdexcept>

namespace talus::dem
{
namespace
{
void require(bool ok, const Material& m, const std::string& what)
{
  if (!ok)
    throw std::invalid_argument("material '" + (m.label.empty() ? std::string("(no label)") : m.label)
                                + "': " + what);
}
} // namespace

void Material::validate() const
{
  // Zero is allowed, as in Yade (walls and fixed bodies); a dynamic body needs a mass (NewtonIntegrator).
  require(std::isfinite(density) && density >= 0, *this, "density must be finite and >= 0");
  require(std::isfinite(frictionAngle) && frictionAngle >= 0 && frictionAngle < M_PI / 2, *this,
          "frictionAngle must be in [0, pi/2) radians");
  if (kind == MaterialKind::CohFrict)
  {
    require(std::isfinite(normalCohesion) && std::isfinite(shearCohesion), *this, "normalCohesion and shearCohesion must be finite");
    require(std::isfinite(alphaKr) && alphaKr >= 0 && std::isfinite(alphaKtw) && alphaKtw >= 0, *this,
            "alphaKr and alphaKtw must be finite and >= 0");
    require(std::isfinite(etaRoll) && std::isfinite(etaTwist), *this, "etaRoll and etaTwist must be finite");
  }
  if (kind == MaterialKind::Frict || kind == MaterialKind::CohFrict)
  {
    // FrictMat(young=0) is accepted, as in Yade: its contacts have no stiffness (Yade's scripts
    // give it to bodies that only show something, e.g. a rising water level).
    if (kind == MaterialKind::Frict)
      require(std::isfinite(young) && young >= 0, *this, "young must be finite and >= 0");
    else
      require(std::isfinite(young) && young > 0, *this, "young must be positive and finite");
    require(std::isfinite(poisson) && poisson >= 0, *this, "poisson (the ks/kn ratio) must be >= 0");
    return;
  }
  // Yade's three forms, tried in this order when a contact is made (Ip2_ViscElMat_ViscElMat_ViscElPhys;
  // its tc, en, et can also come from the functor). An incomplete group would make Yade fall
  // through to the next form and silently ignore it, so it is refused here.
  const bool fromTimes = std::isfinite(tc), fromStiffness = std::isfinite(kn);
  require(!(fromTimes && fromStiffness), *this, "ViscElMat takes either tc (with en, et) or kn (with cn, ks, cs), not both");
  if (fromTimes)
    require(tc > 0 && std::isfinite(en) && std::isfinite(et), *this, "tc must be positive and comes with en and et");
  if (fromStiffness)
    require(kn > 0 && std::isfinite(ks) && ks >= 0 && std::isfinite(cn) && cn >= 0 && std::isfinite(cs) && cs >= 0,
            *this, "kn must be positive and comes with cn, ks, cs (>= 0)");
  if (!fromTimes && !fromStiffness)
  {
    require(std::isfinite(young) && young > 0, *this, "young must be positive and finite");
    require(std::isfinite(poisson) && poisson >= 0, *this, "poisson (the ks/kn ratio) must be >= 0");
    require(std::isfinite(cn) == std::isfinite(cs), *this, "cn and cs come together (with young, poisson)");
  }
  require(std::isnan(en) || (en > 0 && en <= 1), *this, "en must be in (0, 1]");
  require(std::isnan(et) || (et >= 0 && et <= 1), *this, "et must be in [0, 1]");
  require(!fromTimes || et > 0, *this, "et must be positive with tc");
  require(std::isfinite(mR) && mR >= 0, *this, "mR must be finite and >= 0");
  require(mRtype == 1 || mRtype == 2, *this, "mRtype must be 1 or 2");
  if (lubrication)
  {
    // Yade applies it only where the restitution sets the dashpot of a young-based contact.
    require(!fromTimes && !fromStiffness && std::isfinite(en), *this,
            "lubrication needs the young, poisson, en form (Yade ignores it otherwise)");
    require(std::isfinite(viscoDyn) && viscoDyn > 0 && std::isfinite(roughnessScale) && roughnessScale > 0, *this,
            "viscoDyn and roughnessScale must be positive with lubrication");
  }
}
} // namespace talus::dem
