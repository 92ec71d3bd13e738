#pragma once

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace talus::dem
{
/// A contact-physics parameter given per pair of materials, as Yade's MatchMaker reaches a
/// physics functor: values for listed pairs of material ids (in either order), and for the
/// other pairs a fallback (Yade's algo 'val' or 'zero') or none (Yade's 'avg', 'min', 'max',
/// 'harmAvg' need the materials' own values, which its ViscElPhys functor does not pass: such
/// a pair is an error).
struct PairParameter
{
  bool given = false; ///< the functor was given this parameter
  std::map<std::pair<int, int>, double> matches;
  std::optional<double> fallback;

  /// The value for materials a and b; empty if the pair has none.
  /// @param a, b material indices, either order
  /// @return the listed value, else the fallback, else empty
  [[nodiscard]] std::optional<double> at(int a, int b) const
  {
    const auto it = matches.find({std::min(a, b), std::max(a, b)});
    if (it != matches.end())
      return it->second;
    return fallback;
  }
};

/// The first error met while setting up contacts, reported when the step's contacts are done
/// (the set-up runs in parallel loops that must not throw): a pair a MatchMaker has no value
/// for, materials that do not go together.
struct DeferredFailure
{
  std::atomic<bool> failed{false};
  std::mutex failureLock;
  std::string failure;

  /// Record an error (thread-safe); only the first one is kept.
  /// @param what the message thrown later
  void fail(const std::string& what)
  {
    std::lock_guard<std::mutex> lock(failureLock);
    if (!failed.exchange(true))
      failure = what;
  }
  /// Report the recorded error, if any, and clear it (called serially after the loop).
  /// @throws std::runtime_error with the first recorded message
  void throwIfFailed()
  {
    if (failed.exchange(false))
      throw std::runtime_error(failure);
  }
};
} // namespace talus::dem
