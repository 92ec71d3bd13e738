// Contact laws of Potential Blocks (Boon et al. 2012) and Potential Particles (Boon et al.
// 2013), as Yade's Ip2_FrictMat_FrictMat_KnKsPBPhys + Law2_SCG_KnKsPBPhys_KnKsPBLaw and
// Ip2_FrictMat_FrictMat_KnKsPhys + Law2_SCG_KnKsPhys_KnKsLaw: stiffnesses per unit contact
// area, times the area of the overlap region's section computed by the geometry, a dashpot on
// the normal spring and the incremental shear spring capped by Coulomb friction. The two differ
// only where Yade's do: the particles' law has no separate boundary stiffness (its kn_i, ks_i
// are accepted and unused) and caps the shear force with the damped normal force. The blocks'
// law also has Yade's rock-joint bonds (useFaceProperties): a contact between two intact-rock
// faces (BlockGen's rock bridges and cemented joints) carries a cohesion and a tensile strength
// until it breaks, then it is frictional.
#include "dem/laws/PartsLaw.h"
#include "dem/laws/parts/AreaDashpot.h"
#include "dem/laws/parts/JointCoulomb.h"
#include "dem/laws/parts/JointSpring.h"
#include "dem/laws/parts/RockJoint.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace talus::dem
{
namespace
{
/// Ip2_FrictMat_FrictMat_KnKsPBPhys (Blocks) or Ip2_FrictMat_FrictMat_KnKsPhys: any pair of
/// materials, for the contacts of Potential Blocks or Particles. Friction from the smaller
/// FrictMat angle; at every step kn = Knormal A, ks = Kshear A (blocks: with a boundary block
/// kn_i A, ks_i A; the particles' law takes kn_i, ks_i and uses them not, as Yade's), A the
/// area of the overlap region's section (AreaState), with a floor of (1e-3 R)^2 so a vertex
/// touching a face still has some stiffness (calContactArea false: A = 1). Blocks: a new
/// contact's bond from its faces (bondFaces).
template <bool Blocks>
struct KnKsPhys
{
  static constexpr const char* ip2 = Blocks ? "Ip2_FrictMat_FrictMat_KnKsPBPhys" : "Ip2_FrictMat_FrictMat_KnKsPhys";
  static constexpr bool usesExtra = true; // the contact area (and the blocks' bond)
  // Stiffnesses per unit area (N/m^3) between non-boundary blocks (Knormal, Kshear) and between a
  // boundary block and another (kn_i, ks_i); Ig2_PB_PB_ScGeom's calContactArea. Blocks only:
  // useFaceProperties (new contacts read the faces' rock-joint properties) and the flags given to
  // a new bond (Yade's defaults, true: none; a scene of generated blocks sets them false for its
  // first step, so that only the faces that were cut are bonded).
  double Knormal = 1e8, Kshear = 1e7, kn_i = 1e8, ks_i = 1e7;
  bool calContactArea = true, useFaceProperties = false, cohesionBroken = true, tensionBroken = true;
  static constexpr auto parameters()
  {
    const auto stiffness = std::tuple{parts::parameter("Knormal", &KnKsPhys::Knormal),
                                      parts::parameter("Kshear", &KnKsPhys::Kshear),
                                      parts::parameter("kn_i", &KnKsPhys::kn_i), parts::parameter("ks_i", &KnKsPhys::ks_i),
                                      parts::parameter("calContactArea", &KnKsPhys::calContactArea)};
    if constexpr (Blocks)
      return std::tuple_cat(stiffness, std::tuple{parts::parameter("useFaceProperties", &KnKsPhys::useFaceProperties),
                                                  parts::parameter("cohesionBroken", &KnKsPhys::cohesionBroken),
                                                  parts::parameter("tensionBroken", &KnKsPhys::tensionBroken)});
    else
      return stiffness;
  }

  [[nodiscard]] int handles(const Material& /*m1*/, const Material& /*m2*/) const { return 1; }
  [[nodiscard]] bool handlesGeometry(ContactGeometryKind kind) const
  {
    return Blocks ? kind == ContactGeometryKind::BlockBlock || kind == ContactGeometryKind::WallBlock
                  : kind == ContactGeometryKind::ParticleParticle || kind == ContactGeometryKind::WallParticle;
  }
  void initialize(Contact& c, ContactExtra* x, const Scene& scene) const
  {
    const auto& b = scene.bodies;
    const Material& m1 = scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id1)])];
    const Material& m2 = scene.materials[static_cast<std::size_t>(b.material[static_cast<std::size_t>(c.id2)])];
    c.tanPhi = std::tan(std::min(m1.frictionAngle, m2.frictionAngle));
    if constexpr (Blocks)
      if (x)
        parts::bondFaces(c, *x, b, area(c, *x), useFaceProperties, cohesionBroken, tensionBroken);
  }
  void beforeForce(Contact& c, ContactExtra& x, const StepContext& step) const
  {
    const auto i1 = static_cast<std::size_t>(c.id1), i2 = static_cast<std::size_t>(c.id2);
    const bool boundary = Blocks && (parts::isBoundaryBlock(step.bodies, i1) || parts::isBoundaryBlock(step.bodies, i2));
    const double a = area(c, x);
    c.kn = (boundary ? kn_i : Knormal) * a;
    c.ks = (boundary ? ks_i : Kshear) * a;
  }

private:
  [[nodiscard]] double area(const Contact& c, const ContactExtra& x) const
  {
    if (!calContactArea)
      return 1.0;
    const double r = std::min(c.refR1, c.refR2);
    return std::max(x.contactArea, 1e-6 * r * r);
  }
};

struct KnKsPBNames
{
  static constexpr const char* law = "Law2_SCG_KnKsPBPhys_KnKsPBLaw";
};
struct KnKsPPNames
{
  static constexpr const char* law = "Law2_SCG_KnKsPhys_KnKsLaw";
};
} // namespace

/// F_n = Knormal A u_n n (with a boundary block kn_i A), with its dashpot; F_s -= Kshear A du_s
/// capped at tan(phi) |F_n| (elastic F_n; a rock joint's bond adds its cohesion, pulls down to
/// its tension, breaks by allowBreakage); elastic energy 1/2 kn u_n^2 + 1/2 Fs^2 / ks.
using KnKsPB = PartsLaw<KnKsPBNames, KnKsPhys<true>, parts::JointSpring<true>, parts::AreaDashpot,
                        parts::JointCoulomb<true>>;
/// The same without boundary blocks and rock joints, the shear capped with the damped F_n.
using KnKsPP = PartsLaw<KnKsPPNames, KnKsPhys<false>, parts::JointSpring<false>, parts::AreaDashpot,
                        parts::JointCoulomb<false>>;

TALUS_REGISTER_PARTS_LAW(KnKsPB)
TALUS_REGISTER_PARTS_LAW(KnKsPP)
} // namespace talus::dem
