#include "flow/pore/solver/BoomerAmg.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <numeric>
#include <utility>
#include <stdexcept>
#include <string>

#ifdef TALUS_HAVE_HYPRE
#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

namespace talus::flow::pore
{
namespace
{
// BoomerAMG's settings for these networks (each measured on the bench's 30 000 and 100 000-sphere
// systems, docs/flow.md "Remeshing large packings"): HMIS coarsening with extended+i
// interpolation (hypre's advice for 3D problems), at most 4 entries per interpolation row, a
// coupling strong from half the row's largest (0.25 took half as much set-up again for the same
// solve, 0.7 more iterations), one forward Gauss-Seidel sweep before the coarse correction and
// one backward after it: a symmetric cycle, as conjugate gradients need, at half the cost of a
// symmetric sweep on each side (15 iterations instead of 13, a solve a fifth cheaper).
constexpr int kHmisCoarsening = 10;
constexpr int kExtendedPlusI = 6;
constexpr int kInterpolationEntries = 4;
constexpr double kStrength = 0.5;
constexpr int kForwardGaussSeidel = 3;
constexpr int kBackwardGaussSeidel = 4;
constexpr int kGaussianElimination = 9;
// hypre's cycle legs
constexpr int kDown = 1;
constexpr int kUp = 2;
constexpr int kCoarsest = 3;

/// hypre calls MPI on MPI_COMM_SELF: MPI must be initialised. A program that did not (a serial
/// script) gets it initialised here once, and finalised when it exits.
void ensureMpi()
{
  static std::once_flag once;
  std::call_once(once, [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
      // background remeshing builds a network, and so a hierarchy, on another thread
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided);
      std::atexit([] {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (!finalised)
          MPI_Finalize();
      });
    }
  });
}

void check(HYPRE_Int status, const char* what)
{
  if (status != 0 && !HYPRE_CheckError(status, HYPRE_ERROR_CONV))
  {
    HYPRE_ClearAllErrors();
    throw std::runtime_error(std::string("hypre BoomerAMG: ") + what + " failed (hypre error " +
                             std::to_string(status) + ")");
  }
}
} // namespace

struct BoomerAmg::Hypre
{
  HYPRE_Int n = 0;
  std::vector<HYPRE_Int> rows;
  HYPRE_IJMatrix matrix = nullptr;
  HYPRE_IJVector b = nullptr;
  HYPRE_IJVector x = nullptr;
  HYPRE_IJVector r = nullptr; ///< the residual of the initial guess
  HYPRE_ParCSRMatrix parMatrix = nullptr;
  HYPRE_ParVector parB = nullptr;
  HYPRE_ParVector parX = nullptr;
  HYPRE_ParVector parR = nullptr;
  HYPRE_Solver pcg = nullptr;
  HYPRE_Solver amg = nullptr;

  Hypre() = default;
  Hypre(const Hypre&) = delete;
  Hypre& operator=(const Hypre&) = delete;
  ~Hypre()
  {
    if (pcg)
      HYPRE_ParCSRPCGDestroy(pcg);
    if (amg)
      HYPRE_BoomerAMGDestroy(amg);
    if (r)
      HYPRE_IJVectorDestroy(r);
    if (x)
      HYPRE_IJVectorDestroy(x);
    if (b)
      HYPRE_IJVectorDestroy(b);
    if (matrix)
      HYPRE_IJMatrixDestroy(matrix);
  }

  HYPRE_IJVector vector()
  {
    HYPRE_IJVector v = nullptr;
    check(HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, &v), "a vector");
    check(HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR), "a vector");
    check(HYPRE_IJVectorInitialize(v), "a vector");
    return v;
  }
};

BoomerAmg::BoomerAmg(const SparseRows& a) : hypre_(std::make_unique<Hypre>())
{
  ensureMpi();
  Hypre& h = *hypre_;
  h.n = a.n;
  h.rows.resize(static_cast<std::size_t>(a.n));
  std::iota(h.rows.begin(), h.rows.end(), 0);
  std::vector<HYPRE_Int> entries(static_cast<std::size_t>(a.n));
  for (std::size_t r = 0; r < entries.size(); ++r)
    entries[r] = a.start[r + 1] - a.start[r];
  check(HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, a.n - 1, 0, a.n - 1, &h.matrix), "the matrix");
  check(HYPRE_IJMatrixSetObjectType(h.matrix, HYPRE_PARCSR), "the matrix");
  // every column is in this process's diagonal block: given that split, hypre writes the values
  // straight into its CSR arrays instead of an auxiliary matrix it copies at the assembly (the
  // entries of a row land in another order: round-off; measured in docs/flow.md, "10 000 spheres
  // on one thread reached")
  const std::vector<HYPRE_Int> noOffDiagonal(entries.size(), 0);
  check(HYPRE_IJMatrixSetDiagOffdSizes(h.matrix, entries.data(), noOffDiagonal.data()), "the matrix");
  check(HYPRE_IJMatrixInitialize(h.matrix), "the matrix");
  check(HYPRE_IJMatrixSetValues(h.matrix, a.n, entries.data(), h.rows.data(), a.column.data(), a.value.data()),
        "the matrix");
  check(HYPRE_IJMatrixAssemble(h.matrix), "the matrix");
  check(HYPRE_IJMatrixGetObject(h.matrix, reinterpret_cast<void**>(&h.parMatrix)), "the matrix");
  h.b = h.vector();
  h.x = h.vector();
  h.r = h.vector();
  for (auto [v, par] : {std::pair{h.b, &h.parB}, std::pair{h.x, &h.parX}, std::pair{h.r, &h.parR}})
  {
    check(HYPRE_IJVectorAssemble(v), "a vector");
    check(HYPRE_IJVectorGetObject(v, reinterpret_cast<void**>(par)), "a vector");
  }

  check(HYPRE_BoomerAMGCreate(&h.amg), "BoomerAMG");
  HYPRE_BoomerAMGSetCoarsenType(h.amg, kHmisCoarsening);
  HYPRE_BoomerAMGSetInterpType(h.amg, kExtendedPlusI);
  HYPRE_BoomerAMGSetPMaxElmts(h.amg, kInterpolationEntries);
  HYPRE_BoomerAMGSetStrongThreshold(h.amg, kStrength);
  HYPRE_BoomerAMGSetCycleRelaxType(h.amg, kForwardGaussSeidel, kDown);
  HYPRE_BoomerAMGSetCycleRelaxType(h.amg, kBackwardGaussSeidel, kUp);
  HYPRE_BoomerAMGSetCycleRelaxType(h.amg, kGaussianElimination, kCoarsest);
  HYPRE_BoomerAMGSetNumSweeps(h.amg, 1);
  // one V-cycle per preconditioner application
  HYPRE_BoomerAMGSetMaxIter(h.amg, 1);
  HYPRE_BoomerAMGSetTol(h.amg, 0.0);
  HYPRE_BoomerAMGSetPrintLevel(h.amg, 0);
  check(HYPRE_ParCSRPCGCreate(MPI_COMM_SELF, &h.pcg), "conjugate gradients");
  HYPRE_PCGSetTwoNorm(h.pcg, 1);
  HYPRE_PCGSetPrecond(h.pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), h.amg);
  check(HYPRE_ParCSRPCGSetup(h.pcg, h.parMatrix, h.parB, h.parX), "the set-up");
}

BoomerAmg::~BoomerAmg() = default;

bool BoomerAmg::available() { return true; }

int BoomerAmg::solve(const std::vector<double>& b, std::vector<double>& x, double tolerance, int maxIterations) const
{
  Hypre& h = *hypre_;
  // A x = 0 has x = 0 (hypre's conjugate gradients return it without a residual to check)
  if (std::all_of(b.begin(), b.end(), [](double v) { return v == 0.0; }))
  {
    std::fill(x.begin(), x.end(), 0.0);
    return 0;
  }
  HYPRE_ClearAllErrors();
  check(HYPRE_IJVectorSetValues(h.b, h.n, h.rows.data(), b.data()), "the right-hand side");
  check(HYPRE_IJVectorSetValues(h.x, h.n, h.rows.data(), x.data()), "the initial guess");
  // an initial guess that already solves the system is kept as it is (hypre's conjugate
  // gradients would take a step from it): the same system solved again costs one product
  HYPRE_Real bb = 0;
  HYPRE_Real rr = 0;
  check(HYPRE_ParVectorCopy(h.parB, h.parR), "the residual");
  check(HYPRE_ParCSRMatrixMatvec(-1.0, h.parMatrix, h.parX, 1.0, h.parR), "the residual");
  HYPRE_ParVectorInnerProd(h.parB, h.parB, &bb);
  HYPRE_ParVectorInnerProd(h.parR, h.parR, &rr);
  if (rr <= tolerance * tolerance * bb)
    return 0;
  HYPRE_PCGSetTol(h.pcg, tolerance);
  HYPRE_PCGSetMaxIter(h.pcg, maxIterations);
  check(HYPRE_ParCSRPCGSolve(h.pcg, h.parMatrix, h.parB, h.parX), "the solve");
  HYPRE_Int iterations = 0;
  HYPRE_Real residual = 0;
  HYPRE_PCGGetNumIterations(h.pcg, &iterations);
  HYPRE_PCGGetFinalRelativeResidualNorm(h.pcg, &residual);
  HYPRE_ClearAllErrors();
  if (!std::isfinite(residual) || residual > tolerance)
    throw std::runtime_error("hypre BoomerAMG: conjugate gradients did not converge in " +
                             std::to_string(iterations) + " iterations (relative residual " +
                             std::to_string(residual) + "; a group of pores connected to no imposed pressure?)");
  check(HYPRE_IJVectorGetValues(h.x, h.n, h.rows.data(), x.data()), "the solution");
  return iterations;
}
} // namespace talus::flow::pore
#else
namespace talus::flow::pore
{
struct BoomerAmg::Hypre
{
};

BoomerAmg::BoomerAmg(const SparseRows&)
{
  throw std::invalid_argument("useSolver=5 (hypre's BoomerAMG) needs Talus built with hypre (apt-get install "
                              "libhypre-dev, then configure again)");
}

BoomerAmg::~BoomerAmg() = default;

bool BoomerAmg::available() { return false; }

int BoomerAmg::solve(const std::vector<double>&, std::vector<double>&, double, int) const { return 0; }
} // namespace talus::flow::pore
#endif
