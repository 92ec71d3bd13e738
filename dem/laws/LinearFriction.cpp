// Linear elastic contact with Coulomb friction (Cundall & Strack), as Yade's
// Ip2_FrictMat_FrictMat_FrictPhys + Law2_ScGeom_FrictPhys_CundallStrack.
#include "dem/laws/ContactLawKernel.h"

#include <algorithm>
#include <cmath>

namespace talus::dem
{
namespace
{
/// Harmonic-type average 2ab/(a+b) of two springs in series, 0 if both are 0.
double series(double a, double b) { return a + b > 0 ? 2 * a * b / (a + b) : 0.0; }
} // namespace

class LinearFriction : public ContactLawKernel<LinearFriction>
{
public:
  [[nodiscard]] std::string typeName() const override { return "Law2_ScGeom_FrictPhys_CundallStrack"; }
  [[nodiscard]] std::string physicsName() const override { return "Ip2_FrictMat_FrictMat_FrictPhys"; }
  [[nodiscard]] int handles(const Material&, const Material&) const override { return 1; }

  /// Two springs in series, each of stiffness E_i * 2 r_i (normal) and E_i * 2 r_i * nu_i
  /// (shear); friction angle = the smaller of the two.
  void initialize(Contact& c, ContactExtra* /*x*/, const Scene& scene) const override
  {
    const Material& m1 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(scene.bodies.material[static_cast<std::size_t>(c.id2)])];
    const double a = m1.young * c.refR1, b = m2.young * c.refR2;
    c.kn = series(a, b);
    c.ks = series(a * m1.poisson, b * m2.poisson);
    c.cn = c.cs = 0;
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
  }

  /// F_n = kn u_n n; F_s -= ks du_s, capped at tan(phi) |F_n|; sliding dissipates the slip
  /// (F_trial - F_s) / ks times F_s.
  template <bool Track>
  void force(Contact& c, std::size_t /*k*/, const StepContext& /*step*/, ContactEnergy& e) const
  {
    c.normalForce = c.kn * c.penetration * c.normal;
    c.shearForce -= c.ks * c.shearIncrement;
    const double maxFs2 = c.normalForce.squaredNorm() * c.tanPhi * c.tanPhi;
    const double fs2 = c.shearForce.squaredNorm();
    if (fs2 > maxFs2)
    {
      const Vec3 trial = c.shearForce;
      c.shearForce *= std::sqrt(maxFs2 / fs2);
      if constexpr (Track)
        e.plastDissip += (trial - c.shearForce).dot(c.shearForce) / c.ks;
    }
    c.force = c.normalForce + c.shearForce;
  }

  /// 1/2 kn u_n^2 + 1/2 Fs^2 / ks.
  double elastic(const Contact& c, const ContactExtra* /*x*/) const { return springEnergy(c, c.penetration); }
};

TALUS_REGISTER_CONTACT_LAW(LinearFriction, "Law2_ScGeom_FrictPhys_CundallStrack", "linear")
} // namespace talus::dem
