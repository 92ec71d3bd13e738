#pragma once

#include "dem/distributed/BodyRows.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace talus::dem
{
struct Contacts;
}

namespace talus::dem::distributed
{
/// The load of each rank measured between two re-detections, the per-body cost model fitted to
/// it, and the decision to partition again.
///
/// A rank's compute time over an interval is its CPU seconds less those it spent waiting in MPI
/// calls (the ghost updates', the reductions') and in the re-detection's migration: the work it
/// did for its own share, which other work on the machine does not lengthen as it does wall
/// seconds. Its work is its own spheres and the contacts it computes. At each re-detection every
/// rank's (seconds per step, spheres, contacts) is gathered: the imbalance is the slowest rank's
/// time over the mean, and the model "seconds per step = perBody x spheres + perContact x
/// contacts" is fitted by least squares to the last intervals of every rank. When the imbalance
/// passes the threshold, the domain partitions again with each body's modelled cost as its
/// weight. Every rank decides from the same gathered numbers: all decide alike.
class Balance
{
public:
  /// One measurement (a re-detection), the same on every rank.
  struct Interval
  {
    std::int64_t iter = 0;   ///< the step of the re-detection closing it
    std::int64_t steps = 0;  ///< steps it spanned
    double imbalance = 1;    ///< slowest rank's compute time over the mean
    bool rebalanced = false; ///< whether the domain partitioned again there
  };
  /// What the balance measured so far (this rank's seconds; the rest the same on every rank).
  struct Stats
  {
    double computeSeconds = 0;    ///< this rank's compute CPU seconds over the intervals measured
    double slowestSeconds = 0;    ///< the sum over the intervals of the slowest rank's compute seconds
    double meanSeconds = 0;       ///< the sum over the intervals of the ranks' mean compute seconds
    std::int64_t rebalances = 0;  ///< partitions again
    double imbalanceBefore = 0;   ///< the imbalance that set off the last rebalance (0: none yet)
    double imbalanceAfter = 0;    ///< the imbalance of the interval after it (0: not measured yet)
    double perBody = 0, perContact = 0; ///< the fitted model (seconds per step)
    std::vector<Interval> intervals;    ///< every measurement
  };

  /// @param threshold the imbalance above which the domain partitions again (>= 1; infinity: never)
  explicit Balance(double threshold) : threshold_(threshold) {}

  /// An interval starts (after a re-detection, or the split).
  /// @param cpu this process's CPU seconds now
  /// @param waitCpu its CPU seconds spent waiting in MPI calls so far
  /// @param iter the scene's step
  void begin(double cpu, double waitCpu, std::int64_t iter);

  /// Close the interval (collective: every rank calls it at the same re-detection): gather the
  /// ranks' loads, fit the model, decide.
  /// @param comm the domain's ranks
  /// @param cpu, waitCpu, iter as begin's, now
  /// @param spheres the rank's own spheres
  /// @param contacts the contacts it computes
  /// @return whether to partition again (the same on every rank)
  bool measure(MPI_Comm comm, double cpu, double waitCpu, std::int64_t iter, std::int64_t spheres,
               std::int64_t contacts);

  /// The cost of each of the given rows' bodies (Zoltan's weights): perBody plus perContact for
  /// each contact with a replicated body (a wall, a facet: computed by this rank alone) and half
  /// of it for each contact with another sphere (a contact computed once between two bodies of
  /// one rank), relative to perBody; times this rank's last measured time over its modelled
  /// cost, relative to the other ranks' (what the model leaves out: the contacts computed twice
  /// across a region's faces, a slower core), so that Zoltan evens the measured times.
  /// @param contacts the scene's contact list (its records' rows)
  /// @param rows the rows weighted, ascending
  /// @param replicated per row of the scene: whether it is a wall or facet
  /// @return one weight per row of `rows`
  [[nodiscard]] std::vector<double> weights(const Contacts& contacts, std::span<const std::int64_t> rows,
                                            std::span<const std::uint8_t> replicated) const;

  [[nodiscard]] const Stats& stats() const { return stats_; }
  /// This rank's compute seconds in the interval still open (since the last re-detection).
  /// @param cpu, waitCpu as begin's, now
  [[nodiscard]] double openSeconds(double cpu, double waitCpu) const
  {
    return std::max(0.0, (cpu - cpu0_) - (waitCpu - wait0_));
  }
  [[nodiscard]] double threshold() const { return threshold_; }
  /// @param threshold as the constructor's
  /// @throws std::invalid_argument below 1 (or NaN)
  void setThreshold(double threshold);

private:
  /// One rank's interval: its seconds per step, spheres and contacts.
  struct Sample
  {
    double seconds, spheres, contacts;
  };
  /// Least squares of the model over the recent samples; kept when the samples cannot tell the
  /// two costs apart (every rank with the same contacts per sphere) or give a negative cost.
  void fit();
  /// ownFactor_ from the ranks' gathered (seconds, spheres, contacts), after fit().
  void calibrate(std::span<const double> all, std::int64_t steps, int rank);

  double threshold_;
  double cpu0_ = 0, wait0_ = 0;
  std::int64_t iter0_ = 0;
  std::vector<Sample> recent_; ///< the last intervals' samples, every rank's
  /// A contact's cost in bodies' costs until the samples tell: as contactWeights (1 + contacts).
  double contactRatio_ = 1;
  /// This rank's measured time over its modelled cost, over the mean of the ranks' (1 until measured).
  double ownFactor_ = 1;
  Stats stats_;
};
} // namespace talus::dem::distributed
