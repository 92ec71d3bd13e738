#include "fem/GaussPointRVEs.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace talus::fem
{
namespace
{
void checkDim(int dim)
{
  if (dim != 2 && dim != 3)
    throw std::invalid_argument("Gauss-point gradients must be 2x2 or 3x3, got " + std::to_string(dim) + "x" + std::to_string(dim));
}

/// Voigt indices of the in-plane components xx, yy, xy within the 3D order xx, yy, zz, yz, xz, xy.
constexpr std::array<int, 3> planeVoigt{0, 1, 5};
} // namespace

GaussPointRVEs::GaussPointRVEs(std::vector<std::unique_ptr<RVE>> rves) : rves_(std::move(rves))
{
  if (rves_.empty())
    throw std::invalid_argument("GaussPointRVEs: no RVE given");
  for (std::size_t i = 0; i < rves_.size(); ++i)
    if (!rves_[i])
      throw std::invalid_argument("GaussPointRVEs: Gauss point " + std::to_string(i) + " has no RVE");
}

void GaussPointRVEs::deform(std::span<const double> grads, int dim, int nSteps)
{
  deform(grads, dim, std::span<const int>(&nSteps, 1));
}

void GaussPointRVEs::deform(std::span<const double> grads, int dim, std::span<const int> nSteps)
{
  checkDim(dim);
  if (nSteps.size() != 1 && nSteps.size() != rves_.size())
    throw std::invalid_argument("got " + std::to_string(nSteps.size()) + " step counts for " + std::to_string(rves_.size())
                                + " Gauss points (give one, or one per point)");
  for (std::size_t p = 0; p < nSteps.size(); ++p)
    if (nSteps[p] < 1)
      throw std::invalid_argument("Gauss point " + std::to_string(p) + ": nSteps must be >= 1, got " + std::to_string(nSteps[p]));
  const std::size_t per = static_cast<std::size_t>(dim * dim);
  if (grads.size() != rves_.size() * per)
    throw std::invalid_argument("got displacement gradients for " + std::to_string(grads.size() / per)
                                + " Gauss points, but there are " + std::to_string(rves_.size()) + " RVEs");
  std::vector<Mat3> g(rves_.size(), Mat3::Zero());
  for (std::size_t p = 0; p < rves_.size(); ++p)
  {
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        g[p](i, j) = grads[p * per + static_cast<std::size_t>(i * dim + j)];
    if (!g[p].allFinite())
      throw std::invalid_argument("Gauss point " + std::to_string(p) + ": displacement gradient is not finite");
  }
  std::vector<std::string> errors(rves_.size());
  const auto n = static_cast<std::int64_t>(rves_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t p = 0; p < n; ++p)
  {
    try
    {
      const auto i = static_cast<std::size_t>(p);
      rves_[i]->deform(g[i], nSteps.size() == 1 ? nSteps[0] : nSteps[i]);
    }
    catch (const std::exception& e)
    {
      errors[static_cast<std::size_t>(p)] = e.what();
    }
  }
  std::string report;
  for (std::size_t p = 0; p < errors.size(); ++p)
    if (!errors[p].empty())
      report += (report.empty() ? "" : "; ") + ("Gauss point " + std::to_string(p) + ": " + errors[p]);
  if (!report.empty())
    throw std::runtime_error(report);
}

void GaussPointRVEs::getStressAndTangent(std::span<double> stress, std::span<double> tangent, int dim,
                                         dem::TangentForm form) const
{
  checkDim(dim);
  const std::size_t v = dim == 3 ? 6 : 3, n = rves_.size();
  const std::size_t perStress = static_cast<std::size_t>(dim * dim);
  if (stress.size() != n * perStress || tangent.size() != n * v * v)
    throw std::invalid_argument("getStressAndTangent: output arrays do not match " + std::to_string(n) + " Gauss points");
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t q = 0; q < static_cast<std::int64_t>(n); ++q)
  {
    const auto p = static_cast<std::size_t>(q);
    const Mat3 s = rves_[p]->stress();
    const Mat6 c = rves_[p]->tangent(form);
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        stress[p * perStress + static_cast<std::size_t>(i * dim + j)] = s(i, j);
    for (std::size_t a = 0; a < v; ++a)
      for (std::size_t b = 0; b < v; ++b)
        tangent[(p * v + a) * v + b] = dim == 3 ? c(static_cast<int>(a), static_cast<int>(b)) : c(planeVoigt[a], planeVoigt[b]);
  }
}

std::vector<RVEState> GaussPointRVEs::states() const
{
  std::vector<RVEState> out(rves_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t q = 0; q < static_cast<std::int64_t>(rves_.size()); ++q)
    out[static_cast<std::size_t>(q)] = rves_[static_cast<std::size_t>(q)]->state();
  return out;
}

void GaussPointRVEs::commit()
{
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t q = 0; q < static_cast<std::int64_t>(rves_.size()); ++q)
    rves_[static_cast<std::size_t>(q)]->commit();
}

void GaussPointRVEs::rollback()
{
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t q = 0; q < static_cast<std::int64_t>(rves_.size()); ++q)
    rves_[static_cast<std::size_t>(q)]->rollback();
}
} // namespace talus::fem
