#pragma once
// The alpha-shape boundary of a pore network (Yade's FlowEngine.alphaBound): instead of the box
// walls, the fluid domain is the alpha shape of the spheres (CGAL's Alpha_shape_3 of the weighted
// points, weights r^2, as the regular triangulation), and the pores outside it carry an imposed
// pressure (alphaBoundValue). Lets a packing of any outline (a sphere, a specimen with a free
// surface) drain to its surroundings.
#include "flow/pore/PoreNetwork.h"

#include <vector>

namespace talus::flow::pore
{
struct AlphaBoundary
{
  double alpha = 0; ///< the alpha used (squared radius, m^2): the given one, or CGAL's optimal
  /// per pore: 1 when it lies outside the alpha shape (a box vertex, or a cell of the spheres'
  /// triangulation that is not INTERIOR to the alpha shape)
  std::vector<char> exteriorPores;
  /// per vertex of the network: 1 for a sphere on the alpha shape's boundary (a vertex of one
  /// of its boundary facets)
  std::vector<char> boundaryVertices;
};

/// The alpha shape of the network's spheres and the pores outside it.
/// @param net a box network (not periodic)
/// @param alphaBound the alpha value (m^2, squared radius of the probe sphere) > 0, or 0 for
///        CGAL's smallest alpha giving one solid component containing every sphere
/// @return the alpha used, the exterior pores and the boundary spheres
/// @throws std::invalid_argument for a periodic network or a negative or non-finite alphaBound
AlphaBoundary alphaBoundary(const PoreNetwork& net, double alphaBound);
} // namespace talus::flow::pore
