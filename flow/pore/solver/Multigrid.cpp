#include "flow/pore/solver/Multigrid.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace talus::flow::pore
{
namespace
{
/// Levels stop coarsening at this many rows; the coarsest is solved by a dense Cholesky factor.
constexpr int kCoarsest = 400;
constexpr std::size_t kMaxLevels = 12;
/// A level that keeps more than this share of its rows ends the hierarchy (no real coarsening).
constexpr double kMinCoarsening = 0.7;
/// A coupling is strong when -a_ij >= kStrength times the largest coupling of row i or of row j
/// (Ruge-Stueben's measure, symmetrised). The conductances span six orders of magnitude
/// (Yade's clamping at 1e-4 and 100 times the reference): aggregates follow the strong ones.
/// Vanek's measure, |a_ij| against sqrt(a_ii a_jj), let the coarse matrices fill in on these
/// networks (docs/flow.md, "Measurements behind the code").
constexpr double kStrength = 0.5;
/// Gauss-Seidel sweeps before and after the coarse correction (two cost more per cycle than one
/// and save more than that in iterations).
constexpr int kSweeps = 2;

/// One row of `entries` (column, value), sorted by column, appended to m as its next row.
void appendSorted(SparseRows& m, std::vector<std::pair<int, double>>& entries)
{
  std::sort(entries.begin(), entries.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (const auto& [c, v] : entries)
  {
    m.column.push_back(c);
    m.value.push_back(v);
  }
  m.start.push_back(static_cast<int>(m.column.size()));
}

SparseRows transpose(const SparseRows& a, int columns)
{
  SparseRows t;
  t.n = columns;
  t.start.assign(static_cast<std::size_t>(columns) + 1, 0);
  for (const int c : a.column)
    ++t.start[static_cast<std::size_t>(c) + 1];
  std::partial_sum(t.start.begin(), t.start.end(), t.start.begin());
  t.column.resize(a.column.size());
  t.value.resize(a.value.size());
  std::vector<int> next(t.start.begin(), t.start.end() - 1);
  for (int r = 0; r < a.n; ++r)
    for (int e = a.start[static_cast<std::size_t>(r)]; e < a.start[static_cast<std::size_t>(r) + 1]; ++e)
    {
      const auto at = static_cast<std::size_t>(next[static_cast<std::size_t>(a.column[static_cast<std::size_t>(e)])]++);
      t.column[at] = r;
      t.value[at] = a.value[static_cast<std::size_t>(e)];
    }
  return t;
}

/// a * b, b with `columns` columns.
SparseRows multiply(const SparseRows& a, const SparseRows& b, int columns)
{
  SparseRows c;
  c.n = a.n;
  std::vector<int> slot(static_cast<std::size_t>(columns), -1);
  std::vector<std::pair<int, double>> row;
  for (int r = 0; r < a.n; ++r)
  {
    row.clear();
    for (int e = a.start[static_cast<std::size_t>(r)]; e < a.start[static_cast<std::size_t>(r) + 1]; ++e)
    {
      const auto k = static_cast<std::size_t>(a.column[static_cast<std::size_t>(e)]);
      const double av = a.value[static_cast<std::size_t>(e)];
      for (int f = b.start[k]; f < b.start[k + 1]; ++f)
      {
        const int j = b.column[static_cast<std::size_t>(f)];
        int& s = slot[static_cast<std::size_t>(j)];
        if (s < 0)
        {
          s = static_cast<int>(row.size());
          row.emplace_back(j, 0.0);
        }
        row[static_cast<std::size_t>(s)].second += av * b.value[static_cast<std::size_t>(f)];
      }
    }
    for (const auto& entry : row)
      slot[static_cast<std::size_t>(entry.first)] = -1;
    appendSorted(c, row);
  }
  return c;
}

/// y = a x, or y += a x if `add`.
void multiply(const SparseRows& a, const std::vector<double>& x, std::vector<double>& y, bool add = false)
{
  for (std::size_t r = 0; r < static_cast<std::size_t>(a.n); ++r)
  {
    double sum = add ? y[r] : 0.0;
    for (int e = a.start[r]; e < a.start[r + 1]; ++e)
      sum += a.value[static_cast<std::size_t>(e)] * x[static_cast<std::size_t>(a.column[static_cast<std::size_t>(e)])];
    y[r] = sum;
  }
}

double dot(const std::vector<double>& a, const std::vector<double>& b)
{
  return std::inner_product(a.begin(), a.end(), b.begin(), 0.0);
}

/// Aggregates of the rows of m along its strong couplings (Vanek et al.'s three passes): a row
/// whose strong neighbours are all free starts an aggregate with them; a free row joins the
/// aggregate of its strongest aggregated neighbour; what is left forms aggregates with its free
/// strong neighbours. Returns each row's aggregate and their count.
std::pair<std::vector<int>, int> aggregate(const SparseRows& m, const std::vector<std::vector<char>>& strong)
{
  const auto n = static_cast<std::size_t>(m.n);
  std::vector<int> group(n, -1);
  int count = 0;
  const auto isStrong = [&](std::size_t r, int e) { return strong[r][static_cast<std::size_t>(e - m.start[r])] != 0; };
  const auto columnOf = [&](int e) { return static_cast<std::size_t>(m.column[static_cast<std::size_t>(e)]); };
  for (std::size_t r = 0; r < n; ++r)
  {
    bool free = group[r] < 0;
    bool any = false;
    for (int e = m.start[r]; e < m.start[r + 1] && free; ++e)
      if (isStrong(r, e))
      {
        any = true;
        free = group[columnOf(e)] < 0;
      }
    if (!free || !any)
      continue;
    group[r] = count;
    for (int e = m.start[r]; e < m.start[r + 1]; ++e)
      if (isStrong(r, e))
        group[columnOf(e)] = count;
    ++count;
  }
  std::vector<int> joined = group;
  for (std::size_t r = 0; r < n; ++r)
  {
    if (group[r] >= 0)
      continue;
    double best = 0;
    for (int e = m.start[r]; e < m.start[r + 1]; ++e)
      if (const int g = group[columnOf(e)]; g >= 0 && isStrong(r, e) && -m.value[static_cast<std::size_t>(e)] > best)
      {
        best = -m.value[static_cast<std::size_t>(e)];
        joined[r] = g;
      }
  }
  group = std::move(joined);
  for (std::size_t r = 0; r < n; ++r)
  {
    if (group[r] >= 0)
      continue;
    group[r] = count;
    for (int e = m.start[r]; e < m.start[r + 1]; ++e)
      if (group[columnOf(e)] < 0 && isStrong(r, e))
        group[columnOf(e)] = count;
    ++count;
  }
  return {std::move(group), count};
}
} // namespace

struct Multigrid::Level
{
  SparseRows a;
  std::vector<double> inverseDiagonal;
  SparseRows interpolation; ///< prolongation to this level from the next
  SparseRows restriction;   ///< the interpolation transposed
  // the cycle's work vectors
  mutable std::vector<double> residual;
  mutable std::vector<double> coarseB;
  mutable std::vector<double> coarseX;

  /// One Gauss-Seidel sweep on a x = b, forward or backward (the pair keeps the cycle symmetric,
  /// as conjugate gradients need).
  void smooth(const std::vector<double>& b, std::vector<double>& x, bool forward) const
  {
    for (int k = 0; k < a.n; ++k)
    {
      const auto r = static_cast<std::size_t>(forward ? k : a.n - 1 - k);
      double sum = b[r];
      for (int e = a.start[r]; e < a.start[r + 1]; ++e)
      {
        const auto at = static_cast<std::size_t>(e);
        sum -= a.value[at] * x[static_cast<std::size_t>(a.column[at])];
      }
      x[r] += sum * inverseDiagonal[r];
    }
  }

  /// The smoothed prolongation P = (I - omega D_F^-1 A_F) P_tentative, A_F being A with its weak
  /// couplings added to the diagonal (they would fill the coarse matrices in) and omega =
  /// 4 / (3 rho(D^-1 A)), rho by power iterations from a fixed vector.
  void buildTransfer(const std::vector<std::vector<char>>& strong, const std::vector<int>& group, int count)
  {
    const auto n = static_cast<std::size_t>(a.n);
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i)
      v[i] = 1.0 + static_cast<double>(i % 7) / 7.0;
    std::vector<double> w(n);
    double rho = 1;
    for (int it = 0; it < 12; ++it)
    {
      multiply(a, v, w);
      for (std::size_t i = 0; i < n; ++i)
        w[i] *= inverseDiagonal[i];
      const double norm = std::sqrt(dot(w, w));
      rho = norm / std::sqrt(dot(v, v));
      for (std::size_t i = 0; i < n; ++i)
        v[i] = w[i] / norm;
    }
    const double omega = 4.0 / (3.0 * rho);
    interpolation = SparseRows{};
    interpolation.n = a.n;
    std::vector<int> slot(static_cast<std::size_t>(count), -1);
    std::vector<std::pair<int, double>> row;
    for (std::size_t i = 0; i < n; ++i)
    {
      double lumped = 0;
      for (int e = a.start[i]; e < a.start[i + 1]; ++e)
        if (static_cast<std::size_t>(a.column[static_cast<std::size_t>(e)]) == i ||
            !strong[i][static_cast<std::size_t>(e - a.start[i])])
          lumped += a.value[static_cast<std::size_t>(e)];
      row.clear();
      const auto add = [&](int g, double value) {
        int& s = slot[static_cast<std::size_t>(g)];
        if (s < 0)
        {
          s = static_cast<int>(row.size());
          row.emplace_back(g, 0.0);
        }
        row[static_cast<std::size_t>(s)].second += value;
      };
      add(group[i], 1.0 - omega);
      for (int e = a.start[i]; e < a.start[i + 1]; ++e)
        if (strong[i][static_cast<std::size_t>(e - a.start[i])])
          add(group[static_cast<std::size_t>(a.column[static_cast<std::size_t>(e)])],
              -omega * a.value[static_cast<std::size_t>(e)] / lumped);
      for (const auto& entry : row)
        slot[static_cast<std::size_t>(entry.first)] = -1;
      appendSorted(interpolation, row);
    }
    restriction = transpose(interpolation, count);
    residual.resize(n);
    coarseB.resize(static_cast<std::size_t>(count));
    coarseX.resize(static_cast<std::size_t>(count));
  }
};

struct Multigrid::Coarse
{
  Eigen::LLT<Eigen::MatrixXd> factor;
};

Multigrid::Multigrid(SparseRows a)
{
  for (std::size_t l = 0;; ++l)
  {
    auto level = std::make_unique<Level>();
    level->a = std::move(a);
    const SparseRows& m = level->a;
    const auto n = static_cast<std::size_t>(m.n);
    level->inverseDiagonal.assign(n, 0.0);
    std::vector<double> largest(n, 0.0); // largest coupling of each row
    for (std::size_t r = 0; r < n; ++r)
      for (int e = m.start[r]; e < m.start[r + 1]; ++e)
      {
        const auto c = static_cast<std::size_t>(m.column[static_cast<std::size_t>(e)]);
        if (c == r)
          level->inverseDiagonal[r] = 1.0 / m.value[static_cast<std::size_t>(e)];
        else
          largest[r] = std::max(largest[r], -m.value[static_cast<std::size_t>(e)]);
      }
    for (std::size_t r = 0; r < n; ++r)
      if (!(level->inverseDiagonal[r] > 0) || !std::isfinite(level->inverseDiagonal[r]))
        throw std::runtime_error("multigrid: row " + std::to_string(r) + " of level " + std::to_string(l) +
                                 " has no positive diagonal");
    if (m.n <= kCoarsest || l + 1 == kMaxLevels)
    {
      levels_.push_back(std::move(level));
      break;
    }
    std::vector<std::vector<char>> strong(n);
    for (std::size_t r = 0; r < n; ++r)
      for (int e = m.start[r]; e < m.start[r + 1]; ++e)
      {
        const auto c = static_cast<std::size_t>(m.column[static_cast<std::size_t>(e)]);
        const double v = -m.value[static_cast<std::size_t>(e)];
        strong[r].push_back(c != r && (v >= kStrength * largest[r] || v >= kStrength * largest[c]) ? 1 : 0);
      }
    auto [group, count] = aggregate(m, strong);
    if (count > kMinCoarsening * m.n)
    {
      levels_.push_back(std::move(level));
      break;
    }
    level->buildTransfer(strong, group, count);
    a = multiply(level->restriction, multiply(m, level->interpolation, count), count);
    levels_.push_back(std::move(level));
  }
  const SparseRows& last = levels_.back()->a;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(last.n, last.n);
  for (int r = 0; r < last.n; ++r)
    for (int e = last.start[static_cast<std::size_t>(r)]; e < last.start[static_cast<std::size_t>(r) + 1]; ++e)
      dense(r, last.column[static_cast<std::size_t>(e)]) = last.value[static_cast<std::size_t>(e)];
  coarse_ = std::make_unique<Coarse>();
  coarse_->factor.compute(dense);
  if (coarse_->factor.info() != Eigen::Success)
    throw std::runtime_error("multigrid: the coarsest matrix is not positive definite (a group of pores "
                             "connected to no imposed pressure)");
}

Multigrid::~Multigrid() = default;

double Multigrid::operatorComplexity() const
{
  double total = 0;
  for (const auto& l : levels_)
    total += static_cast<double>(l->a.value.size());
  return total / static_cast<double>(levels_.front()->a.value.size());
}

void Multigrid::cycle(std::size_t l, const std::vector<double>& b, std::vector<double>& x) const
{
  const Level& level = *levels_[l];
  if (l + 1 == levels_.size())
  {
    const Eigen::Map<const Eigen::VectorXd> rhs(b.data(), level.a.n);
    Eigen::Map<Eigen::VectorXd>(x.data(), level.a.n) = coarse_->factor.solve(rhs);
    return;
  }
  std::fill(x.begin(), x.end(), 0.0);
  for (int k = 0; k < kSweeps; ++k)
    level.smooth(b, x, true);
  multiply(level.a, x, level.residual);
  for (std::size_t r = 0; r < b.size(); ++r)
    level.residual[r] = b[r] - level.residual[r];
  multiply(level.restriction, level.residual, level.coarseB);
  cycle(l + 1, level.coarseB, level.coarseX);
  multiply(level.interpolation, level.coarseX, x, true);
  for (int k = 0; k < kSweeps; ++k)
    level.smooth(b, x, false);
}

int Multigrid::solve(const std::vector<double>& b, std::vector<double>& x, double tolerance, int maxIterations) const
{
  const SparseRows& a = levels_.front()->a;
  const auto n = static_cast<std::size_t>(a.n);
  std::vector<double> r(n), z(n), p(n), q(n);
  multiply(a, x, q);
  for (std::size_t i = 0; i < n; ++i)
    r[i] = b[i] - q[i];
  const double target = tolerance * std::sqrt(dot(b, b));
  if (std::sqrt(dot(r, r)) <= target)
    return 0;
  cycle(0, r, z);
  p = z;
  double rz = dot(r, z);
  for (int it = 1; it <= maxIterations; ++it)
  {
    multiply(a, p, q);
    const double alpha = rz / dot(p, q);
    for (std::size_t i = 0; i < n; ++i)
    {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    if (std::sqrt(dot(r, r)) <= target)
      return it;
    cycle(0, r, z);
    const double next = dot(r, z);
    const double beta = next / rz;
    rz = next;
    for (std::size_t i = 0; i < n; ++i)
      p[i] = z[i] + beta * p[i];
  }
  throw std::runtime_error("multigrid: conjugate gradients did not converge in " + std::to_string(maxIterations) +
                           " iterations");
}
} // namespace talus::flow::pore
