#include "dem/Material.h"

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
    require(std::isfinite(young) && young > 0, *this, "young must be positive and finite");
    require(std::isfinite(poisson) && poisson >= 0, *this, "poisson (the ks/kn ratio) must be >= 0");
    return;
  }
  const bool fromTimes = std::isfinite(tc);
  const bool fromStiffness = std::isfinite(kn);
  require(fromTimes != fromStiffness, *this, "ViscElMat needs either tc (with en, et) or kn (with cn, ks, cs)");
  if (fromTimes)
  {
    require(tc > 0, *this, "tc must be positive");
    require(std::isfinite(en) && en > 0 && en <= 1, *this, "en must be in (0, 1]");
    require(std::isfinite(et) && et > 0 && et <= 1, *this, "et must be in (0, 1]");
  }
  else
  {
    require(kn > 0 && std::isfinite(ks) && ks >= 0, *this, "kn must be positive and ks >= 0");
    require(std::isfinite(cn) && cn >= 0 && std::isfinite(cs) && cs >= 0, *this, "cn and cs must be >= 0");
  }
}
} // namespace talus::dem
