#include "dem/control/Peri3dController.h"

#include "dem/measure/Measurements.h"
#include "dem/core/Scene.h"

#include <Eigen/SVD>

#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
const char* const pathNames[6] = {"xxPath", "yyPath", "zzPath", "yzPath", "zxPath", "xyPath"};

/// Voigt 6-vector of a symmetric tensor (stress: shear components as they are).
Vec6 toVoigt(const Mat3& m)
{
  Vec6 v;
  v << m(0, 0), m(1, 1), m(2, 2), .5 * (m(1, 2) + m(2, 1)), .5 * (m(2, 0) + m(0, 2)), .5 * (m(0, 1) + m(1, 0));
  return v;
}

/// Symmetric tensor of an engineering-strain 6-vector (shear components halved).
Mat3 strainTensor(const Vec6& v)
{
  Mat3 m;
  m << v[0], .5 * v[5], .5 * v[4], .5 * v[5], v[1], .5 * v[3], .5 * v[4], .5 * v[3], v[2];
  return m;
}
} // namespace

Peri3dController::Peri3dController()
{
  for (auto& p : paths)
    p.assign(1, Eigen::Vector2d(1, 1));
}

/// First step (progress 0): split the components into prescribed stresses (ps) and strains
/// (pe), normalise the paths, and tell whether the run is "stress-based", in which case the
/// first stress rates go through the compliance estimate.
bool Peri3dController::start()
{
  lenPs = lenPe = 0;
  ps = pe = Vec6i::Zero();
  stressGoal = strainGoal = Vec6::Zero();
  for (int i = 0; i < 6; ++i)
    if (stressMask & (1 << i))
    {
      ps[lenPs++] = i;
      stressGoal[i] = goal[i];
    }
    else
    {
      pe[lenPe++] = i;
      strainGoal[i] = goal[i];
    }
  for (int i = 0; i < 6; ++i)
  {
    auto& p = paths[i];
    if (p.empty())
      throw std::runtime_error(std::string("Peri3dController: ") + pathNames[i] + " has no point");
    pathSizes[i] = static_cast<int>(p.size());
    pathsCounter[i] = 0;
    for (std::size_t j = 1; j < p.size(); ++j)
      if (p[j - 1][0] >= p[j][0])
        throw std::runtime_error(std::string("Peri3dController: the progress (first) values of ") + pathNames[i]
                                 + " must increase strictly");
    // In place and in this order, as Yade: the last point is itself rescaled last, so that the
    // earlier points see its original values (and it may end a round-off away from 1 and goal).
    Eigen::Vector2d& last = p.back();
    for (auto& point : p)
    {
      point[0] *= 1. / last[0];
      if (std::abs(last[1]) >= 1e-9)
        point[1] *= goal[i] / last[1];
    }
  }
  // Yade tests the second point's value (< 1e9) of every strain path; a one-point path has no
  // second point and Yade then reads past the end of its vector, which in practice holds a
  // tiny number: such a path counts as passing the test.
  bool stressBased = true;
  for (int k = 0; k < lenPe; ++k)
    if (pathSizes[pe[k]] > 1)
      stressBased = stressBased && paths[pe[k]][1][1] < 1e9;
  return stressBased;
}

/// The ideal rates of the current path segments: strain rates of the strain components, stress
/// rates of the stress components (0 past the end of a multi-point path).
void Peri3dController::pathRates(double dt)
{
  for (int i = 0; i < 6; ++i) // at most one segment further per step, as Yade
    if (pathsCounter[i] < pathSizes[i] && progress >= paths[i][pathsCounter[i]][0])
      ++pathsCounter[i];
  const auto rate = [&](int j, double finalValue) {
    const auto& p = paths[j];
    const int c = pathsCounter[j];
    if (pathSizes[j] == 1)
      return finalValue / (nSteps * dt);
    if (c == 0)
      return p[0][1] / (p[0][0] * nSteps * dt);
    if (progress < 1. && c < pathSizes[j])
      return (p[c][1] - p[c - 1][1]) / ((p[c][0] - p[c - 1][0]) * nSteps * dt);
    return 0.;
  };
  for (int k = 0; k < lenPe; ++k)
    strainRate[pe[k]] = rate(pe[k], strainGoal[pe[k]]);
  for (int k = 0; k < lenPs; ++k)
    stressRate[ps[k]] = rate(ps[k], stressGoal[ps[k]]);
}

/// Strain rates of the stress components (see the class comment).
void Peri3dController::predictStressRates(bool firstStressBasedStep, const Vec6& stressOld, double dt)
{
  if (lenPs == 0)
    return;
  if (firstStressBasedStep)
  {
    const double e = youngEstimation, nu = poissonEstimation;
    const auto compliance = [&](int a, int b) {
      if (a < 3 && b < 3)
        return a == b ? 1 / e : -nu / e;
      return a == b ? (1 + nu) / e : 0.;
    };
    for (int i = 0; i < lenPs; ++i)
    {
      const int a = ps[i];
      strainRate[a] = 0;
      for (int j = 0; j < lenPs; ++j)
        strainRate[a] += compliance(a, ps[j]) * stressRate[ps[j]];
      // Yade adds a second sum meant for the strain components but indexing ps (its entries
      // past lenPs are 0); kept, as it changes the first step's rates.
      for (int j = 0; j < lenPe; ++j)
        strainRate[a] += compliance(a, ps[j]) * stressRate[ps[j]];
    }
    return;
  }
  const double sr = strainRate.cwiseAbs().maxCoeff();
  for (int i = 0; i < lenPs; ++i)
  {
    const int j = ps[i];
    // stress error extrapolated linearly to the next step
    const double linPred = 2 * (stress[j] - stressIdeal[j]) - (stressOld[j] - (stressIdeal[j] - stressRate[j] * dt));
    strainRate[j] += linPred > 0 ? -sr * mod : sr * mod;
  }
}

void Peri3dController::run(Scene& scene)
{
  if (!scene.periodic)
    throw std::runtime_error("Peri3dController: the scene is not periodic (set O.periodic = True)");
  const double dt = scene.dt;
  if (!(dt > 0))
    throw std::runtime_error("Peri3dController: the time step must be positive");
  if (nSteps <= 0)
    throw std::runtime_error("Peri3dController: nSteps must be positive, got " + std::to_string(nSteps));
  const bool stressBased = progress == 0 && start();
  pathRates(dt);

  const Vec6 stressOld = stress;
  stress = toVoigt(loveWeberStress(scene));
  stressIdeal += stressRate * dt;
  strain += strainRate * dt; // with the rates before the maxStrainRate scaling below, as Yade
  predictStressRates(stressBased, stressOld, dt);

  const double fastest = strainRate.cwiseAbs().maxCoeff();
  const double srCorr = fastest > maxStrainRate ? maxStrainRate / fastest : 1.;
  strainRate *= srCorr;

  // Add the strain increment to the stretch of trsf = rot * stretch, in the cell's own axes.
  const Mat3& trsf = scene.cell.trsf;
  const Eigen::JacobiSVD<Mat3> svd(trsf, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat3 u = svd.matrixU(), v = svd.matrixV();
  const Mat3 s = svd.singularValues().asDiagonal();
  const Mat3 rot = u * v.adjoint();
  Mat3 stretch = v * s * v.adjoint();
  const Mat3 strainIncrement = strainTensor(strainRate) * dt;
  stretch += rot.transpose() * strainIncrement * rot;
  scene.cell.velGrad = ((rot * stretch) * trsf.inverse() - Mat3::Identity()) / dt;
  progress += srCorr / nSteps;

  if (progress >= 1. || strain.cwiseAbs().maxCoeff() > maxStrain)
  {
    if (doneHook)
      doneHook();
    else
    {
      dead = true;
      scene.pause();
    }
  }
}
} // namespace talus::dem
