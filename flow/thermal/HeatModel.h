#pragma once
// What the thermal time stepping (ConductionSchedule) advances: an explicit heat model split into
// the rates of the current temperatures and their application over a step.
#include <string>

namespace talus::flow::thermal
{
/// An explicit heat model: each step computes the rates of the current temperatures, which
/// also give the stable step, then applies them.
class HeatModel
{
public:
  virtual ~HeatModel() = default;
  /// Heat rates and conductance sums of the current temperatures (also gives stableTimeStep).
  virtual void computeRates() = 0;
  /// Advance the temperatures by `dt` (s) with the rates of the last computeRates.
  /// @param dt the step (s); at most stableTimeStep() for a step without overshoot
  virtual void applyRates(double dt) = 0;
  /// The largest stable step of the explicit scheme at the last computeRates (+inf: no exchange).
  [[nodiscard]] virtual double stableTimeStep() const = 0;
  /// What limits stableTimeStep, for messages ("sphere 12", "pore 40").
  [[nodiscard]] virtual std::string limitingPart() const = 0;
};
} // namespace talus::flow::thermal
