#pragma once
// The linear system of the pore pressures: for each pore i whose pressure is not imposed,
//   sum_j k_ij (p_i - p_j) = q_i
// over its finite neighbours j (k_ij: throat conductance, q_i: imposed source). Symmetric positive
// definite as soon as every connected group of unknown pores touches an imposed pressure.
// Four solvers: CHOLMOD Cholesky (simplicial for small systems, supernodal above; the factor is
// kept until the matrix changes, ordered by nested dissection on the pore centres), conjugate
// gradients preconditioned by algebraic multigrid, Talus's aggregation one or hypre's classical
// BoomerAMG (for systems whose factor costs more than the solves it would serve: large networks
// remeshed often, or too large for a factor to fit in memory) and Gauss-Seidel with
// over-relaxation (Yade's useSolver=0) for comparison.
#include "flow/pore/solver/BoomerAmg.h"
#include "flow/pore/solver/FactorMemory.h"
#include "flow/pore/solver/Multigrid.h"
#include "flow/pore/PoreNetwork.h"

#include <memory>
#include <vector>

namespace talus::flow::pore
{
enum class SolverKind
{
  GaussSeidel = 0, ///< Yade's useSolver=0
  Cholmod = 3,     ///< Yade's useSolver=3
  /// Talus: conjugate gradients preconditioned by algebraic multigrid (Multigrid.h), from the
  /// last pressures, to a relative residual of PressureSolver::multigridTolerance. No factor:
  /// a new matrix costs a cheap set-up, every solve some tens of cycles.
  Multigrid = 4,
  /// Talus: conjugate gradients preconditioned by hypre's BoomerAMG (BoomerAmg.h, classical
  /// algebraic multigrid), from the last pressures, to the same relative residual; when Talus
  /// was built with hypre (BoomerAmg::available()).
  BoomerAmg = 5,
};


/// The pressure system of a pore network, sum_j k_ij (p_j - p_i) = q_i over the pores of
/// unknown pressure, and its solution by one of SolverKind.
class PressureSolver
{
public:
  /// An empty solver: setSystem gives it its matrix.
  PressureSolver();
  ~PressureSolver();
  PressureSolver(const PressureSolver&) = delete;
  PressureSolver& operator=(const PressureSolver&) = delete;
  PressureSolver(PressureSolver&&) noexcept;
  PressureSolver& operator=(PressureSolver&&) noexcept;

  /// Set the matrix from the network's conductances; `imposed[i]` marks pores of known pressure;
  /// `diagonal[i]` (may be empty) is added to pore i's diagonal (the storage term of a
  /// compressible fluid). Drops the numeric factor; the symbolic analysis (fill-reducing ordering
  /// and supernodes, CHOLMOD's dominant cost) is kept when the sparsity pattern is unchanged.
  /// @param net the network, its throats' conductances computed (m^3/(Pa s))
  /// @param imposed one flag per pore: its pressure is known
  /// @param diagonal empty, or one storage term per pore (m^3/Pa per step)
  /// @throws std::invalid_argument when no pressure is imposed anywhere, or `imposed` or
  ///         `diagonal` do not have one entry per pore
  void setSystem(const PoreNetwork& net, const std::vector<char>& imposed, const std::vector<double>& diagonal = {});

  /// Solve for the unknown pressures; `p` holds the imposed values on entry (and the initial
  /// guess for Gauss-Seidel), the full field on exit. `source[i]` is q_i (may be empty).
  /// @param kind the method (Gauss-Seidel, CHOLMOD or multigrid)
  /// @param p one pressure per pore (Pa): imposed values in, the field out
  /// @param source empty, or one volume rate per pore (m^3/s)
  /// @throws std::runtime_error on a singular system (a group of pores with no imposed pressure),
  ///         a CHOLMOD failure, or when Gauss-Seidel diverges or does not converge
  /// @throws std::invalid_argument if `p` has not one entry per pore
  void solve(SolverKind kind, std::vector<double>& p, const std::vector<double>& source = {});

  /// CHOLMOD's factor is simplicial below this many unknowns, supernodal from it (the default
  /// from measurements, see PressureSolver.cpp; tests set it to compare both kinds). Read at the
  /// symbolic analysis.
  int supernodalFrom = 2500;
  double tolerance = 1e-7; ///< Gauss-Seidel: relative change of the pressure field
  /// Multigrid and BoomerAMG: ||b - A p|| <= multigridTolerance ||b|| (FlowParameters's)
  double multigridTolerance = 1e-8;
  double relax = 1.9;      ///< Gauss-Seidel over-relaxation (Yade's relax)
  int maxIterations = 100000;

  /// Factorise now (CHOLMOD) or build the multigrid hierarchy instead of at the next solve;
  /// nothing for Gauss-Seidel.
  /// @param kind the method the next solves use
  /// @throws std::runtime_error for a singular system or a CHOLMOD failure
  void prepare(SolverKind kind);
  [[nodiscard]] bool factorized() const;
  /// How many symbolic analyses and numeric factorisations CHOLMOD has done, and their times.
  struct Counters
  {
    int analyses = 0;
    int factorizations = 0;
    double analyseSeconds = 0;
    double factorizeSeconds = 0;
    int multigridSetups = 0;     ///< multigrid or BoomerAMG hierarchies built
    int multigridIterations = 0; ///< conjugate-gradient iterations over all multigrid solves
    double multigridSeconds = 0; ///< set-ups and solves
  };
  /// The work done so far (this solver's and what addCounters added).
  [[nodiscard]] const Counters& counters() const { return counters_; }
  /// Add the work of an earlier solver to the counters (a model that replaced its network).
  /// @param earlier the replaced solver's counters
  void addCounters(const Counters& earlier);
  [[nodiscard]] int lastIterations() const { return iterations_; }
  [[nodiscard]] std::size_t unknowns() const { return rowOfPore_.empty() ? 0 : static_cast<std::size_t>(nUnknown_); }

private:
  struct Cholmod;
  void factorize();
  /// The matrix of the unknown rows with both triangles (the multigrid's input).
  [[nodiscard]] SparseRows fullRows() const;

  /// keeps the large blocks of a freed factor for the next one while this solver exists
  FactorMemory::User memoryUser_;
  std::vector<int> rowOfPore_;  ///< -1 for imposed pores
  std::vector<int> poreOfRow_;
  std::vector<Vec3> centreOfRow_; ///< pore centres, for the fill-reducing ordering
  int nUnknown_ = 0;
  // Matrix in compressed rows: diagonal, then (column pore, conductance) couplings of each row
  // to all its finite neighbours (imposed or not).
  std::vector<double> diag_;
  std::vector<int> start_;
  std::vector<int> neighbour_;
  std::vector<double> k_;
  std::unique_ptr<Cholmod> cholmod_;
  bool numeric_ = false; ///< the factor holds the current matrix's values
  /// Right-hand side of the last CHOLMOD solve with the current factor (empty: none): the same
  /// one again has the same solution, still in the solver's x (a static packing's every step).
  std::vector<double> solvedRhs_;
  std::unique_ptr<Multigrid> multigrid_; ///< the current matrix's hierarchy (null: not built)
  std::unique_ptr<BoomerAmg> boomerAmg_; ///< the same with hypre's BoomerAMG
  int iterations_ = 0;
  Counters counters_;
};
} // namespace talus::flow::pore
