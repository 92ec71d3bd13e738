#pragma once
// The alpha-shape boundary of a pore network (Yade's FlowEngine.alphaBound): instead of the box
// walls, the fluid domain is bounded by the alpha shape of the spheres (CGAL's Alpha_shape_3 of
// the weighted points, weights r^2, as the regular triangulation). As Yade, "alpha vertices"
// (spheres orthogonal to the packing's outer spheres) are added over the shape's boundary facets
// and triangulated with the packing; the pores they touch carry an imposed pressure
// (alphaBoundValue). Lets a packing of any outline (a sphere, a specimen with a free surface)
// drain to its surroundings.
#include "flow/pore/PoreNetwork.h"

#include <vector>

namespace talus::flow::pore
{
/// The alpha vertices of a packing and the alpha they were made with.
struct AlphaVertices
{
  double alpha = 0; ///< the alpha used (squared radius, m^2): the given one, or CGAL's optimal
  /// Over a boundary facet of the alpha shape whose outer side is unbounded: the sphere of
  /// squared radius alpha orthogonal to the facet's three spheres, on the outer side; over one
  /// whose outer side is a finite cell: that cell's orthogonal sphere (once per cell). Every
  /// boundary facet gets one (Yade: about half of them, see the .cpp). Ids -1, -2, ...
  std::vector<PoreSphere> vertices;
};

/// The alpha shape of `spheres` (CGAL's REGULARIZED mode, as Yade) and its alpha vertices
/// (Yade 2023.02a's with fixedAlpha false).
/// @param spheres the packing
/// @param alphaBound the alpha value (m^2, squared radius of the probe sphere) > 0, or 0 for
///        CGAL's smallest alpha giving one solid component containing every sphere
/// @return the alpha used and the alpha vertices
/// @throws std::invalid_argument for a negative or non-finite alphaBound
AlphaVertices alphaVertices(const std::vector<PoreSphere>& spheres, double alphaBound);

/// The pores and spheres of a network triangulated with alpha vertices (Vertex::alpha).
struct AlphaBoundary
{
  double alpha = 0; ///< the alpha used (m^2)
  /// per pore: 1 for a pore outside the packing (with an alpha or a box vertex)
  std::vector<char> exteriorPores;
  /// per vertex: 1 for a sphere of the packing in a pore with an alpha vertex
  std::vector<char> boundaryVertices;
};

/// @param net a network whose vertices after the spheres are alpha vertices
/// @param alpha the alpha they were made with
/// @return the exterior pores and the spheres on the boundary
AlphaBoundary alphaBoundary(const PoreNetwork& net, double alpha);
} // namespace talus::flow::pore

namespace talus::flow::pore
{
/// Triangulate `spheres` with their alpha vertices (after them, Vertex::alpha, not counted in
/// nSpheres) in a box around all of them (the box is no boundary: its pores are exterior).
/// @param spheres the packing
/// @param alphaBound as alphaVertices
/// @param boundary receives the exterior pores and the spheres on the shape
/// @return the network, triangulated in InsertionOrder::Yade (see the .cpp)
/// @throws std::invalid_argument as alphaVertices and triangulate
PoreNetwork triangulateAlphaShape(const std::vector<PoreSphere>& spheres, double alphaBound, AlphaBoundary& boundary);
} // namespace talus::flow::pore
