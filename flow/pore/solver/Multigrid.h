#pragma once
// Conjugate gradients preconditioned by smoothed-aggregation algebraic multigrid (Vanek, Mandel
// and Brezina 1996) for the pore pressure system: a symmetric positive definite M-matrix (a
// weighted graph Laplacian with the imposed pores eliminated). Its cost grows in proportion to
// the unknowns, where a Cholesky factor of a 3D network grows as their square in flops and as
// their 4/3 power in memory: PressureSolver uses it for the solves of large systems that would
// otherwise wait for a factorisation.
#include <Eigen/Core>

#include <memory>
#include <vector>

namespace talus::flow::pore
{
/// A square sparse matrix in compressed rows, columns sorted in each row.
struct SparseRows
{
  int n = 0;
  std::vector<int> start{0};
  std::vector<int> column;
  std::vector<double> value;
};

/// Algebraic multigrid for the pressure system of a large network (useSolver=4): a hierarchy
/// of coarser matrices built once per matrix, used as the preconditioner of conjugate gradients.
class Multigrid
{
public:
  /// Build the hierarchy of `a` (symmetric positive definite, in compressed rows with both
  /// triangles).
  /// @param a the matrix, taken over
  /// @throws std::runtime_error if a row has no positive diagonal or the coarsest matrix is not
  ///         positive definite (a group of pores connected to no imposed pressure)
  explicit Multigrid(SparseRows a);
  ~Multigrid();
  Multigrid(const Multigrid&) = delete;
  Multigrid& operator=(const Multigrid&) = delete;

  /// Solve A x = b by preconditioned conjugate gradients from the initial guess in x, until
  /// ||b - A x|| <= tolerance ||b||.
  /// @param b the right-hand side, n values
  /// @param x the initial guess on entry, the solution on return (n values)
  /// @param tolerance the relative residual to reach
  /// @param maxIterations the conjugate gradient iterations allowed
  /// @returns the iterations taken
  /// @throws std::runtime_error when it does not converge in maxIterations
  int solve(const std::vector<double>& b, std::vector<double>& x, double tolerance, int maxIterations) const;

  /// The number of levels, the finest (the matrix given) and the coarsest (factorised) included.
  [[nodiscard]] std::size_t levels() const { return levels_.size(); }
  /// Sum of the nonzeros of all levels' matrices over the finest one's.
  [[nodiscard]] double operatorComplexity() const;

private:
  struct Level;
  void cycle(std::size_t l, const std::vector<double>& b, std::vector<double>& x) const;

  std::vector<std::unique_ptr<Level>> levels_;
  struct Coarse;
  std::unique_ptr<Coarse> coarse_;
};
} // namespace talus::flow::pore
