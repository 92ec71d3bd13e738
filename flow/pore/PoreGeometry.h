#pragma once
// Hydraulic geometry of the pore network and throat conductances, with Yade's FlowEngine
// formulas (CGT::Network and FlowBoundingSphere::computePermeability), so that results can be
// compared with Yade throat by throat. Depends on the boundary flow conditions: no-flux walls
// count as solid surface in the hydraulic radius, pressure boundaries do not.
#include "flow/pore/PoreNetwork.h"

namespace talus::flow::pore
{
/// Yade's FlowEngine options that enter the conductances (same names and defaults).
struct ConductanceParameters
{
  double permeabilityFactor = 1.0; ///< > 0: scales Poiseuille; < 0: -value * area / length (Darcy)
  double viscosity = 1.0;
  bool clampKValues = true;
  double minKdivKmean = 1e-4;
  double maxKdivKmean = 100.0;
  bool slipBoundary = true;        ///< no-flux walls not counted as solid surface (Yade: true)
};

/// Solid angle of the triangle (a, b, c) seen from `s` (Van Oosterom & Strackee; as Yade, the
/// absolute value of 2 atan(ratio), i.e. correct below 2 pi steradians / 2).
/// @param s the viewpoint
/// @param a, b, c the triangle's vertices
/// @return the solid angle (sr), >= 0
double solidAngle(const Vec3& s, const Vec3& a, const Vec3& b, const Vec3& c);

/// Pore volumes, void volumes and the throat geometry (areas, fluid areas, hydraulic radii,
/// lengths). Needs net.boundaries' flow conditions.
/// @param net the triangulated network, its pores and throats written
/// @param slipBoundary no-flux walls not counted as solid surface
void computeGeometry(PoreNetwork& net, bool slipBoundary);

/// Pore volumes (and void volumes if `voids`: the sphere sectors' solid angles are most of the
/// cost) from the current vertex and boundary positions, the mesh being kept between remeshes
/// while the spheres move (Yade's updateVolumes).
/// @param net the network, its pore volumes written
/// @param voids update the void volumes too
void updatePoreVolumes(PoreNetwork& net, bool voids);

/// Throat conductances k = permeabilityFactor * A_f * (2 R_h)^2 / (8 mu L), clamped as Yade does.
/// @param net the network, its throats' conductances written
/// @param params Yade's FlowEngine options that enter them
/// @param outside per pore, 1 for a pore outside the packing (the alpha shape's exterior; empty:
///        none): a throat between two such pores gets conductance 0 and stays out of the means
///        (both pores are imposed; Yade computes no conductance there)
/// @return the reference value the clamping used (Yade's "globalK")
/// @throws std::invalid_argument if the viscosity is not positive or permeabilityFactor is 0
double computeConductances(PoreNetwork& net, const ConductanceParameters& params, const std::vector<char>& outside = {});
} // namespace talus::flow::pore
