#pragma once
// How the forces of the phase pressures (Yade's TwoPhaseFlowEngine.computeCapillaryForce) share
// each facet's fluid area among its three vertices: by their solid lines in the facet (the arcs
// of the spheres inside the facet triangle; along a wall, the length of the facet's trace on it)
// rather than by their solid surfaces in the throat as FlowEngine does; the rest of the facet
// scheme is FlowEngine's (pore::unitForceVectors).
#include "flow/pore/PoreNetwork.h"

#include <array>
#include <vector>

namespace talus::flow::twophase
{
/// The share of each facet vertex in its solid line, per throat (zero for a facet of three walls).
/// @param net the network, its geometry computed
/// @return per throat (index as PoreNetwork::throats), the three vertices' shares, summing to 1
std::vector<std::array<double, 3>> solidLineShares(const pore::PoreNetwork& net);

} // namespace talus::flow::twophase
