#include "flow/thermal/ConductionSchedule.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace talus::flow::thermal
{
void ConductionSchedule::step(HeatModel& model, double dt)
{
  if (tsSafetyFactor <= 0)
  {
    model.computeRates();
    if (dt > model.stableTimeStep())
    {
      std::ostringstream message;
      message << "ThermalEngine: the thermal step O.dt = " << dt << " s exceeds the stable conduction step "
              << model.stableTimeStep() << " s (" << model.limitingPart()
              << ": heat capacity / sum of its conductances); with tsSafetyFactor <= 0 the thermal step is "
                 "O.dt: lower O.dt or set tsSafetyFactor in (0, 1] to let ThermalEngine choose its step";
      throw std::domain_error(message.str());
    }
    model.applyRates(dt);
    maxTimeStep_ = model.stableTimeStep();
    thermalDT_ = dt;
    period_ = substeps_ = 1;
    ++runs_;
    sinceRun_ = 0;
    timeSinceRun_ = 0;
    return;
  }
  timeSinceRun_ += dt;
  ++sinceRun_;
  // As Yade: the first call conducts over its own step, later ones once `period_` steps passed.
  if (runs_ > 0 && sinceRun_ < period_)
    return;
  conduct(model, runs_ == 0 ? dt : timeSinceRun_);
  period_ = std::max(1, static_cast<int>(std::floor(tsSafetyFactor * maxTimeStep_ / dt)));
  sinceRun_ = 0;
  timeSinceRun_ = 0;
}

void ConductionSchedule::conduct(HeatModel& model, double span)
{
  model.computeRates();
  maxTimeStep_ = model.stableTimeStep();
  const double target = tsSafetyFactor * maxTimeStep_;
  substeps_ = span > target ? static_cast<int>(std::ceil(span / target)) : 1;
  const double h = span / substeps_;
  for (int s = 0; s < substeps_; ++s)
  {
    if (s > 0)
      model.computeRates();
    model.applyRates(h);
  }
  thermalDT_ = span;
  ++runs_;
}

ConductionSchedule::Counters ConductionSchedule::counters() const
{
  return {runs_, sinceRun_, period_, timeSinceRun_, thermalDT_, maxTimeStep_};
}

void ConductionSchedule::setCounters(const Counters& c)
{
  runs_ = c.runs;
  sinceRun_ = c.sinceRun;
  period_ = c.period;
  timeSinceRun_ = c.timeSinceRun;
  thermalDT_ = c.thermalDT;
  maxTimeStep_ = c.maxTimeStep;
}
} // namespace talus::flow::thermal
