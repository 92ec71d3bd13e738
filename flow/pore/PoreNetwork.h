#pragma once
// The pore network of a sphere packing in a box (Yade's FlowEngine "PFV" discretisation, Chareyre
// et al. 2012): the regular (weighted Delaunay) triangulation of the spheres with weights r^2,
// the six sides of the box entering as huge fictitious spheres. Pores are the finite tetrahedra,
// throats the facets between two finite tetrahedra. Plain data, no CGAL: the triangulation lives
// in PoreNetwork.cpp only, so that including this header stays cheap.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace talus::flow::pore
{
using Vec3 = Eigen::Vector3d;

/// A sphere of the packing; `id` is the caller's body id, used in messages and results.
struct PoreSphere
{
  Vec3 pos = Vec3::Zero();
  double radius = 0;
  std::int64_t id = 0;
};

/// The six boundaries in Yade's order (FlowEngine.xmin .. zmax): xmin, xmax, ymin, ymax, zmin, zmax.
constexpr int kBoundaries = 6;

/// One side of the box: an axis-aligned plane with its inward normal and flow condition.
struct Boundary
{
  int coordinate = 0;              ///< 0, 1, 2 for x, y, z
  double position = 0;             ///< plane coordinate
  Vec3 normal = Vec3::UnitX();     ///< pointing into the sample
  bool imposedPressure = false;    ///< false: no flux (Yade's flowCondition=1)
  double value = 0;                ///< imposed pressure
};

/// A vertex of the triangulation: index 0..5 are the boundaries (fictitious spheres), 6+i is
/// sphere i of the input list (as Yade numbers walls 0..5 and spheres after them).
struct Vertex
{
  Vec3 pos = Vec3::Zero();
  double radius = 0;
  bool fictitious = false;
  std::int64_t id = -1; ///< body id of a sphere, boundary index for a fictitious vertex
};

/// A pore: a finite tetrahedron.
struct Pore
{
  std::array<int, 4> vertices{};   ///< indices into PoreNetwork::vertices
  std::array<int, 4> neighbours{}; ///< pore across the facet opposite vertex k; -1: infinite cell
  std::array<int, 4> throats{};    ///< throat across facet k; -1 when the neighbour is infinite
  Vec3 centre = Vec3::Zero();      ///< weighted circumcentre (vertex of the power diagram)
  double volume = 0;               ///< Yade's cell volume (tetrahedron; cut at the walls)
  double voidVolume = 0;           ///< volume minus the sphere sectors inside it
  int nFictitious = 0;             ///< how many vertices are boundaries
};

/// A throat: the facet shared by two finite pores, with its hydraulic geometry.
struct Throat
{
  std::array<int, 2> pores{};    ///< pores[0] sees this facet as facet `facet` (opposite vertex)
  int facet = 0;
  double area = 0;               ///< facet area (walls: the projected quadrilateral, as Yade)
  double fluidArea = 0;          ///< facet area minus the sphere sectors cut by it
  double poreVolume = 0;         ///< void volume of the double pyramid (facet, both centres)
  double solidSurface = 0;       ///< solid (sphere and no-flux wall) surface in that region
  double hydraulicRadius = 0;    ///< poreVolume / solidSurface, with Yade's wall factors
  double length = 0;             ///< distance between the two pore centres
  double conductance = 0;
  int nFictitious = 0;
  // What the fluid forces need (Yade's facetSurfaces, facetSphereCrossSections, solidSurfaces):
  std::array<int, 3> vertices{};          ///< facet vertices (indices into PoreNetwork::vertices)
  Vec3 facetVector = Vec3::Zero();        ///< area vector, pointing from pores[1] to pores[0]
  std::array<double, 3> crossSections{};  ///< sphere sector areas in the facet (0 for walls)
  std::array<double, 3> solidSurfaces{};  ///< each vertex's share of solidSurface
};

struct Triangulation; // the CGAL triangulation, kept for point location (PoreNetwork.cpp)

/// The triangulated packing.
struct PoreNetwork
{
  std::shared_ptr<const Triangulation> triangulation;
  std::vector<Vertex> vertices; ///< 6 boundaries then the spheres
  std::vector<Pore> pores;
  std::vector<Throat> throats;
  std::array<Boundary, kBoundaries> boundaries{};
  std::vector<std::int64_t> hiddenSpheres; ///< body ids the regular triangulation dropped
  /// pores incident to each boundary vertex (Yade's boundingCells)
  std::array<std::vector<int>, kBoundaries> boundaryPores{};

  [[nodiscard]] std::size_t sphereCount() const { return vertices.size() - kBoundaries; }
};

/// The box of a packing: Yade's boundaryUseMaxMin, the extremes of x-r .. x+r over the spheres.
std::array<Boundary, kBoundaries> boundingBoxBoundaries(const std::vector<PoreSphere>& spheres);

/// Triangulate `spheres` inside `boundaries` (the pores, their neighbours and centres; no
/// hydraulic geometry yet, see computeGeometry).
/// @throws std::invalid_argument fewer than 4 spheres, a non-finite position or radius, a
///         non-positive radius or a sphere centre outside the boundaries (naming the body id)
PoreNetwork triangulate(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries);

/// The pore containing point x (Yade's Tri.locate), -1 outside the triangulated region.
int locatePore(const PoreNetwork& net, const Vec3& x);
} // namespace talus::flow::pore
