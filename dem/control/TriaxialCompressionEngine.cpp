#include "dem/control/TriaxialCompressionEngine.h"

#include "dem/measure/Measurements.h"
#include "dem/impose/SampleOperations.h"
#include "dem/core/Scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace talus::dem
{
std::string TriaxialCompressionEngine::stateName(int state)
{
  switch (state)
  {
  case uninitialized: return "STATE_UNINITIALIZED";
  case isoCompaction: return "STATE_ISO_COMPACTION";
  case isoUnloading: return "STATE_ISO_UNLOADING";
  case triaxLoading: return "STATE_TRIAX_LOADING";
  case fixedPorosityCompaction: return "STATE_FIXED_POROSITY_COMPACTION";
  case limbo: return "STATE_LIMBO";
  default: return "<unknown state " + std::to_string(state) + ">";
  }
}

void TriaxialCompressionEngine::doStateTransition(Scene& scene, int next)
{
  const auto freezeSizes = [this] {
    height0 = height;
    depth0 = depth;
    width0 = width;
  };
  const auto frictionForLoading = [&] {
    if (frictionAngleDegree > 0)
      setContactFriction(scene, frictionAngleDegree * M_PI / 180.0);
  };
  if (next == isoCompaction)
  {
    sigma_iso = previousSigmaIso = sigmaIsoCompaction;
  }
  else if (next == triaxLoading)
  {
    sigma_iso = previousSigmaIso = sigmaLateralConfinement;
    internalCompaction = false;
    frictionForLoading();
    freezeSizes();
    wallActivated[Bottom] = wallActivated[Top] = false; // moved by run() at the strain rate
    if (!firstRun && !noFiles)
      saveSimulation_ = true;
    phase1End_ = "Unloaded";
  }
  else if (currentState == isoCompaction && next == isoUnloading)
  {
    sigma_iso = previousSigmaIso = sigmaIsoCompaction = sigmaLateralConfinement;
    internalCompaction = false; // unloading does not change the sizes
    frictionForLoading();
    if (!firstRun && !noFiles)
      saveSimulation_ = true;
    phase1End_ = "Compacted";
  }
  else if ((currentState == isoCompaction || currentState == isoUnloading) && next == limbo)
  {
    internalCompaction = false;
    frictionForLoading();
    freezeSizes();
    if (!firstRun && !noFiles)
      saveSimulation_ = true;
    phase1End_ = currentState == isoCompaction ? "compacted" : "unloaded";
  }
  else if (next == fixedPorosityCompaction)
  {
    internalCompaction = false;
    wallActivated.fill(false); // all six walls move at the strain rate
  }
  else
    throw std::logic_error("TriaxialCompressionEngine: no transition from " + stateName(currentState) + " to "
                           + stateName(next));
  currentState = previousState = next;
}

void TriaxialCompressionEngine::updateParameters(Scene& scene)
{
  UnbalancedForce = unbalancedForce(scene, sceneGravity(scene));
  // Yade's test, kept as written: with autoCompressionActivation it also runs while loading.
  if (!(currentState == isoCompaction || currentState == isoUnloading || currentState == fixedPorosityCompaction
        || autoCompressionActivation))
    return;
  // NaN (no contact force yet) compares false: not stable.
  const bool stable = UnbalancedForce <= StabilityCriterion && std::abs((meanStress - sigma_iso) / sigma_iso) < 0.005;
  if (!stable || fixedPoroCompaction)
    return;
  if (currentState == isoCompaction && autoUnload && sigmaLateralConfinement != sigmaIsoCompaction)
    doStateTransition(scene, isoUnloading);
  else if ((currentState == isoCompaction || currentState == isoUnloading || currentState == limbo)
           && autoCompressionActivation)
    doStateTransition(scene, triaxLoading);
  else
    return;
  computeStressStrain(scene);
}

void TriaxialCompressionEngine::run(Scene& scene)
{
  if (firstRun)
  {
    // A fresh engine, or one loaded from a file whose state or goal was edited by hand.
    if ((sigmaIsoCompaction != previousSigmaIso || currentState == uninitialized || currentState == limbo)
        && currentState != triaxLoading && !fixedPoroCompaction)
      doStateTransition(scene, isoCompaction);
    if (previousState != triaxLoading && currentState == triaxLoading)
      doStateTransition(scene, triaxLoading);
    if (fixedPorosity < 1 && currentState == uninitialized && fixedPoroCompaction)
      doStateTransition(scene, fixedPorosityCompaction);
    previousState = currentState;
    previousSigmaIso = sigma_iso;
    firstRun = false;
  }
  if (testEquilibriumInterval < 1)
    throw std::invalid_argument("TriaxialCompressionEngine: testEquilibriumInterval must be >= 1, got "
                                + std::to_string(testEquilibriumInterval));
  if (scene.iter % testEquilibriumInterval == 0)
  {
    updateParameters(scene);
    maxStress = std::max(maxStress, -stress[Top][1]);
  }
  if (saveSimulation_)
  {
    saveSimulation_ = false;
    if (!noFiles && saveHook)
      saveHook("./" + Key + "_" + phase1End_ + "_" + std::to_string(scene.iter) + "_" + std::to_string(currentState));
  }
  if (isAxisymetric || internalCompaction)
  {
    if (stressMask & 1)
      goal1 = sigma_iso;
    if (stressMask & 2)
      goal2 = sigma_iso;
    if (stressMask & 3) // sic: Yade tests bits 1 and 2 here, not bit 4
      goal3 = sigma_iso;
  }

  TriaxialStressController::run(scene);
  if (currentState == limbo && autoStopSimulation)
  {
    scene.pause();
    return;
  }

  Bodies& b = scene.bodies;
  const std::array<std::size_t, 6> rows = wallRows(scene);
  auto shift = [&](int wall, const Vec3& by) { b.pos[rows[static_cast<std::size_t>(wall)]] += by; };
  if (currentState == triaxLoading && std::abs(epsilonMax) > std::abs(strain[1]))
  {
    if (currentStrainRate != strainRate)
      currentStrainRate += (strainRate - currentStrainRate) * 0.0003;
    const Vec3 step = 0.5 * currentStrainRate * height * scene.dt * translationAxis;
    shift(Bottom, step);
    shift(Top, -step);
  }
  if (currentState == fixedPorosityCompaction)
  {
    const double h = 0.5 * strainRate * scene.dt;
    shift(Bottom, h * height * translationAxis);
    shift(Top, -h * height * translationAxis);
    shift(Back, Vec3(0, 0, h * depth));
    shift(Front, Vec3(0, 0, -h * depth));
    shift(Left, Vec3(h * width, 0, 0));
    shift(Right, Vec3(-h * width, 0, 0));
  }
}

} // namespace talus::dem
