// Cohesive-frictional contact with rolling and twisting resistance and bond breakage, as Yade's
// Ip2_CohFrictMat_CohFrictMat_CohFrictPhys + Law2_ScGeom6D_CohFrictPhys_CohesionMoment (without
// creep). The relative rotation of ScGeom6D (twist and bending) lives in ContactExtra.
#include "dem/laws/ContactLawKernel.h"
#include "dem/laws/parts/Bond.h"
#include "dem/laws/parts/Coulomb.h"
#include "dem/laws/parts/Moments.h"

#include <algorithm>
#include <cmath>

namespace talus::dem
{
class CohesiveFriction : public ContactLawKernel<CohesiveFriction>
{
public:
  static constexpr bool usesExtra = true;

  [[nodiscard]] std::string typeName() const override { return "Law2_ScGeom6D_CohFrictPhys_CohesionMoment"; }
  [[nodiscard]] std::string physicsName() const override { return "Ip2_CohFrictMat_CohFrictMat_CohFrictPhys"; }
  [[nodiscard]] int handles(const Material& m1, const Material& m2) const override
  {
    return m1.kind == MaterialKind::CohFrict && m2.kind == MaterialKind::CohFrict ? 2 : 0;
  }

  // Ip2 parameters: bond every cohesive contact at the next step (one shot), bond new contacts.
  bool setCohesionNow = false, setCohesionOnNewContacts = false;
  // Law2 parameters: moments from incremental rotations (plastic limits are then exact) rather
  // than from the total rotation since the bond; keep moments after the bond broke.
  bool useIncrementalForm = false, alwaysUseMomentLaw = false;

  [[nodiscard]] std::vector<std::string> parameterNames() const override
  {
    return {"setCohesionNow", "setCohesionOnNewContacts", "useIncrementalForm", "always_use_moment_law"};
  }
  void setParameter(const std::string& name, double value) override { *flag(name) = value != 0; }
  [[nodiscard]] double parameter(const std::string& name) const override
  {
    return *const_cast<CohesiveFriction*>(this)->flag(name) ? 1.0 : 0.0;
  }

  /// kn = 2 E1 r1 E2 r2 / (E1 r1 + E2 r2), ks the same with E_i nu_i, tan(phi) of the smaller
  /// angle; kr = r1 r2 ks alphaKr, ktw = r1 r2 ks alphaKtw (harmonic means of the materials'
  /// alphas); plastic moments etaRoll r, etaTwist r (smaller of the two) per unit normal force
  /// when both materials have momentRotationLaw. A bond if asked (setCohesionOnNewContacts or
  /// setCohesionNow) and both materials are cohesive.
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const override
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

  /// Normal: F_n = kn (u - unp); tension beyond the bond's strength breaks a fragile bond (the
  /// contact ends) or yields (unp grows). Shear: incremental, capped at shearAdhesion +
  /// F_n tan(phi); exceeding it breaks a fragile bond. Moments (momentRotationLaw, while bonded
  /// or always_use_moment_law): bending kr and twist ktw springs on the relative rotation since
  /// the bond (or incremental), capped at maxRollPl |F_n| and maxTwistPl |F_n| when those are
  /// >= 0.
  template <bool Track>
  void force(Contact& c, std::size_t k, const StepContext& step, ContactEnergy& energy) const
  {
    ContactExtra& x = step.extra[k];
    const Bodies& b = step.bodies;
    if (setCohesionNow && !c.fresh && x.cohesionBroken)
    {
      bond(c, x, material(step.materials, b, c.id1), material(step.materials, b, c.id2));
      parts::startRotations(c, x, b);
    }
    double fn = c.kn * (c.penetration - x.unp);
    if (-fn > x.normalAdhesion)
    {
      if (x.fragile)
      {
        end(c, x);
        return;
      }
      fn = -x.normalAdhesion;
      x.unp = c.penetration + x.normalAdhesion / c.kn;
      if (x.unpMax >= 0 && -x.unp > x.unpMax)
      {
        end(c, x);
        return;
      }
    }
    c.normalForce = fn * c.normal;
    c.shearForce -= c.ks * c.shearIncrement;
    double maxFs = parts::bondedShearStrength(x.shearAdhesion, fn, c.tanPhi, x.cohesionDisablesFriction);
    const double fs = c.shearForce.norm();
    if (fs > maxFs)
    {
      if (x.fragile && !x.cohesionBroken)
      {
        breakBond(x);
        maxFs = parts::frictionStrength(fn, c.tanPhi);
      }
      parts::slide<Track>(c, maxFs / fs, energy);
      if (fn < 0)
        c.normalForce.setZero();
    }
    c.force = c.normalForce + c.shearForce;

    if (!x.momentRotationLaw || (x.cohesionBroken && !alwaysUseMomentLaw))
    {
      x.momentBending.setZero();
      x.momentTwist.setZero();
      return;
    }
    if (useIncrementalForm)
      parts::incrementalRotationMoments(c, x, b, step.dt);
    else
      parts::totalRotationMoments(c, x, b);
    const double normal = c.normalForce.norm();
    parts::capMoment<Track>(x.momentBending, x.maxRollPl, normal, x.kr, useIncrementalForm, energy);
    parts::capMoment<Track>(x.momentTwist, x.maxTwistPl, normal, x.ktw, useIncrementalForm, energy);
  }

  /// 1/2 kn (u_n - unp)^2 + 1/2 Fs^2/ks + the moment springs' 1/2 M^2/k.
  double elastic(const Contact& c, const ContactExtra* x) const
  {
    double e = springEnergy(c, c.penetration - (x ? x->unp : 0.0));
    if (x && x->kr > 0)
      e += 0.5 * x->momentBending.squaredNorm() / x->kr;
    if (x && x->ktw > 0)
      e += 0.5 * x->momentTwist.squaredNorm() / x->ktw;
    return e;
  }

protected:
  void stepDone() override { setCohesionNow = false; }

private:
  bool* flag(const std::string& name)
  {
    if (name == "setCohesionNow")
      return &setCohesionNow;
    if (name == "setCohesionOnNewContacts")
      return &setCohesionOnNewContacts;
    if (name == "useIncrementalForm")
      return &useIncrementalForm;
    if (name == "always_use_moment_law")
      return &alwaysUseMomentLaw;
    unknownParameter(name);
  }

  static const Material& material(const std::deque<Material>& materials, const Bodies& b, BodyId id)
  {
    return materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(id)])];
  }

  /// Create the bond: strengths = cohesion (the smaller of the two) times the smaller radius
  /// squared.
  static void bond(const Contact& c, ContactExtra& x, const Material& m1, const Material& m2)
  {
    if (!m1.isCohesive || !m2.isCohesive)
      return;
    const double r2 = std::pow(std::min(c.refR1, c.refR2), 2);
    x.cohesionBroken = 0;
    x.normalAdhesion = r2 * std::min(m1.normalCohesion, m2.normalCohesion);
    x.shearAdhesion = r2 * std::min(m1.shearCohesion, m2.shearCohesion);
    x.fragile = m1.fragile || m2.fragile;
  }

  void breakBond(ContactExtra& x) const
  {
    x.cohesionBroken = 1;
    x.normalAdhesion = x.shearAdhesion = 0;
    if (!alwaysUseMomentLaw)
    {
      x.momentBending.setZero();
      x.momentTwist.setZero();
    }
  }

  /// The contact ends (Yade erases the interaction): forces and history are dropped.
  static void end(Contact& c, ContactExtra& x)
  {
    c.reset();
    x.cohesionBroken = 1;
    x.normalAdhesion = x.shearAdhesion = 0;
    x.momentBending.setZero();
    x.momentTwist.setZero();
  }
};

TALUS_REGISTER_CONTACT_LAW(CohesiveFriction, "Law2_ScGeom6D_CohFrictPhys_CohesionMoment", "cohesive")
} // namespace talus::dem
