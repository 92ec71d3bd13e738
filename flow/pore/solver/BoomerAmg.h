#pragma once
// Conjugate gradients preconditioned by hypre's BoomerAMG, a classical (Ruge-Stueben type)
// algebraic multigrid, for the pore pressure system (useSolver=5). Its coarse grids keep the
// strongly coupled pores and interpolate the others from them, which follows the conductances'
// six decades where aggregates do not: on the bench networks its conjugate gradients converge
// about four times as fast per iteration as Multigrid.h's (a residual divided by 5 an iteration
// instead of by 1.8), so the set-up and two solves cost less than a CHOLMOD factorisation from
// some tens of thousands of pores (docs/flow.md, "Remeshing large packings").
//
// hypre is built on MPI: the first solver initialises MPI (one process, MPI_COMM_SELF) when the
// program has not, and finalises it at exit.
#include "flow/pore/solver/Multigrid.h"

#include <memory>
#include <vector>

namespace talus::flow::pore
{
/// hypre's BoomerAMG as the preconditioner of conjugate gradients, built once per matrix.
class BoomerAmg
{
public:
  /// Talus was built with hypre (otherwise the constructor refuses).
  static bool available();

  /// Build the hierarchy of `a` (symmetric positive definite, both triangles, columns sorted).
  /// @param a the matrix
  /// @throws std::runtime_error if hypre fails to build it
  /// @throws std::invalid_argument when Talus was built without hypre
  explicit BoomerAmg(const SparseRows& a);
  ~BoomerAmg();
  BoomerAmg(const BoomerAmg&) = delete;
  BoomerAmg& operator=(const BoomerAmg&) = delete;

  /// Solve A x = b from the initial guess in x until ||b - A x|| <= tolerance ||b||.
  /// @param b the right-hand side, n values
  /// @param x the initial guess on entry, the solution on return (n values)
  /// @param tolerance the relative residual to reach
  /// @param maxIterations the conjugate gradient iterations allowed
  /// @returns the iterations taken
  /// @throws std::runtime_error when it does not converge in maxIterations (a group of pores
  ///         connected to no imposed pressure) or the residual is not finite
  int solve(const std::vector<double>& b, std::vector<double>& x, double tolerance, int maxIterations) const;

private:
  struct Hypre;
  std::unique_ptr<Hypre> hypre_;
};
} // namespace talus::flow::pore
