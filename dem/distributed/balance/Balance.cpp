#include "dem/distributed/balance/Balance.h"

#include "dem/core/Contacts.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace talus::dem::distributed
{
namespace
{
/// Intervals of every rank the model is fitted to: enough to average out one interval's noise,
/// few enough to follow a scene whose contacts change (a silo emptying).
constexpr std::size_t fittedIntervals = 16;
} // namespace

void Balance::setThreshold(double threshold)
{
  if (!(threshold >= 1.0))
    throw std::invalid_argument("rebalanceThreshold " + std::to_string(threshold)
                                + " is below 1 (the slowest process's compute time over the mean above which the "
                                  "processes partition again; infinity: never)");
  threshold_ = threshold;
}

void Balance::begin(double cpu, double waitCpu, std::int64_t iter)
{
  cpu0_ = cpu;
  wait0_ = waitCpu;
  iter0_ = iter;
}

bool Balance::measure(MPI_Comm comm, double cpu, double waitCpu, std::int64_t iter, std::int64_t spheres,
                      std::int64_t contacts)
{
  const std::int64_t steps = iter - iter0_;
  // A re-detection in the step that split the scene (or loaded it) closes no interval: nothing
  // was computed since. `steps` is the same on every rank, so all skip alike.
  if (steps <= 0)
    return false;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const double seconds = openSeconds(cpu, waitCpu);
  const std::array<double, 3> mine{seconds, static_cast<double>(spheres), static_cast<double>(contacts)};
  std::vector<double> all(3 * static_cast<std::size_t>(ranks));
  MPI_Allgather(mine.data(), 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, comm);

  double slowest = 0, total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    const double* s = all.data() + 3 * r;
    slowest = std::max(slowest, s[0]);
    total += s[0];
    recent_.push_back({s[0] / static_cast<double>(steps), s[1], s[2]});
  }
  const std::size_t kept = fittedIntervals * static_cast<std::size_t>(ranks);
  if (recent_.size() > kept)
    recent_.erase(recent_.begin(), recent_.end() - static_cast<std::ptrdiff_t>(kept));
  fit();
  calibrate(all, steps, rank);

  const double mean = total / ranks;
  Interval interval{iter, steps, mean > 0 ? slowest / mean : 1.0, false};
  stats_.computeSeconds += seconds;
  stats_.slowestSeconds += slowest;
  stats_.meanSeconds += mean;
  if (!stats_.intervals.empty() && stats_.intervals.back().rebalanced)
    stats_.imbalanceAfter = interval.imbalance;
  interval.rebalanced = interval.imbalance > threshold_;
  if (interval.rebalanced)
  {
    ++stats_.rebalances;
    stats_.imbalanceBefore = interval.imbalance;
    stats_.imbalanceAfter = 0;
  }
  stats_.intervals.push_back(interval);
  return interval.rebalanced;
}

void Balance::fit()
{
  double nn = 0, nc = 0, cc = 0, nt = 0, ct = 0;
  for (const Sample& s : recent_)
  {
    nn += s.spheres * s.spheres;
    nc += s.spheres * s.contacts;
    cc += s.contacts * s.contacts;
    nt += s.spheres * s.seconds;
    ct += s.contacts * s.seconds;
  }
  // The two costs apart only when the ranks' contacts per sphere differ enough (the normal
  // equations' determinant is then a fair share of its largest possible value).
  const double det = nn * cc - nc * nc;
  if (det > 1e-4 * nn * cc)
  {
    const double perBody = (nt * cc - ct * nc) / det, perContact = (nn * ct - nc * nt) / det;
    if (perBody > 0 && perContact >= 0)
      contactRatio_ = perContact / perBody;
  }
  // The scale at that ratio: least squares of seconds = perBody (spheres + ratio contacts).
  double uu = 0, ut = 0;
  for (const Sample& s : recent_)
  {
    const double u = s.spheres + contactRatio_ * s.contacts;
    uu += u * u;
    ut += u * s.seconds;
  }
  stats_.perBody = uu > 0 ? ut / uu : 0;
  stats_.perContact = contactRatio_ * stats_.perBody;
}

void Balance::calibrate(std::span<const double> all, std::int64_t steps, int rank)
{
  // Within a factor of 2 either way: one short interval's noise moves the cuts a little, not far.
  const std::size_t ranks = all.size() / 3;
  std::vector<double> factor(ranks, 0.0);
  double sum = 0;
  std::size_t counted = 0;
  for (std::size_t r = 0; r < ranks; ++r)
  {
    const double modelled = stats_.perBody * all[3 * r + 1] + stats_.perContact * all[3 * r + 2];
    if (modelled > 0 && all[3 * r] > 0)
    {
      factor[r] = all[3 * r] / static_cast<double>(steps) / modelled;
      sum += factor[r];
      ++counted;
    }
  }
  const double mine = factor[static_cast<std::size_t>(rank)];
  ownFactor_ = counted > 0 && mine > 0 ? std::clamp(mine * static_cast<double>(counted) / sum, 0.5, 2.0) : 1.0;
}

std::vector<double> Balance::weights(const Contacts& contacts, std::span<const std::int64_t> rows,
                                     std::span<const std::uint8_t> replicated) const
{
  std::vector<std::int64_t> slot(replicated.size(), -1);
  for (std::size_t k = 0; k < rows.size(); ++k)
    slot[static_cast<std::size_t>(rows[k])] = static_cast<std::int64_t>(k);
  std::vector<double> w(rows.size(), 1.0);
  for (const Contact& c : contacts.list)
  {
    const auto r1 = static_cast<std::size_t>(c.id1), r2 = static_cast<std::size_t>(c.id2);
    const double share = replicated[r1] || replicated[r2] ? 1.0 : 0.5;
    for (const std::size_t r : {r1, r2})
      if (slot[r] >= 0)
        w[static_cast<std::size_t>(slot[r])] += contactRatio_ * share;
  }
  for (double& x : w)
    x *= ownFactor_;
  return w;
}
} // namespace talus::dem::distributed
