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
using Vec3i = Eigen::Vector3i;

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
  /// Periodic networks: the real vertex this one is an image of (-1: not an image), shifted by
  /// `period` cells (pos = vertices[image].pos + period * cell size).
  int image = -1;
  Vec3i period = Vec3i::Zero();
  /// An alpha vertex (AlphaBoundary.h): a fictitious sphere over the alpha shape of the
  /// packing, after the real spheres (and not counted in nSpheres); its pores are outside.
  bool alpha = false;
};

/// A pore: a finite tetrahedron.
struct Pore
{
  std::array<int, 4> vertices{};   ///< indices into PoreNetwork::vertices
  std::array<int, 4> neighbours{}; ///< pore across the facet opposite vertex k; -1: infinite cell
  std::array<int, 4> throats{};    ///< throat across facet k; -1 when the neighbour is infinite
  /// Periodic networks: the neighbour across facet k is pore neighbours[k] shifted by this many
  /// cells (its pressure there is p + gradP . shift); zero otherwise.
  std::array<Vec3i, 4> neighbourPeriod{Vec3i::Zero(), Vec3i::Zero(), Vec3i::Zero(), Vec3i::Zero()};
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
  /// pores[1] as pores[0] sees it: shifted by this many periodic cells (zero if not periodic)
  Vec3i period = Vec3i::Zero();
  /// local index (0..3) in pores[1] of each facet vertex (`vertices`, given in pores[0]'s frame)
  std::array<int, 3> mirrorLocal{};
  double area = 0;               ///< facet area (walls: the projected quadrilateral, as Yade)
  double fluidArea = 0;          ///< facet area minus the sphere sectors cut by it
  double poreVolume = 0;         ///< void volume of the double pyramid (facet, both centres)
  double solidSurface = 0;       ///< solid (sphere and no-flux wall) surface in that region
  double hydraulicRadius = 0;    ///< poreVolume / solidSurface, with Yade's wall factors
  double length = 0;             ///< distance between the two pore centres
  double conductance = 0;
  int nFictitious = 0;
  // What the fluid forces need (Yade's facetSurfaces, facetSphereCrossSections, solidSurfaces):
  std::array<int, 3> vertices{};          ///< facet vertices (indices into PoreNetwork::vertices; order: setFacetVertices)
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
  /// Periodic networks (Yade's PeriodicFlowEngine): the spheres are wrapped into the cell
  /// [0, cellSize) and images of those near its faces are added as vertices after the spheres;
  /// pores are one per periodic pore. Boundaries absent (`hasBoundary` false) leave their
  /// axis periodic; an axis with a boundary is not wrapped nor duplicated.
  bool periodic = false;
  Vec3 cellSize = Vec3::Zero();
  std::array<bool, kBoundaries> hasBoundary{true, true, true, true, true, true};
  std::size_t nSpheres = 0;          ///< real spheres (vertices kBoundaries .. kBoundaries + nSpheres)
  /// The pore indices along a space-filling curve through their centres (CurveOrder.h), set
  /// with the triangulation: the order of the pressure solver's rows, local in memory where the
  /// pore ids (CGAL's cell order) are not.
  std::vector<int> curveOrder;
  std::vector<Vec3i> wrap;           ///< periodic: cells each sphere was moved by to enter the cell

  /// The real spheres' count (images of a periodic network left out).
  [[nodiscard]] std::size_t sphereCount() const { return nSpheres; }
  /// Periodic networks: axis a (0..2) is periodic when it has no boundary on either side.
  /// @param a the axis, 0..2
  /// @return whether it is periodic (always false for a non-periodic network)
  [[nodiscard]] bool periodicAxis(int a) const
  {
    return periodic && !hasBoundary[static_cast<std::size_t>(2 * a)] && !hasBoundary[static_cast<std::size_t>(2 * a + 1)];
  }
  /// The shift of `period` cells (zero vector for non-periodic networks).
  /// @param period whole cells along each axis
  /// @return the displacement (m)
  [[nodiscard]] Vec3 shift(const Vec3i& period) const { return cellSize.cwiseProduct(period.cast<double>()); }
};

/// How the spheres enter the CGAL triangulation. Both give the same pores (the regular
/// triangulation is unique unless points are degenerate); they differ in speed and in the order
/// of the vertices inside each cell, on which Yade's geometry depends (the weighted centres of
/// the pores touching a wall, see Sorted; the sphere-edge overlap S0 takes the first sphere it
/// finds crossing its opposite edge).
enum class InsertionOrder
{
  /// one range, spatially sorted by CGAL (faster from about 30 000 spheres, where inserting in
  /// the input's order misses the caches: docs/flow.md, "Measurements behind the code"); the
  /// cell and facet vertices are then taken in a canonical order (boundaries, then by body id),
  /// so the geometry depends neither on CGAL's order nor on the order of the input. It differs
  /// from Yade's where the weighted centres of the pores touching a wall carry the round-off of
  /// the fictitious spheres' huge weights, which depends on the order of the four vertices
  /// (throat lengths by percents where two such centres nearly coincide; the flux by 2.4e-6 at
  /// 10 000 spheres, 4.5e-4 at 200 000), and on facets where two spheres cross their opposite
  /// edges (Yade's S0)
  Sorted,
  /// one by one in the caller's order, each location started near the sphere, and the vertices
  /// in CGAL's cell order, as Yade's FlowEngine: the same cells with their vertices in the same
  /// order as Yade's, the same numbers to round-off
  Yade,
};

/// The box of a packing: Yade's boundaryUseMaxMin, the extremes of x-r .. x+r over the spheres.
/// @param spheres the packing's spheres
/// @return the six boundaries at the box's faces
std::array<Boundary, kBoundaries> boundingBoxBoundaries(const std::vector<PoreSphere>& spheres);

/// Triangulate `spheres` inside `boundaries` (the pores, their neighbours and centres; no
/// hydraulic geometry yet, see computeGeometry). With `concurrent`, InsertionOrder::Sorted, a
/// caller running more than one OpenMP thread and a build with TBB, CGAL inserts the spheres on
/// that many threads; the pores are then numbered in a canonical order (the same pores, numbered
/// alike from run to run; results differ from a one-thread run's by round-off only). Without it
/// the network is the same bits at any thread count.
/// @param spheres the spheres (positions and radii in m, with their body ids)
/// @param boundaries the six boundaries (walls or the packing's box)
/// @param order how the spheres enter CGAL (see InsertionOrder)
/// @param concurrent allow the concurrent insertion (above)
/// @return the network: vertices, pores, throats, the pores along each boundary
/// @throws std::invalid_argument fewer than 4 spheres, a non-finite position or radius, a
///         non-positive radius or a sphere centre outside the boundaries (naming the body id)
PoreNetwork triangulate(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries,
                        InsertionOrder order = InsertionOrder::Sorted, bool concurrent = false);

/// Periodic variant (Yade's PeriodicFlowEngine): `spheres` (any positions, wrapped here along
/// the periodic axes) in the orthorhombic cell [0, cellSize); images of the spheres closer than
/// radius + duplicateThreshold to a cell face are added so that the pores of the cell are complete;
/// boundary k is used only if `hasBoundary[k]` (its axis then is neither wrapped nor duplicated).
/// @param spheres, boundaries, order as triangulate's
/// @param hasBoundary which of the six boundaries exist
/// @param cellSize the cell's edges (m), each > 0
/// @param duplicateThreshold the distance (m) beyond its radius within which a sphere is imaged
///        across a cell face
/// @return the network, one pore per periodic pore
/// @throws std::invalid_argument on bad input (as triangulate, plus a non-positive cell size)
/// @throws std::runtime_error if a pore of the cell has a neighbour with no periodic counterpart
///         (duplicateThreshold too small for the packing)
PoreNetwork triangulatePeriodic(const std::vector<PoreSphere>& spheres, const std::array<Boundary, kBoundaries>& boundaries,
                                const std::array<bool, kBoundaries>& hasBoundary, const Vec3& cellSize,
                                double duplicateThreshold, InsertionOrder order = InsertionOrder::Sorted);

/// The pore containing point x (Yade's Tri.locate), -1 outside the triangulated region. In a
/// periodic network, `period` (if given) receives how many cells x is from that pore's frame.
/// `near` (if given): where the search starts, a cell from an earlier call or cellAtVertex (-1:
/// anywhere), and on return the cell x is in. From a cell near x the search walks a few cells
/// instead of across the triangulation.
/// @param net a triangulated network
/// @param x the point (m)
/// @param period receives the cells between x and the pore's frame, or null
/// @param near the search's start and, on return, x's cell; or null
/// @return the pore's index, or -1
int locatePore(const PoreNetwork& net, const Vec3& x, Vec3i* period = nullptr, int* near = nullptr);

/// A cell of the triangulation around vertex `vertex` (index into net.vertices), for locatePore's
/// `near`; -1 if there is none.
/// @param net a triangulated network
/// @param vertex an index into net.vertices
/// @return a cell index for locatePore's `near`, or -1
int cellAtVertex(const PoreNetwork& net, int vertex);
} // namespace talus::flow::pore
