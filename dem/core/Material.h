#pragma once

#include <limits>
#include <string>

namespace talus::dem
{
/// Material families, named as in Yade.
enum class MaterialKind
{
  Frict,   ///< FrictMat: elastic-frictional (young, poisson, frictionAngle, density)
  ViscEl,  ///< ViscElMat: linear visco-elastic, from (tc, en, et), (kn, cn, ks, cs) or (young, poisson, en)
  CohFrict, ///< CohFrictMat: FrictMat with cohesive bonds and rolling/twisting resistance
};

/// A material: the per-body parameters contact laws combine into per-contact stiffnesses.
///
/// FrictMat defaults are Yade's: young 1e7 Pa, poisson 0.3, frictionAngle 0.5 rad,
/// density 1000 kg/m^3.
struct Material
{
  MaterialKind kind = MaterialKind::Frict;
  std::string label;
  double density = 1000.0;
  double young = 1e7;
  double poisson = 0.3;
  double frictionAngle = 0.5;
  // ViscElMat: contact duration and restitution coefficients (normal, tangential), or
  // directly the stiffnesses and damping coefficients. NaN means "not given".
  double tc = std::numeric_limits<double>::quiet_NaN();
  double en = std::numeric_limits<double>::quiet_NaN();
  double et = std::numeric_limits<double>::quiet_NaN();
  double kn = std::numeric_limits<double>::quiet_NaN();
  double cn = std::numeric_limits<double>::quiet_NaN();
  double ks = std::numeric_limits<double>::quiet_NaN();
  double cs = std::numeric_limits<double>::quiet_NaN();
  // ViscElMat: rolling resistance (Yade's mR: a moment mR |Fn| times the relative angular
  // velocity, mRtype 1; mRtype 2 also times the relative velocity of the surfaces), and the
  // lubrication of the young/en form (the restitution of a contact lowered by the Stokes number
  // of its approach: fluid viscosity viscoDyn, surface roughness roughnessScale).
  double mR = 0;
  int mRtype = 1;
  bool lubrication = false;
  double viscoDyn = 1e-3, roughnessScale = 1e-3;
  // CohFrictMat (Yade's defaults): bond strengths as stresses (Pa, times the smaller radius
  // squared gives the bond's forces; negative: no bond strength), rolling and twisting
  // stiffnesses relative to ks r1 r2 (alphaKr, alphaKtw), plastic rolling/twisting moments per
  // unit normal force relative to the radius (etaRoll, etaTwist; negative: no limit).
  double normalCohesion = -1, shearCohesion = -1;
  double alphaKr = 2, alphaKtw = 2, etaRoll = -1, etaTwist = -1;
  bool isCohesive = true;         ///< bonds can be created between two such materials
  bool momentRotationLaw = false; ///< contacts transmit rolling and twisting moments
  bool fragile = true;            ///< a bond breaks for good at its first failure

  /// @throws std::invalid_argument naming the material and the parameter that is out of range
  void validate() const;
};
} // namespace talus::dem
