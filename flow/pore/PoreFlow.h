#pragma once
// The pore-scale flow model (Yade's FlowEngine, PFV): builds the pore network of a sphere
// packing, its conductances and the pressure field for the six boundaries' conditions, and
// reports fluxes, pressures and the sample permeability. No DEM here: the caller passes the
// spheres (FlowCoupling.h connects it to a scene through the particle exchange interface).
#include "flow/pore/AlphaBoundary.h"
#include "flow/pore/PoreGeometry.h"
#include "flow/pore/PoreNetwork.h"
#include "flow/pore/solver/PressureSolver.h"
#include "flow/pore/SphereLubrication.h"

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace talus::flow::pore
{
/// FlowEngine's options, Yade's names and defaults.
struct FlowParameters : ConductanceParameters, ViscousParameters
{
  std::array<bool, kBoundaries> bndCondIsPressure{};
  std::array<double, kBoundaries> bndCondValue{};
  /// true: the boundary is the packing's extreme (x - r or x + r); false: `wallPosition`
  std::array<bool, kBoundaries> boundaryUseMaxMin{true, true, true, true, true, true};
  std::array<double, kBoundaries> wallPosition{};
  int useSolver = 3; ///< 0 Gauss-Seidel, 3 CHOLMOD (Yade's numbers); Talus: 4 multigrid, 5 BoomerAMG (SolverKind)
  double tolerance = 1e-6; ///< Gauss-Seidel relative change
  /// Talus: the multigrid solvers (useSolver 4, 5) stop at ||b - A p|| <= this ||b||. At 1e-8 the
  /// pressures stay within 1e-6 of CHOLMOD's largest and the boundary fluxes within 1e-7 of
  /// CHOLMOD's (tests/flow/pore/test_pore_multigrid.py), inside the 1e-6 to Yade's that the
  /// validation holds the permeability to; why not 1e-10: docs/flow.md.
  double multigridTolerance = 1e-8;
  double relax = 1.9;
  /// Bulk modulus of the fluid; 0: incompressible (Yade's fluidBulkModulus). With K_f > 0 each
  /// pore stores fluid, V_void / (K_f dt) (p - p_old) (V_void of the mesh, as Yade), and the
  /// solve is transient.
  double fluidBulkModulus = 0;
  /// Pressure of the pores of the first network, and of new pores no old one covers (Yade's
  /// pZero); it matters for a compressible fluid, and for an incompressible one where no
  /// pressure is imposed: it is then the mean pressure (see reference_).
  double pZero = 0;

  // --- periodic variant (Yade's PeriodicFlowEngine) ---
  bool periodic = false;
  /// edges of the orthorhombic periodic cell [0, cellSize)
  Vec3 cellSize = Vec3::Ones();
  /// images of the spheres within radius + this distance of a cell face enter the triangulation
  double duplicateThreshold = 0.06;
  /// macroscopic pressure gradient: the pressure is periodic plus gradP . x (Yade's gradP)
  Vec3 gradP = Vec3::Zero();
  /// which of the six boundaries exist (Yade: those with a wallIds entry); an axis with none is
  /// periodic. Ignored when not periodic (all six exist).
  std::array<bool, kBoundaries> hasBoundary{};
  /// Talus: insert the spheres one by one and keep CGAL's vertex order, as Yade (the same
  /// numbers as Yade to round-off); false: as one sorted range, the vertices in a canonical
  /// order (see InsertionOrder; faster from about 30 000 spheres, the wall pores' centres carry
  /// other round-off, so the permeability differs from Yade's by up to 5e-4 at 200 000 spheres)
  bool yadeInsertionOrder = true;
  /// Talus: with more than one OpenMP thread and TBB, insert the spheres of a box network
  /// concurrently (CGAL's Parallel_tag; needs yadeInsertionOrder false). Off by default: the pores are then numbered in another
  /// canonical order, so the results differ from a one-thread run's by round-off, and on two
  /// cores it is no faster; without it the results are the same bits at any thread count.
  bool concurrentTriangulation = false;

  // --- alpha-shape boundary (Yade's alphaBound, alphaBoundValue) ---
  /// < 0 (default -1): the box's boundaries; >= 0: the network is triangulated with alpha
  /// vertices over the alpha shape of the spheres (AlphaBoundary.h), the pores they touch take
  /// the pressure alphaBoundValue and the box's conditions are ignored; 0 lets CGAL choose the
  /// smallest alpha giving one solid (m^2). Read at the triangulation.
  double alphaBound = -1;
  double alphaBoundValue = 0;
};

/// A point inside the pore (its weighted circumcentre may lie outside the tetrahedron): the
/// centroid of its vertices, a boundary vertex standing for the projection of the real
/// vertices' centroid on that boundary plane (Yade's getCellBarycenter). NaN for a pore of
/// boundary vertices only.
/// @param net the network the pore belongs to
/// @return the point (m)
Vec3 interiorPoint(const PoreNetwork& net, const Pore& pore);

/// Force on each pore's four vertices per unit pressure in the pore (Yade's unitForceVectors):
/// the pressure on the sphere sectors cut by the pore's facets, on a wall facing a facet (its
/// projected area), and the facet's fluid area shared among the facet's three vertices by
/// `shares[throat]` (FlowEngine: their solid surfaces in the throat; TwoPhaseFlowEngine: their
/// solid lines in the facet).
/// @param net the network, its geometry computed
/// @param shares per throat, the fluid area's share of each facet vertex (summing to 1)
/// @return per pore, the force on each of its four vertices per unit pressure (m^2)
std::vector<std::array<Vec3, 4>> unitForceVectors(const PoreNetwork& net, const std::vector<std::array<double, 3>>& shares);

/// Pore-scale flow in a sphere packing (Yade's FlowEngine): the network of pores and throats,
/// the pressure solve and the fluid forces on the solids.
class PoreFlow
{
public:
  FlowParameters params;

  /// Triangulate the packing and compute geometry and conductances (drops the factor). The
  /// pressures of a previous network are carried over: each new pore takes the pressure of the
  /// old pore containing its centre (Yade's interpolate), so a transient solve continues.
  /// @param spheres the packing (positions and radii in m, body ids)
  /// @throws std::invalid_argument as triangulate (too few spheres, bad positions or radii)
  void build(const std::vector<PoreSphere>& spheres);
  /// Move the spheres (same order as in build) and the boundaries without remeshing, over the
  /// time step dt: pore volumes are recomputed and their rates of change dV/dt become the source
  /// of the next solve (fluid expelled from shrinking pores; Yade's updateVolumes).
  /// @param spherePositions one per sphere given to build (m)
  /// @param boundaryPositions the six boundaries' coordinates along their axes (m)
  /// @param dt the time since the last move (s), > 0
  /// @throws std::invalid_argument on a size mismatch, non-finite positions or dt <= 0
  /// @throws std::logic_error before the first build
  void moveVertices(const std::vector<Vec3>& spherePositions, const std::array<double, kBoundaries>& boundaryPositions,
                    double dt);
  // --- background remeshing (Yade's FlowEngine.multithread) ---
  /// A model with this one's parameters, imposed points and time step but no network: build it
  /// (build + prepareSolver) in another thread while this one keeps solving, then adopt it.
  [[nodiscard]] std::unique_ptr<PoreFlow> detachedCopy() const;
  /// Factorise the pressure system now if the next solve would re-use the factor (CHOLMOD,
  /// incompressible fluid), so that a background build also takes the factorisation off the
  /// stepping thread.
  void prepareSolver();
  /// Replace this model's network by `fresh` (a detachedCopy built since): pressures carried
  /// over from the current network as in build, the mesh's spheres and boundaries moved to the
  /// given current positions with no volume-change source for that motion (it happened while
  /// the old mesh gave the sources), this model's parameters, time step and imposed points kept
  /// (imposed pressure points moved since the copy are located again, refactorising).
  /// @param fresh the built copy, taken over
  /// @param spherePositions, boundaryPositions the current positions, as for moveVertices
  /// @throws std::logic_error if `fresh` is null
  /// @throws std::invalid_argument as moveVertices for the positions
  void adopt(std::unique_ptr<PoreFlow> fresh, const std::vector<Vec3>& spherePositions,
             const std::array<double, kBoundaries>& boundaryPositions);

  /// Recompute the void volumes if the spheres moved since (moveVertices skips them: the
  /// storage term uses the mesh's void volumes, as Yade).
  void updateVoidVolumes();
  /// Time step of the transient (compressible) solve when no motion was given.
  /// @param dt the step (s), > 0
  /// @throws std::invalid_argument for dt <= 0 (or not a number)
  void setTimeStep(double dt);
  /// Largest relative change of a pore volume since the last triangulation, |V - V_mesh| / |V_mesh|
  /// (infinite once a pore has turned inside out: the mesh is invalid).
  [[nodiscard]] double maxVolumetricStrain() const { return maxStrain_; }
  /// Pores whose volume changed sign since the triangulation (inverted tetrahedra).
  [[nodiscard]] int invertedPores() const { return inverted_; }
  /// Rate of volume change of each pore from the last moveVertices (Yade's dv()).
  [[nodiscard]] const std::vector<double>& volumeRates() const { return dv_; }
  /// Rates of change of the pores' fluid volume from other causes than the motion (thermal
  /// expansion of the fluid and of the particles: a positive rate draws fluid in, as a growing
  /// pore), one per pore, added to the motion's at every solve until replaced; a new network
  /// drops them (its pores are others).
  /// @param rates one rate per pore (m^3/s)
  /// @throws std::invalid_argument if not one finite value per pore of the current network (or
  ///         no network yet)
  void setExtraVolumeRates(std::vector<double> rates);
  /// The rates setExtraVolumeRates gave (empty: none).
  [[nodiscard]] const std::vector<double>& extraVolumeRates() const { return extraDv_; }
  /// The solver's work so far (analyses, factorisations, multigrid set-ups and their times).
  [[nodiscard]] const PressureSolver::Counters& solverCounters() const { return solver_.counters(); }
  /// Recompute conductances after a change of the parameters (same mesh; drops the factor).
  void updateConductances();
  /// Solve the pressures for the current boundary values (re-using the factor if the mesh and
  /// boundary types are unchanged).
  /// @throws std::logic_error before the first build
  /// @throws std::invalid_argument for useSolver not 0, 3, 4 or 5, a negative fluidBulkModulus, a
  ///         compressible fluid without a time step, or a closed network of incompressible fluid
  ///         whose volume sources do not sum to zero
  /// @throws std::runtime_error from the solver (a singular system, no convergence)
  void solve();

  /// Impose pressure p in the pore containing `pos` (Yade's imposePressure), re-located at each
  /// triangulation; overrides the boundary values.
  /// @param pos the point (m)
  /// @param p the pressure (Pa)
  /// @returns its index ("cond")
  /// @throws std::invalid_argument for a non-finite position or pressure; at the next solve, for
  ///         a point outside the network
  int imposePressure(const Vec3& pos, double p);
  /// Change the value of imposed point `cond` (keeps the factor).
  /// @param cond an index imposePressure returned
  /// @param p the new pressure (Pa)
  /// @throws std::out_of_range for an unknown index
  void setImposedPressure(int cond, double p);
  /// Forget every imposed pressure point (the boundaries' values apply again).
  void clearImposedPressure();
  /// Impose the flux q at the pore containing `pos`, a source term (Yade's imposeFlux: outflux
  /// positive, influx negative), located again after each triangulation.
  /// @param pos the point (m)
  /// @param q the flux (m^3/s)
  /// @returns its index
  /// @throws std::invalid_argument for a non-finite position or flux; at the next solve, for a
  ///         point outside the network
  int imposeFlux(const Vec3& pos, double q);
  /// Forget every imposed flux.
  void clearImposedFlux();
  /// Flux leaving the pore of imposed point `cond` into the network, sum k (p_cell - p_j)
  /// (Yade's getCellFlux; positive for injection).
  /// @param cond an index imposePressure returned
  /// @return the flux (m^3/s)
  /// @throws std::out_of_range for an unknown index or a point not located yet (solve first)
  [[nodiscard]] double getCellFlux(int cond) const;

  /// A network has been built.
  [[nodiscard]] bool built() const { return net_.has_value(); }
  /// @return the current network (owned here; replaced by the next build or adopt)
  /// @throws std::logic_error before the first build
  [[nodiscard]] const PoreNetwork& network() const;
  /// The pressure of each pore of the current network (Pa), from the last solve.
  [[nodiscard]] const std::vector<double>& pressures() const { return p_; }

  /// Yade's getBoundaryFlux: sum over the pores touching boundary k of the flux they receive,
  /// sum k_ij (p_j - p_i); negative where fluid enters. Meaningful on pressure boundaries (a
  /// no-flux boundary gives the flux crossing its first layer of pores, not zero).
  /// @param k the boundary, 0..5
  /// @return the flux (m^3/s)
  /// @throws std::out_of_range for k outside 0..5
  [[nodiscard]] double boundaryFlux(int k) const;
  /// Pressure of the pore containing x (Yade's getPorePressure); 0 outside.
  /// @param x a point (m)
  /// @return the pressure (Pa)
  [[nodiscard]] double porePressure(const Vec3& x) const;
  /// Darcy permeability of the sample between two opposite pressure boundaries along their
  /// axis: K = Q mu L / (A dP) with the flux Q through boundary `lo`, the sample length L and
  /// cross-section A from the box.
  /// @param lo, hi two opposite boundaries (2k and 2k + 1, either order)
  /// @return K (m^2)
  /// @throws std::invalid_argument if they are not opposite pressure boundaries of different
  ///         pressures
  [[nodiscard]] double samplePermeability(int lo, int hi) const;
  /// Periodic networks: Darcy permeability along the imposed gradient, K = -mu (v . g) / |g|^2
  /// with v the volume-averaged Darcy velocity.
  /// @return K (m^2)
  /// @throws std::logic_error if the network is not periodic
  /// @throws std::invalid_argument if gradP is zero
  [[nodiscard]] double periodicPermeability() const;
  /// Periodic networks: the pressure drop g . shift across `period` cells (0 otherwise).
  /// @param period whole cells along each axis
  /// @return the drop (Pa)
  [[nodiscard]] double pressureJump(const Vec3i& period) const;
  /// Darcy velocity of each pore: sum over its facets of the outgoing flux times the facet
  /// position relative to the pore centre, over the pore volume (the terms of averageVelocity).
  [[nodiscard]] std::vector<Vec3> poreVelocities() const;
  /// Volume-averaged Darcy velocity over all pores (Yade's averageVelocity).
  [[nodiscard]] Vec3 averageVelocity() const;
  /// The reference conductance of the clamping (Yade's globalK), from the last computation.
  [[nodiscard]] double globalConductance() const { return globalK_; }
  /// Fluid force on each vertex of the network (index as PoreNetwork::vertices: 0..5 the
  /// boundaries, then the spheres), Yade's computeFacetForcesWithCache: for each pore and throat,
  /// the pressure on the sphere sectors cut by the facet (pressure part) plus the pressure drop
  /// on the fluid area shared among the solids by their surface in the throat (viscous part).
  [[nodiscard]] std::vector<Vec3> vertexForces() const;
  /// The viscous forces between neighbouring spheres (params.viscousShear, shearLubrication,
  /// normalLubrication) for the spheres' velocities and angular velocities (same order as in
  /// build) over the step dt; the sphere pairs are found at the first call after a build.
  /// @param velocities, angularVelocities one per sphere (m/s, rad/s)
  /// @param dt the step (s)
  /// @throws std::invalid_argument see SphereLubrication::compute, or if no option is set
  void computeViscousForces(const std::vector<Vec3>& velocities, const std::vector<Vec3>& angularVelocities, double dt);
  /// The pairs and the forces of the last computeViscousForces.
  [[nodiscard]] const SphereLubrication& lubrication() const { return lubrication_; }
  /// Iterations of the last solve (Gauss-Seidel sweeps, conjugate-gradient iterations; 1 for
  /// CHOLMOD).
  [[nodiscard]] int lastIterations() const { return solver_.lastIterations(); }
  /// The solver holds a CHOLMOD factor of the current matrix.
  [[nodiscard]] bool factorized() const { return solver_.factorized(); }
  /// The alpha-shape boundary of the current network (empty vectors when alphaBound < 0).
  [[nodiscard]] const AlphaBoundary& alphaShape() const { return alpha_; }

private:
  std::array<Boundary, kBoundaries> boundaries(const std::vector<PoreSphere>& spheres) const;
  /// The pressures of the current network carried to the pores of `fresh` (pZero where none).
  [[nodiscard]] std::vector<double> carriedPressures(const PoreNetwork& fresh) const;
  /// Move the network's spheres and boundaries (checked first), recompute the pore volumes,
  /// the strain since the mesh and the inverted pores; no volume-change source.
  void placeVertices(const std::vector<Vec3>& spherePositions, const std::array<double, kBoundaries>& boundaryPositions);
  /// Geometry, conductances and force vectors of the network (not the linear system).
  void computeHydraulics();
  void applyBoundaryTypes();
  void computeUnitForces();

  /// Net flux leaving pore i through its facet f, k (p_i - p_j - jump).
  [[nodiscard]] double facetFlux(std::size_t i, int f) const;
  /// The storage term V_void / (K_f dt) per pore (empty when incompressible).
  std::vector<double> storage() const;
  /// A closed network (reference_): the sources must sum to zero.
  /// @throws std::invalid_argument naming what to set when they do not
  void checkClosedBalance(const std::vector<double>& source) const;

  std::optional<PoreNetwork> net_;
  std::vector<char> imposed_;
  std::vector<double> p_;
  std::vector<double> dv_;        ///< dV/dt per pore since the last moveVertices (0 after a build)
  std::vector<double> extraDv_;   ///< setExtraVolumeRates (empty: none)
  std::vector<double> meshVolume_; ///< pore volumes at the triangulation
  std::vector<double> meshVoidVolume_; ///< void volumes at the triangulation (storage term)
  double maxStrain_ = 0;
  int inverted_ = 0;
  double dt_ = 0;
  bool storageInMatrix_ = false;  ///< the factor includes a storage term
  bool voidsStale_ = false;       ///< spheres moved, void volumes not recomputed
  /// force on the pore's vertex k per unit pressure in the pore (Yade's unitForceVectors)
  std::vector<std::array<Vec3, 4>> unitForces_;
  std::array<bool, kBoundaries> builtTypes_{};
  struct PointPressure
  {
    Vec3 pos;
    double value;
    int pore; ///< -1 until located in the current network
  };
  std::vector<PointPressure> points_;
  std::vector<PointPressure> fluxPoints_; ///< value: the imposed outflux
  bool pointsChanged_ = false;
  /// With nothing imposed and an incompressible fluid the system is singular (the pressure is
  /// known up to a constant, and exists only if the sources sum to zero): pore 0 is held at 0
  /// for the solve, then the field is shifted so that its volume-weighted mean (of the periodic
  /// part p - gradP . x on a periodic network) is pZero. Zero sources on a bounded network: all
  /// pores at pZero, no solve.
  bool reference_ = false;
  PressureSolver solver_;
  double globalK_ = 0;
  SphereLubrication lubrication_;
  bool lubricationMeshed_ = false; ///< lubrication_ has the pairs of the current network
  AlphaBoundary alpha_;
  double alphaBuilt_ = -1; ///< the alphaBound alpha_ and the system were set for
};
} // namespace talus::flow::pore
