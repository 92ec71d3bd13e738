#pragma once

#include "dem/control/TriaxialStressController.h"

#include <functional>
#include <string>

namespace talus::dem
{
/// Yade's TriaxialCompressionEngine: a TriaxialStressController driven by a state machine that
/// runs a whole triaxial test.
///
/// 1. isoCompaction: all walls (or the spheres' growth, internalCompaction) bring the mean
///    stress to sigmaIsoCompaction;
/// 2. isoUnloading (only if autoUnload and sigmaLateralConfinement differs): the same down to
///    sigmaLateralConfinement;
/// 3. triaxLoading (if autoCompressionActivation): the lateral walls keep
///    sigmaLateralConfinement, top and bottom approach each other at a strain rate that relaxes
///    towards strainRate, until |strain[1]| reaches epsilonMax.
/// A phase ends when unbalancedForce <= StabilityCriterion and the mean stress is within 0.5 %
/// of its goal, tested every testEquilibriumInterval steps. On entering the deviatoric phase the
/// strains restart from zero and, if frictionAngleDegree > 0, the contacts get that friction.
/// fixedPorosityCompaction moves all six walls at strainRate (Yade's fixedPoroCompaction).
///
/// The state numbers and the order of the tests are Yade's, so that a state saved by a script
/// and changed by hand (currentState, sigmaIsoCompaction) continues as it would in Yade.
class TriaxialCompressionEngine : public TriaxialStressController
{
public:
  /// Yade's state numbers (TriaxialCompressionEngine.currentState).
  enum State : int
  {
    uninitialized = 0,
    isoCompaction = 1,
    isoUnloading = 2,
    triaxLoading = 3,
    fixedPorosityCompaction = 4,
    limbo = 5
  };

  void run(Scene& scene) override;
  [[nodiscard]] std::string typeName() const override { return "TriaxialCompressionEngine"; }

  /// Go to `next`, with Yade's side effects (goals, friction, reference sizes, wall switches);
  /// a transition Yade does not define throws std::logic_error naming both states.
  /// @param next the state to enter (a State value)
  /// @throws std::logic_error for a transition from currentState that Yade does not define
  void doStateTransition(Scene& scene, int next);
  /// Yade's state name ("STATE_ISO_COMPACTION", ...).
  /// @param state a State value
  /// @return its name; "<unknown state N>" for a value outside State
  static std::string stateName(int state);

  // parameters (Yade's names and defaults)
  double strainRate = 0;
  double StabilityCriterion = 0.001;
  Vec3 translationAxis = Vec3(0, 1, 0);
  bool autoCompressionActivation = true;
  bool autoUnload = true;
  bool autoStopSimulation = false;
  int testEquilibriumInterval = 20;
  double sigmaIsoCompaction = 1;
  double sigmaLateralConfinement = 1;
  std::string Key;
  bool noFiles = false;
  double frictionAngleDegree = -1;
  double epsilonMax = 0.5;
  bool fixedPoroCompaction = false;
  double fixedPorosity = 0;
  bool isAxisymetric = true;

  // state and read-outs
  int currentState = uninitialized;
  int previousState = uninitialized;
  double currentStrainRate = 0;
  double UnbalancedForce = 1;
  double sigma_iso = 0;
  double previousSigmaIso = 0;
  double maxStress = 0;
  double uniaxialEpsilonCurr = 1;
  bool firstRun = true;

  /// Called with a file stem ("./<Key>_<phase>_<iter>_<state>") when Yade would save the
  /// simulation (.xml) and the spheres (.spheres): the Python layer writes them.
  std::function<void(const std::string&)> saveHook;

private:
  void updateParameters(Scene& scene);
  /// The end of the isotropic phase to name files after ("Compacted", "Unloaded").
  std::string phase1End_ = "Compacted";
  bool saveSimulation_ = false;
};

} // namespace talus::dem
