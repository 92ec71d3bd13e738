#include "flow/pore/solver/PressureSolver.h"

#include <cholmod.h>
#include <dlfcn.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <span>
#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
namespace
{
// The factor is simplicial below PressureSolver::supernodalFrom (2 500) unknowns, supernodal
// above: the two cost alike near that size, the supernodal one ever less above it (docs/flow.md,
// "Measurements behind the code").
/// Supernodal factors of fewer unknowns amalgamate more columns into each supernode (CHOLMOD's
/// nrelax 8, 32, 128 instead of its 4, 16, 48): fewer, larger supernodes, at the price of more
/// explicit zeros. A small factorisation is bound by the per-supernode overhead (each supernode
/// and each update opens CHOLMOD OpenMP regions, a team allocation and a futex call each even
/// on one thread, and makes small BLAS calls), not by its flops: at 1 000 spheres (5 758
/// unknowns) 783 supernodes become 504. The coarser factors are faster up to a few thousand
/// spheres; at 10 000 spheres the two are alike, and CHOLMOD's default is kept there
/// (docs/flow.md, "Measurements behind the code").
constexpr int kCoarseBelow = 20000;
/// Conjugate gradients give up after this many multigrid cycles (they take some tens; many more
/// mean a group of pores connected to no imposed pressure).
constexpr int kMultigridIterations = 1000;
/// Nested dissection stops at this many unknowns (their order inside does not matter).
constexpr std::size_t kDissectionLeaf = 16;

/// Fill-reducing ordering of the rows (CHOLMOD's "given" permutation): nested dissection by
/// coordinate bisection on the pore centres. The rows are split at the median along the longest
/// extent of their centres; the separator is a minimum vertex cover of the couplings across the
/// cut (König's theorem on a maximum matching of the bipartite graph they form: the smallest set
/// of rows, from either half, that touches every one of them), ordered after both halves, which
/// are ordered the same way. The pore network is a 3D mesh whose geometry is known, so plane
/// cuts give good separators at almost no cost: the ordering takes a tenth of METIS's time for a
/// factor about as cheap, and AMD's factors take more flops. The minimum vertex cover gives
/// smaller factors than the one-sided separator (the lower half's rows coupled to the upper
/// half). Choosing the cut axis by the smallest separator, and CAMD on the leaves and
/// separators, saved a few per cent of flops for more ordering time than they saved: kept out
/// (docs/flow.md, "Measurements behind the code").
class NestedDissection
{
public:
  /// `start`, `adjacent`: the couplings of each row to the other rows, in compressed rows;
  /// `sequence`: the rows in the order the splits take them (the cuts' ties and the matchings
  /// follow it: the same sequence of pores gives the same ordering of the pores, and so the same
  /// factor, whatever the rows' numbering).
  NestedDissection(const std::vector<Vec3>& centres, const std::vector<int>& sequence, const std::vector<int>& start,
                   const std::vector<int>& adjacent)
      : start_(start), adjacent_(adjacent), items_(centres.size()), label_(centres.size(), 0), slot_(centres.size(), -1)
  {
    for (std::size_t k = 0; k < sequence.size(); ++k)
      items_[k] = {centres[static_cast<std::size_t>(sequence[k])], sequence[k]};
  }
  std::vector<int> order()
  {
    perm_.clear();
    perm_.reserve(items_.size());
    dissect(0, items_.size());
    return std::move(perm_);
  }

private:
  /// A row with its centre beside it: the splits reorder these in place, reading the centres
  /// in sequence (with the rows as indices into the centres, the reads missed the cache at
  /// every split).
  struct Item
  {
    Vec3 centre;
    int row;
  };

  void dissect(std::size_t begin, std::size_t end)
  {
    if (end - begin <= kDissectionLeaf)
    {
      for (std::size_t i = begin; i < end; ++i)
        perm_.push_back(items_[i].row);
      return;
    }
    Vec3 lo = items_[begin].centre;
    Vec3 hi = lo;
    for (std::size_t i = begin; i < end; ++i)
    {
      lo = lo.cwiseMin(items_[i].centre);
      hi = hi.cwiseMax(items_[i].centre);
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const std::size_t mid = begin + (end - begin) / 2;
    const auto first = items_.begin();
    std::nth_element(first + static_cast<std::ptrdiff_t>(begin), first + static_cast<std::ptrdiff_t>(mid),
                     first + static_cast<std::ptrdiff_t>(end),
                     [axis](const Item& a, const Item& b) { return a.centre[axis] < b.centre[axis]; });
    const int lower = ++labels_;
    const int upper = ++labels_;
    for (std::size_t i = begin; i < end; ++i)
      label_[static_cast<std::size_t>(items_[i].row)] = i < mid ? lower : upper;
    // the separator waits on `pending_` (above the ones of the enclosing splits) until both
    // halves are ordered
    const std::size_t separator = pending_.size();
    cover(begin, mid, end, lower, upper);
    for (std::size_t k = separator; k < pending_.size(); ++k)
      label_[static_cast<std::size_t>(pending_[k])] = 0; // out of both halves
    // pack the two halves without the separator from `begin`, stably, in place
    std::size_t kept = begin;
    for (std::size_t i = begin; i < end; ++i)
      if (label_[static_cast<std::size_t>(items_[i].row)] != 0)
        items_[kept++] = items_[i];
    std::size_t split = begin;
    while (split < kept && label_[static_cast<std::size_t>(items_[split].row)] == lower)
      ++split;
    dissect(begin, split);
    dissect(split, kept);
    perm_.insert(perm_.end(), pending_.begin() + static_cast<std::ptrdiff_t>(separator), pending_.end());
    pending_.resize(separator);
  }

  /// Appends to pending_ a minimum vertex cover of the couplings between rows labelled `lower`
  /// (items_[begin, mid)) and `upper` (items_[mid, end)). The work lists are members: kept
  /// from split to split, they are allocated once.
  void cover(std::size_t begin, std::size_t mid, std::size_t end, int lower, int upper)
  {
    const auto around = [&](int r) {
      return std::span<const int>(adjacent_.data() + start_[static_cast<std::size_t>(r)],
                                  adjacent_.data() + start_[static_cast<std::size_t>(r) + 1]);
    };
    const auto touches = [&](int r, int side) {
      const auto a = around(r);
      return std::any_of(a.begin(), a.end(), [&](int q) { return label_[static_cast<std::size_t>(q)] == side; });
    };
    left_.clear();  // lower rows with a coupling across
    right_.clear(); // upper rows with a coupling across
    for (std::size_t i = begin; i < mid; ++i)
      if (touches(items_[i].row, upper))
        left_.push_back(items_[i].row);
    for (std::size_t i = mid; i < end; ++i)
      if (touches(items_[i].row, lower))
      {
        slot_[static_cast<std::size_t>(items_[i].row)] = static_cast<int>(right_.size());
        right_.push_back(items_[i].row);
      }
    // maximum matching by augmenting paths (depth-first, iterative)
    matchLeft_.assign(left_.size(), -1);
    matchRight_.assign(right_.size(), -1);
    seen_.assign(right_.size(), -1);
    for (std::size_t root = 0; root < left_.size(); ++root)
    {
      path_.assign(1, {static_cast<int>(root), 0});
      via_.assign(1, -1);
      while (!path_.empty())
      {
        auto& [l, next] = path_.back();
        const auto a = around(left_[static_cast<std::size_t>(l)]);
        if (next == a.size())
        {
          path_.pop_back();
          via_.pop_back();
          continue;
        }
        const int q = a[next++];
        if (label_[static_cast<std::size_t>(q)] != upper)
          continue;
        const int r = slot_[static_cast<std::size_t>(q)];
        if (seen_[static_cast<std::size_t>(r)] == static_cast<int>(root))
          continue;
        seen_[static_cast<std::size_t>(r)] = static_cast<int>(root);
        via_.back() = r;
        if (matchRight_[static_cast<std::size_t>(r)] < 0)
        {
          for (std::size_t d = 0; d < path_.size(); ++d)
          {
            matchLeft_[static_cast<std::size_t>(path_[d].first)] = via_[d];
            matchRight_[static_cast<std::size_t>(via_[d])] = path_[d].first;
          }
          break;
        }
        path_.emplace_back(matchRight_[static_cast<std::size_t>(r)], 0);
        via_.push_back(-1);
      }
    }
    // König: Z = rows reachable from unmatched left rows by alternating paths; the cover is the
    // left rows outside Z and the right rows inside it
    inLeft_.assign(left_.size(), 0);
    inRight_.assign(right_.size(), 0);
    stack_.clear();
    for (std::size_t l = 0; l < left_.size(); ++l)
      if (matchLeft_[l] < 0)
      {
        inLeft_[l] = 1;
        stack_.push_back(static_cast<int>(l));
      }
    while (!stack_.empty())
    {
      const int l = stack_.back();
      stack_.pop_back();
      for (const int q : around(left_[static_cast<std::size_t>(l)]))
      {
        if (label_[static_cast<std::size_t>(q)] != upper)
          continue;
        const int r = slot_[static_cast<std::size_t>(q)];
        if (inRight_[static_cast<std::size_t>(r)] || matchLeft_[static_cast<std::size_t>(l)] == r)
          continue;
        inRight_[static_cast<std::size_t>(r)] = 1;
        const int back = matchRight_[static_cast<std::size_t>(r)];
        if (back >= 0 && !inLeft_[static_cast<std::size_t>(back)])
        {
          inLeft_[static_cast<std::size_t>(back)] = 1;
          stack_.push_back(back);
        }
      }
    }
    for (std::size_t l = 0; l < left_.size(); ++l)
      if (!inLeft_[l])
        pending_.push_back(left_[l]);
    for (std::size_t r = 0; r < right_.size(); ++r)
      if (inRight_[r])
        pending_.push_back(right_[r]);
  }

  const std::vector<int>& start_;
  const std::vector<int>& adjacent_;
  std::vector<Item> items_;
  std::vector<int> label_; ///< which half of the current split a row is in (0: neither)
  std::vector<int> slot_;  ///< index of an upper row among the rows coupled across the cut
  int labels_ = 0;
  std::vector<int> perm_;
  std::vector<int> pending_; ///< separators of the splits in progress, outermost first
  // cover's work lists
  std::vector<int> left_;
  std::vector<int> right_;
  std::vector<int> matchLeft_;
  std::vector<int> matchRight_;
  std::vector<int> seen_;
  std::vector<std::pair<int, std::size_t>> path_; ///< (left vertex, next coupling to try)
  std::vector<int> via_;                          ///< right vertex taken at each depth
  std::vector<char> inLeft_;
  std::vector<char> inRight_;
  std::vector<int> stack_;
};
} // namespace

/// For its lifetime, OpenMP parallel regions of this thread run on one thread if the caller is
/// set to one (omp_get_max_threads() == 1, e.g. OMP_NUM_THREADS=1). CHOLMOD's supernodal
/// factorisation (SuiteSparse 5) opens teams with a fixed num_threads(4) clause, which overrides
/// OMP_NUM_THREADS: a "single-threaded" run had three more threads spinning in every
/// factorisation, which cost a single-threaded run two to three times its CPU time on a loaded
/// machine (docs/flow.md, "Measurements behind the code").
class OneThreadIfAsked
{
public:
#ifdef _OPENMP
  OneThreadIfAsked() : levels_(omp_get_max_active_levels())
  {
    if (omp_get_max_threads() == 1)
      omp_set_max_active_levels(0);
  }
  ~OneThreadIfAsked() { omp_set_max_active_levels(levels_); }

private:
  int levels_;
#endif
public:
  OneThreadIfAsked(const OneThreadIfAsked&) = delete;
  OneThreadIfAsked& operator=(const OneThreadIfAsked&) = delete;
};

/// For its lifetime, OpenBLAS runs its calls on the calling thread, as Yade's FlowEngine has it
/// for the factorisation and the solve (numFactorizeThreads and numSolveThreads, both 1 by
/// default). A supernodal factor makes many small BLAS calls, between which OpenBLAS's own
/// threads spin: on two threads they cost more CPU time than they saved wall time (docs/flow.md,
/// "Measurements behind the code"). OpenBLAS is looked up at run time: another BLAS is left as
/// it is.
class OneBlasThread
{
public:
  OneBlasThread()
  {
    if (kSet && kGet && (threads_ = kGet()) != 1)
      kSet(1);
  }
  ~OneBlasThread()
  {
    if (kSet && kGet && threads_ != 1)
      kSet(threads_);
  }
  OneBlasThread(const OneBlasThread&) = delete;
  OneBlasThread& operator=(const OneBlasThread&) = delete;

private:
  using Set = void (*)(int);
  using Get = int (*)();
  inline static const Set kSet = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  inline static const Get kGet = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  int threads_ = 1;
};

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
    // the ordering is ours (NestedDissection), given to CHOLMOD, which then only postorders
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_GIVEN;
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
  const bool amg = kind == SolverKind::BoomerAmg;
  if (((kind == SolverKind::Multigrid && !multigrid_) || (amg && !boomerAmg_)) && nUnknown_ > 0)
  {
    const auto start = std::chrono::steady_clock::now();
    if (amg)
    {
      SparseRows rows = fullRows();
      // BoomerAMG's smoother skips a row without diagonal, which would leave that pore at its
      // initial pressure: a pore whose throats all have zero conductance is named instead
      for (std::size_t r = 0; r < static_cast<std::size_t>(rows.n); ++r)
      {
        const auto first = rows.column.begin() + rows.start[r];
        const auto last = rows.column.begin() + rows.start[r + 1];
        const auto d = std::lower_bound(first, last, static_cast<int>(r));
        if (d == last || *d != static_cast<int>(r) || !(rows.value[static_cast<std::size_t>(d - rows.column.begin())] > 0))
          throw std::runtime_error("pressure system is singular: pore " + std::to_string(poreOfRow_[r]) +
                                   " is connected to no imposed pressure (its throats have no conductance)");
      }
      boomerAmg_ = std::make_unique<BoomerAmg>(rows);
    }
    else
      multigrid_ = std::make_unique<Multigrid>(fullRows());
    counters_.multigridSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++counters_.multigridSetups;
  }
}

SparseRows PressureSolver::fullRows() const
{
  // as the triangle given to CHOLMOD (factorize): couplings to the same row summed, a coupling
  // of a row to itself cancelling on the diagonal
  SparseRows a;
  a.n = nUnknown_;
  a.start.reserve(static_cast<std::size_t>(nUnknown_) + 1);
  a.column.reserve(neighbour_.size() + static_cast<std::size_t>(nUnknown_));
  a.value.reserve(neighbour_.size() + static_cast<std::size_t>(nUnknown_));
  std::vector<std::pair<int, double>> row;
  for (std::size_t r = 0; r < static_cast<std::size_t>(nUnknown_); ++r)
  {
    row.assign(1, {static_cast<int>(r), diag_[r]});
    for (int e = start_[r]; e < start_[r + 1]; ++e)
    {
      const int column = rowOfPore_[static_cast<std::size_t>(neighbour_[static_cast<std::size_t>(e)])];
      if (column < 0)
        continue;
      const auto same = std::find_if(row.begin(), row.end(), [&](const auto& entry) { return entry.first == column; });
      if (same != row.end())
        same->second -= k_[static_cast<std::size_t>(e)];
      else
        row.emplace_back(column, -k_[static_cast<std::size_t>(e)]);
    }
    std::sort(row.begin(), row.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [column, value] : row)
    {
      a.column.push_back(column);
      a.value.push_back(value);
    }
    a.start.push_back(static_cast<int>(a.column.size()));
  }
  return a;
}

void PressureSolver::addCounters(const Counters& earlier)
{
  counters_.analyses += earlier.analyses;
  counters_.factorizations += earlier.factorizations;
  counters_.analyseSeconds += earlier.analyseSeconds;
  counters_.factorizeSeconds += earlier.factorizeSeconds;
  counters_.multigridSetups += earlier.multigridSetups;
  counters_.multigridIterations += earlier.multigridIterations;
  counters_.multigridSeconds += earlier.multigridSeconds;
}

void PressureSolver::setSystem(const PoreNetwork& net, const std::vector<char>& imposed, const std::vector<double>& diagonal)
{
  const std::size_t n = net.pores.size();
  if (imposed.size() != n)
    throw std::invalid_argument("pressure system: imposed-pressure flags do not match the pores");
  if (!diagonal.empty() && diagonal.size() != n)
    throw std::invalid_argument("pressure system: diagonal terms do not match the pores");
  // a storage term (compressible fluid) makes the system definite without an imposed pressure
  if (diagonal.empty() && std::find(imposed.begin(), imposed.end(), 1) == imposed.end())
    throw std::invalid_argument("pressure system is singular: no pressure is imposed anywhere (set "
                                "bndCondIsPressure on at least one boundary, or fluidBulkModulus > 0)");
  // The pattern is kept to compare: same rows and same couplings keep the symbolic analysis.
  const std::vector<int> oldRows = std::move(rowOfPore_);
  const std::vector<int> oldStart = std::move(start_);
  const std::vector<int> oldNeighbour = std::move(neighbour_);
  numeric_ = false;
  multigrid_.reset();
  boomerAmg_.reset();
  if (cholmod_->a)
    cholmod_free_sparse(&cholmod_->a, &cholmod_->common);
  rowOfPore_.assign(n, -1);
  poreOfRow_.clear();
  poreOfRow_.reserve(n);
  centreOfRow_.clear();
  centreOfRow_.reserve(n);
  // the rows along the network's space-filling curve: a row's couplings are to rows close to
  // it, so the multigrids' set-ups and cycles and the assembly below read within the caches (in
  // pore order, CGAL's cell order, they jumped across the arrays at every coupling; measured in
  // docs/flow.md, "The solvers' rows along a curve")
  const bool alongCurve = net.curveOrder.size() == n;
  for (std::size_t k = 0; k < n; ++k)
    if (const std::size_t i = alongCurve ? static_cast<std::size_t>(net.curveOrder[k]) : k; !imposed[i])
    {
      rowOfPore_[i] = static_cast<int>(poreOfRow_.size());
      poreOfRow_.push_back(static_cast<int>(i));
      centreOfRow_.push_back(net.pores[i].centre);
    }
  nUnknown_ = static_cast<int>(poreOfRow_.size());
  diag_.assign(poreOfRow_.size(), 0.0);
  start_.assign(1, 0);
  start_.reserve(poreOfRow_.size() + 1);
  // the old arrays were moved out above: without the reservation every push_back below grows
  // them again from nothing (copies and fresh pages, which page faults make dear)
  neighbour_.clear();
  neighbour_.reserve(4 * poreOfRow_.size());
  k_.clear();
  k_.reserve(4 * poreOfRow_.size());
  // the rows go along the curve, their pores and throats are anywhere in the arrays: each is
  // fetched some rows ahead (the pore twice as far, its throats once it is there)
  constexpr std::size_t kAhead = 8;
  for (std::size_t r = 0; r < poreOfRow_.size(); ++r)
  {
    if (r + 2 * kAhead < poreOfRow_.size())
      __builtin_prefetch(&net.pores[static_cast<std::size_t>(poreOfRow_[r + 2 * kAhead])].throats);
    if (r + kAhead < poreOfRow_.size())
      for (const int t : net.pores[static_cast<std::size_t>(poreOfRow_[r + kAhead])].throats)
        if (t >= 0)
          __builtin_prefetch(&net.throats[static_cast<std::size_t>(t)].conductance);
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
  solvedRhs_.clear();
  Cholmod& c = *cholmod_;
  const auto n = static_cast<std::size_t>(nUnknown_);
  // CHOLMOD permutes the matrix before factorising it; it takes one transpose for the upper
  // triangle of a supernodal factor and for the lower one of a simplicial factor, two otherwise
  // (cholmod_factorize): with the lower triangle given to the supernodal factor, the transpose is
  // a visible part of a remesh (docs/flow.md, "Measurements behind the code").
  // the kind is decided with the analysis and kept with it (the triangle must match the factor's)
  const bool supernodal = c.factor ? c.factor->is_super != 0 : nUnknown_ >= supernodalFrom;
  // That triangle in compressed columns, built directly: column j holds row j's couplings to the
  // rows after it (lower) or before it (upper), by symmetry, in increasing row order, with the
  // diagonal first (lower) or last (upper); couplings to the same row (a periodic pore meeting
  // another through two facets) summed, a coupling of a row to itself (its own periodic image)
  // cancelling on the diagonal.
  c.a = cholmod_allocate_sparse(n, n, n + neighbour_.size(), 1 /* sorted */, 1 /* packed */, supernodal ? 1 : -1,
                                CHOLMOD_REAL, &c.common);
  auto* ap = static_cast<int*>(c.a->p);
  auto* ai = static_cast<int*>(c.a->i);
  auto* ax = static_cast<double*>(c.a->x);
  std::size_t nz = 0;
  for (std::size_t j = 0; j < n; ++j)
  {
    const int column = static_cast<int>(j);
    ap[j] = static_cast<int>(nz);
    const std::size_t diagonal = nz;
    if (!supernodal)
      ++nz; // the diagonal's slot
    const std::size_t offDiagonal = nz;
    double pivot = diag_[j];
    for (int e = start_[j]; e < start_[j + 1]; ++e)
    {
      const int row = rowOfPore_[static_cast<std::size_t>(neighbour_[static_cast<std::size_t>(e)])];
      const double value = -k_[static_cast<std::size_t>(e)];
      if (row == column)
        pivot += value;
      if (row < 0 || row == column || (supernodal ? row > column : row < column))
        continue;
      // insert in order among this column's few entries (at most four couplings)
      std::size_t at = nz;
      while (at > offDiagonal && ai[at - 1] > row)
        --at;
      if (at > offDiagonal && ai[at - 1] == row)
      {
        ax[at - 1] += value;
        continue;
      }
      for (std::size_t m = nz; m > at; --m)
      {
        ai[m] = ai[m - 1];
        ax[m] = ax[m - 1];
      }
      ai[at] = row;
      ax[at] = value;
      ++nz;
    }
    const std::size_t at = supernodal ? nz++ : diagonal;
    ai[at] = column;
    ax[at] = pivot;
  }
  ap[n] = static_cast<int>(nz);
  using Clock = std::chrono::steady_clock;
  if (!c.factor)
  {
    const auto start = Clock::now();
    // the couplings between unknown rows, in compressed rows (one allocation, not one a row)
    std::vector<int> coupledStart(n + 1, 0);
    std::vector<int> coupled;
    coupled.reserve(neighbour_.size());
    for (std::size_t r = 0; r < n; ++r)
    {
      for (int e = start_[r]; e < start_[r + 1]; ++e)
        if (const int col = rowOfPore_[static_cast<std::size_t>(neighbour_[static_cast<std::size_t>(e)])]; col >= 0)
          coupled.push_back(col);
      coupledStart[r + 1] = static_cast<int>(coupled.size());
    }
    // the rows in pore order: the factor of the pores' matrix is the same bits whatever order
    // the rows are in (setSystem numbers them along a curve for the multigrids)
    std::vector<int> rowsInPoreOrder;
    rowsInPoreOrder.reserve(n);
    for (const int row : rowOfPore_)
      if (row >= 0)
        rowsInPoreOrder.push_back(row);
    std::vector<int> perm = NestedDissection(centreOfRow_, rowsInPoreOrder, coupledStart, coupled).order();
    c.common.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    const bool coarse = nUnknown_ < kCoarseBelow;
    const std::size_t nrelax[3] = {coarse ? 8U : 4U, coarse ? 32U : 16U, coarse ? 128U : 48U}; // CHOLMOD's: 4, 16, 48
    std::copy(std::begin(nrelax), std::end(nrelax), c.common.nrelax);
    c.factor = cholmod_analyze_p(c.a, perm.data(), nullptr, 0, &c.common);
    counters_.analyseSeconds += std::chrono::duration<double>(Clock::now() - start).count();
    ++counters_.analyses;
    if (!c.factor)
      throw std::runtime_error("CHOLMOD failed to analyse the pressure system (status " +
                               std::to_string(c.common.status) + ")");
  }
  const auto start = Clock::now();
  {
    const OneThreadIfAsked oneThread;
    const OneBlasThread oneBlasThread;
    cholmod_factorize(c.a, c.factor, &c.common);
  }
  counters_.factorizeSeconds += std::chrono::duration<double>(Clock::now() - start).count();
  ++counters_.factorizations;
  if (c.common.status == CHOLMOD_NOT_POSDEF || c.factor->minor < c.factor->n)
  {
    // minor is the failing column of the permuted matrix
    const auto column = static_cast<std::size_t>(c.factor->minor);
    const int pore = column < poreOfRow_.size()
                         ? poreOfRow_[static_cast<std::size_t>(static_cast<const int*>(c.factor->Perm)[column])]
                         : -1;
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
    if (b != solvedRhs_)
    {
      std::copy(b.begin(), b.end(), static_cast<double*>(c.b->x));
      // cholmod_solve2 re-uses x, y and e when their sizes fit
      const OneBlasThread oneBlasThread;
      cholmod_solve2(CHOLMOD_A, c.factor, c.b, nullptr, &c.x, nullptr, &c.y, &c.e, &c.common);
      solvedRhs_ = std::move(b);
    }
    const auto* xv = static_cast<const double*>(c.x->x);
    for (std::size_t r = 0; r < n; ++r)
      p[static_cast<std::size_t>(poreOfRow_[r])] = xv[r];
    iterations_ = 1;
    return;
  }
  if (kind == SolverKind::Multigrid || kind == SolverKind::BoomerAmg)
  {
    prepare(kind);
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> x(n);
    for (std::size_t r = 0; r < n; ++r)
      x[r] = p[static_cast<std::size_t>(poreOfRow_[r])];
    iterations_ = kind == SolverKind::Multigrid ? multigrid_->solve(b, x, multigridTolerance, kMultigridIterations)
                                               : boomerAmg_->solve(b, x, multigridTolerance, kMultigridIterations);
    for (std::size_t r = 0; r < n; ++r)
      p[static_cast<std::size_t>(poreOfRow_[r])] = x[r];
    counters_.multigridSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    counters_.multigridIterations += iterations_;
    return;
  }
  // Gauss-Seidel with over-relaxation, in place on p, sweeping the pores in their order, as
  // Yade's (not the rows')
  for (iterations_ = 1; iterations_ <= maxIterations; ++iterations_)
  {
    double maxDp = 0;
    double maxP = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      if (rowOfPore_[i] < 0)
        continue;
      const auto r = static_cast<std::size_t>(rowOfPore_[i]);
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
