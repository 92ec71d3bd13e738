#include "flow/pore/PressureSolver.h"

#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
namespace
{
/// Unknowns from which CHOLMOD orders with METIS rather than AMD (see factorize).
constexpr std::size_t kMetisFrom = 5000;
} // namespace

/// CHOLMOD's workspace and the factor of the current matrix.
struct PressureSolver::Cholmod
{
  cholmod_common common{};
  cholmod_sparse* a = nullptr;
  cholmod_factor* factor = nullptr;
  // right-hand side, solution and cholmod_solve2's workspaces, kept from solve to solve (a
  // step between remeshes is one solve: no allocation in it)
  cholmod_dense* b = nullptr;
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;

  Cholmod()
  {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    // One ordering method (chosen per matrix in factorize): CHOLMOD's default tries AMD, then
    // METIS when the fill is high, and keeps the better -- on these 3D networks an analysis two
    // to three times longer than METIS alone for no less fill.
    common.nmethods = 1;
  }
  ~Cholmod()
  {
    clear();
    for (cholmod_dense** d : {&b, &x, &y, &e})
      if (*d)
        cholmod_free_dense(d, &common);
    cholmod_finish(&common);
  }
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;
  void clear()
  {
    if (factor)
      cholmod_free_factor(&factor, &common);
    if (a)
      cholmod_free_sparse(&a, &common);
  }
};

PressureSolver::PressureSolver() : cholmod_(std::make_unique<Cholmod>()) {}
PressureSolver::~PressureSolver() = default;
PressureSolver::PressureSolver(PressureSolver&&) noexcept = default;
PressureSolver& PressureSolver::operator=(PressureSolver&&) noexcept = default;

bool PressureSolver::factorized() const { return numeric_; }

void PressureSolver::prepare(SolverKind kind)
{
  if (kind == SolverKind::Cholmod && !numeric_ && nUnknown_ > 0)
    factorize();
}

void PressureSolver::addCounters(const Counters& earlier)
{
  counters_.analyses += earlier.analyses;
  counters_.factorizations += earlier.factorizations;
  counters_.analyseSeconds += earlier.analyseSeconds;
  counters_.factorizeSeconds += earlier.factorizeSeconds;
}

void PressureSolver::setSystem(const PoreNetwork& net, const std::vector<char>& imposed, const std::vector<double>& diagonal)
{
  const std::size_t n = net.pores.size();
  if (imposed.size() != n)
    throw std::invalid_argument("pressure system: imposed-pressure flags do not match the pores");
  if (!diagonal.empty() && diagonal.size() != n)
    throw std::invalid_argument("pressure system: diagonal terms do not match the pores");
  if (std::find(imposed.begin(), imposed.end(), 1) == imposed.end())
    throw std::invalid_argument("pressure system is singular: no pressure is imposed anywhere (set "
                                "bndCondIsPressure on at least one boundary)");
  // The pattern is kept to compare: same rows and same couplings keep the symbolic analysis.
  const std::vector<int> oldRows = std::move(rowOfPore_);
  const std::vector<int> oldStart = std::move(start_);
  const std::vector<int> oldNeighbour = std::move(neighbour_);
  numeric_ = false;
  if (cholmod_->a)
    cholmod_free_sparse(&cholmod_->a, &cholmod_->common);
  rowOfPore_.assign(n, -1);
  poreOfRow_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (!imposed[i])
    {
      rowOfPore_[i] = static_cast<int>(poreOfRow_.size());
      poreOfRow_.push_back(static_cast<int>(i));
    }
  nUnknown_ = static_cast<int>(poreOfRow_.size());
  diag_.assign(poreOfRow_.size(), 0.0);
  start_.assign(1, 0);
  neighbour_.clear();
  k_.clear();
  for (std::size_t r = 0; r < poreOfRow_.size(); ++r)
  {
    const Pore& p = net.pores[static_cast<std::size_t>(poreOfRow_[r])];
    for (int f = 0; f < 4; ++f)
    {
      if (p.throats[f] < 0)
        continue;
      const double k = net.throats[static_cast<std::size_t>(p.throats[f])].conductance;
      diag_[r] += k;
      neighbour_.push_back(p.neighbours[f]);
      k_.push_back(k);
    }
    if (!diagonal.empty())
      diag_[r] += diagonal[static_cast<std::size_t>(poreOfRow_[r])];
    start_.push_back(static_cast<int>(neighbour_.size()));
  }
  if (oldRows != rowOfPore_ || oldStart != start_ || oldNeighbour != neighbour_)
    cholmod_->clear();
}

void PressureSolver::factorize()
{
  Cholmod& c = *cholmod_;
  const auto n = static_cast<std::size_t>(nUnknown_);
  cholmod_triplet* t = cholmod_allocate_triplet(n, n, n + neighbour_.size(), -1 /* lower */, CHOLMOD_REAL, &c.common);
  auto* ti = static_cast<int*>(t->i);
  auto* tj = static_cast<int*>(t->j);
  auto* tx = static_cast<double*>(t->x);
  std::size_t nz = 0;
  for (std::size_t r = 0; r < n; ++r)
  {
    ti[nz] = tj[nz] = static_cast<int>(r);
    tx[nz++] = diag_[r];
    for (int e = start_[r]; e < start_[r + 1]; ++e)
    {
      const int col = rowOfPore_[static_cast<std::size_t>(neighbour_[static_cast<std::size_t>(e)])];
      if (col < 0 || col > static_cast<int>(r))
        continue;
      ti[nz] = static_cast<int>(r);
      tj[nz] = col;
      tx[nz++] = -k_[static_cast<std::size_t>(e)];
    }
  }
  t->nnz = nz;
  c.a = cholmod_triplet_to_sparse(t, nz, &c.common);
  cholmod_free_triplet(&t, &c.common);
  using Clock = std::chrono::steady_clock;
  if (!c.factor)
  {
    // AMD for small systems (its analysis is much cheaper and the fill does not matter yet:
    // 2 800 pores, 0.007 s + 0.03 s against METIS's 0.04 s + 0.04 s), METIS nested dissection
    // for large ones (15 000 pores: AMD 0.06 s + 1.1 s, METIS 0.30 s + 0.43 s; 31 000: AMD
    // 0.06 s + 1.0 s, METIS 0.41 s + 0.54 s; 135 000: AMD 0.5 s + 11 s, METIS 2.0 s + 3.1 s;
    // CHOLMOD's default, both tried, 1.0-1.3 s + 0.7-1.2 s at 31 000)
    c.common.method[0].ordering = n < kMetisFrom ? CHOLMOD_AMD : CHOLMOD_METIS;
    const auto start = Clock::now();
    c.factor = cholmod_analyze(c.a, &c.common);
    if (!c.factor && c.common.status == CHOLMOD_NOT_INSTALLED) // a CHOLMOD built without METIS
    {
      c.common.nmethods = 0;
      c.factor = cholmod_analyze(c.a, &c.common);
    }
    counters_.analyseSeconds += std::chrono::duration<double>(Clock::now() - start).count();
    ++counters_.analyses;
  }
  const auto start = Clock::now();
  cholmod_factorize(c.a, c.factor, &c.common);
  counters_.factorizeSeconds += std::chrono::duration<double>(Clock::now() - start).count();
  ++counters_.factorizations;
  if (c.common.status == CHOLMOD_NOT_POSDEF || c.factor->minor < c.factor->n)
  {
    const auto row = static_cast<std::size_t>(c.factor->minor);
    const int pore = row < poreOfRow_.size() ? poreOfRow_[row] : -1;
    c.clear();
    throw std::runtime_error("pressure system is singular: pore " + std::to_string(pore) +
                             " belongs to a group of pores connected to no imposed pressure");
  }
  if (c.common.status < CHOLMOD_OK)
  {
    c.clear();
    throw std::runtime_error("CHOLMOD failed to factorise the pressure system (status " +
                             std::to_string(c.common.status) + ")");
  }
  numeric_ = true;
}

void PressureSolver::solve(SolverKind kind, std::vector<double>& p, const std::vector<double>& source)
{
  if (p.size() != rowOfPore_.size())
    throw std::invalid_argument("pressure system: the pressure vector does not match the pores");
  const auto n = static_cast<std::size_t>(nUnknown_);
  // b_r = q_r + sum over imposed neighbours of k p_imposed
  std::vector<double> b(n, 0.0);
  for (std::size_t r = 0; r < n; ++r)
  {
    if (!source.empty())
      b[r] = source[static_cast<std::size_t>(poreOfRow_[r])];
    for (int e = start_[r]; e < start_[r + 1]; ++e)
    {
      const auto j = static_cast<std::size_t>(neighbour_[static_cast<std::size_t>(e)]);
      if (rowOfPore_[j] < 0)
        b[r] += k_[static_cast<std::size_t>(e)] * p[j];
    }
  }
  if (kind == SolverKind::Cholmod)
  {
    if (!factorized())
      factorize();
    Cholmod& c = *cholmod_;
    if (c.b && c.b->nrow != n)
      cholmod_free_dense(&c.b, &c.common);
    if (!c.b)
      c.b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &c.common);
    std::copy(b.begin(), b.end(), static_cast<double*>(c.b->x));
    // cholmod_solve2 re-uses x, y and e when their sizes fit
    cholmod_solve2(CHOLMOD_A, c.factor, c.b, nullptr, &c.x, nullptr, &c.y, &c.e, &c.common);
    const auto* xv = static_cast<const double*>(c.x->x);
    for (std::size_t r = 0; r < n; ++r)
      p[static_cast<std::size_t>(poreOfRow_[r])] = xv[r];
    iterations_ = 1;
    return;
  }
  // Gauss-Seidel with over-relaxation, in place on p.
  for (iterations_ = 1; iterations_ <= maxIterations; ++iterations_)
  {
    double maxDp = 0;
    double maxP = 0;
    for (std::size_t r = 0; r < n; ++r)
    {
      const auto i = static_cast<std::size_t>(poreOfRow_[r]);
      double sum = b[r];
      for (int e = start_[r]; e < start_[r + 1]; ++e)
      {
        const auto j = static_cast<std::size_t>(neighbour_[static_cast<std::size_t>(e)]);
        if (rowOfPore_[j] >= 0)
          sum += k_[static_cast<std::size_t>(e)] * p[j];
      }
      const double dp = relax * (sum / diag_[r] - p[i]);
      p[i] += dp;
      maxDp = std::max(maxDp, std::abs(dp));
      maxP = std::max(maxP, std::abs(p[i]));
    }
    if (!std::isfinite(maxDp))
      throw std::runtime_error("Gauss-Seidel diverged (non-finite pressure)");
    if (maxDp <= tolerance * std::max(maxP, 1e-300))
      return;
  }
  throw std::runtime_error("Gauss-Seidel did not converge in " + std::to_string(maxIterations) +
                           " iterations (a group of pores may be connected to no imposed pressure)");
}
} // namespace talus::flow::pore
