#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace talus::dem
{
/// Wall time spent in the labelled stages of one engine (Yade's TimingDeltas): an engine calls
/// start() on entry and checkpoint("stage") after each stage; with timing off (O.timingEnabled
/// false) both return at once, so the hot loops pay one branch per step.
class TimingDeltas
{
public:
  /// Mark the engine's entry.
  /// @param enabled the scene's timingEnabled: false makes checkpoint() return at once
  void start(bool enabled)
  {
    on_ = enabled;
    if (on_)
    {
      next_ = 0;
      last_ = Clock::now();
    }
  }

  /// Add the time since the previous checkpoint (or start) to stage `label`. Stages are kept
  /// in the order an engine passes them; a label is looked up at its usual position first.
  /// @param label the stage's name (compared by content; a new one is appended)
  void checkpoint(const char* label)
  {
    if (!on_)
      return;
    const Clock::time_point now = Clock::now();
    if (next_ >= labels.size() || labels[next_] != label)
      next_ = slot(label);
    nsec[next_] += std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_).count();
    ++count[next_];
    ++next_;
    last_ = now;
  }

  /// Add `nanoseconds` to stage `label` as one pass (a stage timed by the step's scheduler).
  /// @param label the stage's name (a new one is appended)
  /// @param nanoseconds the stage's wall time (ns)
  void add(const char* label, std::int64_t nanoseconds)
  {
    const std::size_t k = slot(label);
    nsec[k] += nanoseconds;
    ++count[k];
  }

  /// Forget every stage (Yade's timing.reset()).
  void reset()
  {
    labels.clear();
    nsec.clear();
    count.clear();
  }

  std::vector<std::string> labels;
  std::vector<std::int64_t> nsec;  ///< total nanoseconds per stage
  std::vector<std::int64_t> count; ///< passes per stage

private:
  using Clock = std::chrono::steady_clock;

  std::size_t slot(const char* label)
  {
    for (std::size_t k = 0; k < labels.size(); ++k)
      if (labels[k] == label)
        return k;
    labels.emplace_back(label);
    nsec.push_back(0);
    count.push_back(0);
    return labels.size() - 1;
  }

  bool on_ = false;
  std::size_t next_ = 0;
  Clock::time_point last_;
};
} // namespace talus::dem
