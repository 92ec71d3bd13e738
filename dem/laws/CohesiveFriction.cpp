// Cohesive-frictional contact with rolling and twisting resistance and bond breakage, as Yade's
// Ip2_CohFrictMat_CohFrictMat_CohFrictPhys + Law2_ScGeom6D_CohFrictPhys_CohesionMoment (without
// creep): a bond's normal spring, the incremental shear spring capped at the bond's strength,
// and the rolling and twisting moments. The relative rotation of ScGeom6D (twist and bending)
// lives in ContactExtra.
#include "dem/laws/PartsLaw.h"

#include <algorithm>
#include <cmath>

namespace talus::dem
{
namespace
{
const Material& material(const std::deque<Material>& materials, const Bodies& b, BodyId id)
{
  return materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(id)])];
}

/// Create the bond: strengths = cohesion (the smaller of the two) times the smaller radius
/// squared.
void bond(const Contact& c, ContactExtra& x, const Material& m1, const Material& m2)
{
  if (!m1.isCohesive || !m2.isCohesive)
    return;
  const double r2 = std::pow(std::min(c.refR1, c.refR2), 2);
  x.cohesionBroken = 0;
  x.normalAdhesion = r2 * std::min(m1.normalCohesion, m2.normalCohesion);
  x.shearAdhesion = r2 * std::min(m1.shearCohesion, m2.shearCohesion);
  x.fragile = m1.fragile || m2.fragile;
}

/// Ip2_CohFrictMat_CohFrictMat_CohFrictPhys: pairs of CohFrictMat.
struct CohFrictPhys
{
  static constexpr const char* ip2 = "Ip2_CohFrictMat_CohFrictMat_CohFrictPhys";
  static constexpr bool usesExtra = true;
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const
  {
    return m1.kind == MaterialKind::CohFrict && m2.kind == MaterialKind::CohFrict ? 2 : 0;
  }

  // Bond every cohesive contact at the next step (one shot), bond new contacts.
  bool setCohesionNow = false, setCohesionOnNewContacts = false;
  static constexpr auto parameters()
  {
    return std::tuple{parts::parameter("setCohesionNow", &CohFrictPhys::setCohesionNow),
                      parts::parameter("setCohesionOnNewContacts", &CohFrictPhys::setCohesionOnNewContacts)};
  }
  void stepDone() { setCohesionNow = false; }

  /// kn = 2 E1 r1 E2 r2 / (E1 r1 + E2 r2), ks the same with E_i nu_i, tan(phi) of the smaller
  /// angle; kr = r1 r2 ks alphaKr, ktw = r1 r2 ks alphaKtw (harmonic means of the materials'
  /// alphas); plastic moments etaRoll r, etaTwist r (smaller of the two) per unit normal force
  /// when both materials have momentRotationLaw. A bond if asked (setCohesionOnNewContacts or
  /// setCohesionNow) and both materials are cohesive.
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const
  {
    const Material& m1 = material(scene.materials, scene.bodies, c.id1);
    const Material& m2 = material(scene.materials, scene.bodies, c.id2);
    const double da = c.refR1, db = c.refR2;
    const double a = m1.young * da, b = m2.young * db;
    c.kn = 2 * a * b / (a + b);
    c.ks = m1.poisson > 0 && m2.poisson > 0 ? 2 * a * m1.poisson * b * m2.poisson / (a * m1.poisson + b * m2.poisson) : 0;
    c.cn = c.cs = 0;
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
    const auto harmonic = [](double p, double q) { return p + q > 0 ? 2 * p * q / (p + q) : 0.0; };
    *x = ContactExtra{};
    x->kr = da * db * c.ks * harmonic(m1.alphaKr, m2.alphaKr);
    x->ktw = da * db * c.ks * harmonic(m1.alphaKtw, m2.alphaKtw);
    x->momentRotationLaw = m1.momentRotationLaw && m2.momentRotationLaw;
    x->maxRollPl = x->momentRotationLaw ? std::min(m1.etaRoll * da, m2.etaRoll * db) : 0;
    x->maxTwistPl = x->momentRotationLaw ? std::min(m1.etaTwist * da, m2.etaTwist * db) : 0;
    parts::startRotations(c, *x, scene.bodies);
    if (setCohesionOnNewContacts || setCohesionNow)
      bond(c, *x, m1, m2);
  }

  /// setCohesionNow bonds the contacts without a bond (rotations count from now).
  void beforeForce(Contact& c, ContactExtra& x, const StepContext& step) const
  {
    if (setCohesionNow && !c.fresh && x.cohesionBroken)
    {
      bond(c, x, material(step.materials, step.bodies, c.id1), material(step.materials, step.bodies, c.id2));
      parts::startRotations(c, x, step.bodies);
    }
  }
};

struct CohesiveFrictionNames
{
  static constexpr const char* law = "Law2_ScGeom6D_CohFrictPhys_CohesionMoment";
};
} // namespace

/// Normal: F_n = kn (u - unp); tension beyond the bond's strength breaks a fragile bond (the
/// contact ends) or yields (unp grows). Shear: incremental, capped at shearAdhesion +
/// F_n tan(phi); exceeding it breaks a fragile bond. Moments (momentRotationLaw, while bonded
/// or always_use_moment_law): bending kr and twist ktw springs on the relative rotation since
/// the bond (or incremental), capped at maxRollPl |F_n| and maxTwistPl |F_n| when those are
/// >= 0. Elastic energy 1/2 kn (u_n - unp)^2 + 1/2 Fs^2/ks + the moment springs' 1/2 M^2/k.
using CohesiveFriction = PartsLaw<CohesiveFrictionNames, CohFrictPhys, parts::BondedSpring, parts::NoDamping,
                                  parts::BondedCoulomb, parts::RotationMoments>;

TALUS_REGISTER_PARTS_LAW(CohesiveFriction, "cohesive")
} // namespace talus::dem
