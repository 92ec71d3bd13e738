#pragma once
// When heat conduction runs and with which step, against the DEM step (Yade's tsSafetyFactor
// policy of ThermalEngine, with sub-steps where Yade would run past the stability limit).
#include "flow/thermal/HeatModel.h"

namespace talus::flow::thermal
{
/// Runs a HeatModel (ParticleConduction, or PoreHeat with the pore fluid) alongside the DEM steps.
///
/// - `tsSafetyFactor` <= 0: conduction every DEM step with the DEM step; a step above the
///   stable one stops the run (std::domain_error naming the limit and the body) rather than
///   letting the temperatures oscillate and blow up.
/// - `tsSafetyFactor` > 0 (Yade's default 0.8): the thermal step aims at tsSafetyFactor times
///   the stable one. When that spans N >= 1 DEM steps, conduction runs every N steps with the
///   time elapsed since its last run (Yade's conductionIterPeriod, re-estimated at each run as
///   the contacts change); when it is shorter than the DEM step, conduction runs in as many
///   equal sub-steps per DEM step as needed (Talus: Yade would run one unstable step).
class ConductionSchedule
{
public:
  double tsSafetyFactor = 0.8;

  /// One DEM step of `dt` seconds.
  /// @param model the heat model advanced (computeRates, then applyRates over the span or its
  ///        sub-steps when a conduction run is due)
  /// @param dt the DEM step (s)
  /// @throws std::domain_error if tsSafetyFactor <= 0 and dt exceeds the stable step
  void step(HeatModel& model, double dt);

  /// DEM steps between conduction runs (Yade's getConductionIterPeriod).
  [[nodiscard]] int conductionIterPeriod() const { return period_; }
  /// Time covered by the last conduction run (Yade's getThermalDT).
  [[nodiscard]] double thermalDT() const { return thermalDT_; }
  /// Stable step at the last conduction run (Yade's getMaxTimeStep).
  [[nodiscard]] double maxTimeStep() const { return maxTimeStep_; }
  /// Sub-steps of the last conduction run (1 unless its step was above the stable one).
  [[nodiscard]] int substeps() const { return substeps_; }

  /// The counters, for checkpoints: runs so far, DEM steps and time since the last run.
  struct Counters
  {
    long long runs = 0;
    int sinceRun = 0, period = 1;
    double timeSinceRun = 0, thermalDT = 0, maxTimeStep = 0;
  };
  /// The schedule's state, to be stored with a checkpoint.
  [[nodiscard]] Counters counters() const;
  /// Restore the state counters() gave (a checkpoint loaded): the next run comes when it would have.
  /// @param c the stored counters
  void setCounters(const Counters& c);

private:
  void conduct(HeatModel& model, double span);

  long long runs_ = 0;
  int sinceRun_ = 0, period_ = 1, substeps_ = 1;
  double timeSinceRun_ = 0, thermalDT_ = 0, maxTimeStep_ = 0;
};
} // namespace talus::flow::thermal
