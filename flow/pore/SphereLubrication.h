#pragma once
// Viscous forces between neighbouring spheres of the pore network, from their relative
// velocities (Yade's FlowEngine options viscousShear, shearLubrication, normalLubrication). The
// neighbours are the pairs of spheres joined by an edge of the regular triangulation; the fluid
// between them is sheared over the face of the power diagram dual to that edge (the polygon of
// the weighted circumcentres of the pores around the edge). These forces come on top of the
// pressure forces (PoreFlow::vertexForces), which do not depend on the particle velocities.
#include "flow/pore/PoreNetwork.h"

#include <vector>

namespace talus::flow::pore
{
/// Yade's FlowEngine options for these forces (same names and defaults).
struct ViscousParameters
{
  /// tangential force mu * dv_t / R_h * A on each pair: dv_t the tangential relative velocity of
  /// the two surfaces, R_h = gap + 0.45 min(r1, r2), A the power-diagram face of the pair
  bool viscousShear = false;
  /// tangential lubrication force (pi mu / 2) (-2 R + L ln(L / h)) dv_t instead (wins over
  /// viscousShear); R mean radius, L distance between centres, h = max(gap, 0) + 2 eps R
  bool shearLubrication = false;
  /// normal lubrication force 3 pi R^2 mu dv_n / (2 h), in series with a spring of stiffness
  /// `stiffness` * R when stiffness > 0 (a visco-elastic gap, the force a state of each pair)
  bool normalLubrication = false;
  /// roughness: the smallest gap, as a fraction of the mean radius (h above)
  double eps = 1e-5;
  /// normal lubrication: contact stiffness per unit radius in series with the fluid (<= 0: none)
  double stiffness = 10000;

  /// Some viscous force between spheres is asked for (else nothing is computed).
  [[nodiscard]] bool any() const { return viscousShear || shearLubrication || normalLubrication; }
};

/// Two spheres joined by an edge of the triangulation.
struct SpherePair
{
  int a = 0, b = 0;          ///< vertex indices (kBoundaries + sphere index)
  double faceArea = 0;       ///< power-diagram face between them, at the mesh (Yade's edgeSurfaces)
  double normalForce = 0;    ///< last normal lubrication force: the spring's state
};

/// The viscous forces between neighbouring spheres (Yade's viscousShear, shearLubrication,
/// normalLubrication of FlowEngine), over the sphere pairs of the pore network.
class SphereLubrication
{
public:
  /// Find the sphere pairs of `net` and their face areas. The normal lubrication force of a pair
  /// of the previous network (same two body ids) is carried over: the spring keeps its load
  /// across a remesh, as in Yade.
  /// @param net the new network (its sphere pairs and their face areas are copied)
  /// @throws std::invalid_argument for a periodic network (not supported)
  void setNetwork(const PoreNetwork& net);

  /// The forces for the spheres' velocities and angular velocities (index as the network's
  /// spheres) at their current positions (the network's vertices); dt is the step over which the
  /// normal lubrication spring relaxes.
  /// @param net the network given to setNetwork, its vertices at the current positions
  /// @param params which forces, roughness and spring stiffness
  /// @param viscosity the fluid's dynamic viscosity (Pa s)
  /// @param velocities, angularVelocities one per network sphere (m/s, rad/s)
  /// @param dt the time step (s)
  /// @throws std::invalid_argument on a size mismatch, non-finite velocities, or a normal
  ///         lubrication spring with dt <= 0
  void compute(const PoreNetwork& net, const ViscousParameters& params, double viscosity,
               const std::vector<Vec3>& velocities, const std::vector<Vec3>& angularVelocities, double dt);

  /// The sphere pairs of the current network, with their lubrication springs' state.
  [[nodiscard]] const std::vector<SpherePair>& pairs() const { return pairs_; }
  /// Per sphere of the network, from the last compute (Yade's shearLubForce, shearLubTorque,
  /// normalLubForce): tangential force (viscous shear or lubrication), its torque, normal force.
  [[nodiscard]] const std::vector<Vec3>& shearForces() const { return shearForce_; }
  [[nodiscard]] const std::vector<Vec3>& shearTorques() const { return shearTorque_; }
  [[nodiscard]] const std::vector<Vec3>& normalForces() const { return normalForce_; }

private:
  std::vector<SpherePair> pairs_;
  std::vector<std::array<std::int64_t, 2>> pairIds_; ///< body ids of each pair (smaller first), for the carry-over
  std::vector<Vec3> shearForce_, shearTorque_, normalForce_;
};
} // namespace talus::flow::pore
