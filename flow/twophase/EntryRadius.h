#pragma once
// The capillary geometry of the pore network for quasi-static two-phase flow (Yade's
// TwoPhaseFlowEngine): the entry radius of each throat, whose entry capillary pressure is
// surfaceTension / radius, and the radius of the sphere inscribed in each pore body. The
// formulas are Yade's, so that invasion sequences can be compared with Yade's pore by pore.
#include "flow/pore/PoreNetwork.h"

#include <vector>

namespace talus::flow::twophase
{
using pore::Vec3;

/// Yade's TwoPhaseFlowEngine.entryPressureMethod (same numbers).
enum class EntryPressureMethod
{
  /// Mayer-Stowe-Princen (Yuan & Chareyre 2017): the meniscus radius at which the capillary force
  /// on the non-wetting front (interface length) balances its pressure (void area / radius) in
  /// the throat's plane; throats touching a boundary use the inscribed circle
  MSP = 1,
  /// the circle inscribed between the three spheres of the throat
  Inscribed = 2,
  /// the circle of the throat's fluid area
  EquivalentArea = 3,
};

/// The method of Yade's number.
/// @param number 1, 2 or 3 (Yade's entryPressureMethod)
/// @return the method
/// @throws std::invalid_argument naming entryPressureMethod for another number
EntryPressureMethod entryPressureMethod(int number);

/// Radius of the circle tangent to the three circles the spheres cut in the plane of their
/// centres (Yade's computeEffectiveRadiusByPosRadius; NaN when there is none).
/// @param a, ra, b, rb, c, rc the spheres' centres and radii (m)
/// @return the radius (m), or NaN
double inscribedRadius(const Vec3& a, double ra, const Vec3& b, double rb, const Vec3& c, double rc);

/// The MS-P entry radius of the throat between three spheres: the root of the force balance
/// between the smallest gap and the inscribed radius, by bisection to 1e-6 of the inscribed
/// radius (Yade's computeMSPRcByPosRadius).
/// @param a, ra, b, rb, c, rc the spheres' centres and radii (m)
/// @return the entry radius (m)
double mspRadius(const Vec3& a, double ra, const Vec3& b, double rb, const Vec3& c, double rc);

/// The entry radius of every throat (index as PoreNetwork::throats). MSP on a throat with a
/// boundary vertex takes the inscribed radius. `invadeBoundary` false (Yade's isInvadeBoundary,
/// MS-P only, as Yade): throats between two boundary pores get -1, closed to invasion.
/// @param net the network, its geometry computed
/// @param method how each radius is computed
/// @param invadeBoundary whether throats between two boundary pores may be invaded
/// @return one radius per throat (m; -1: closed)
std::vector<double> throatEntryRadii(const pore::PoreNetwork& net, EntryPressureMethod method, bool invadeBoundary);

/// Radius of the sphere inscribed between the four spheres of each pore (Yade's
/// computePoreBodyRadius, Mackay et al. 1972): the largest multiple of min(r)/50 (from twice
/// that) at which the sign of the tangency determinant has not changed yet, the walls entering
/// as their fictitious spheres.
/// @param net the network
/// @return one radius per pore (m)
std::vector<double> poreBodyRadii(const pore::PoreNetwork& net);
} // namespace talus::flow::twophase
