#include "dem/shapes/SpherePack.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace talus::dem
{
namespace
{
/// x wrapped into [x0, x1), relative to x0 (the arithmetic of Yade's cellWrapRel, so that the
/// overlap tests round as Yade's do).
double wrapRelative(double x, double x0, double x1)
{
  const double period = x1 - x0;
  const double s = (x - x0) / period;
  return (s - std::floor(s)) * period;
}

/// Radius at fraction x between a and b such that x is distributed like the mass (volume)
/// rather than the count: interpolation of r^-2.
double massInterpolation(double x, double a, double b)
{
  return std::pow(x * (std::pow(b, -2) - std::pow(a, -2)) + std::pow(a, -2), -0.5);
}

/// Piece i of a cumulative table with cumm[i] <= x < cumm[i+1], and x's fraction in it.
int pieceOf(double x, const std::vector<double>& cumm, double& fraction)
{
  const int n = static_cast<int>(cumm.size());
  int i = 0;
  while (i < n && cumm[static_cast<std::size_t>(i)] <= x)
    ++i;
  if (i == n - 1 && cumm[static_cast<std::size_t>(i)] <= x)
  {
    fraction = 1;
    return n - 2;
  }
  --i;
  const auto k = static_cast<std::size_t>(i);
  fraction = (x - cumm[k]) / (cumm[k + 1] - cumm[k]);
  return i;
}

/// The lattice of a sheared periodic cell H (edges as columns): which images of a sphere are
/// within reach. |d + H k| <= R implies |(H^-1 d)_a + k_a| <= R |row a of H^-1| (the distance
/// between the cell's faces across axis a is 1 / |row a|), so the few k in that box are all
/// that can be that close, however sheared the cell.
class PeriodicLattice
{
public:
  explicit PeriodicLattice(const Mat3& h) : h_(h), inverse_(h.inverse()), rowNorms_(inverse_.rowwise().norm().transpose()) {}

  /// Whether some image d + H k (k = 0 included unless excludeOrigin) is within R of the origin
  /// (touching counts, as Yade's overlap test).
  [[nodiscard]] bool within(const Vec3& d, double R, bool excludeOrigin = false) const
  {
    const Vec3 f = inverse_ * d;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = static_cast<int>(std::ceil(-f[a] - R * rowNorms_[a]));
      hi[a] = static_cast<int>(std::floor(-f[a] + R * rowNorms_[a]));
    }
    for (int i = lo[0]; i <= hi[0]; ++i)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int k = lo[2]; k <= hi[2]; ++k)
          if (!(excludeOrigin && i == 0 && j == 0 && k == 0) && (d + h_ * Vec3(i, j, k)).squaredNorm() <= R * R)
            return true;
    return false;
  }

  /// Length of the shortest non-zero period |H k| (a sphere overlaps its own image from this
  /// diameter on); searched within the shortest edge, an upper bound.
  [[nodiscard]] double shortestPeriod() const
  {
    double best = h_.colwise().norm().minCoeff();
    const Vec3 reach = best * rowNorms_;
    for (int i = -static_cast<int>(reach[0]); i <= static_cast<int>(reach[0]); ++i)
      for (int j = -static_cast<int>(reach[1]); j <= static_cast<int>(reach[1]); ++j)
        for (int k = -static_cast<int>(reach[2]); k <= static_cast<int>(reach[2]); ++k)
          if (i != 0 || j != 0 || k != 0)
            best = std::min(best, (h_ * Vec3(i, j, k)).norm());
    return best;
  }

private:
  Mat3 h_, inverse_;
  Vec3 rowNorms_;
};

enum class RadiusMode
{
  Undefined,
  Mean,         ///< rMean and rRelFuzz given
  FromPorosity, ///< rMean from num and porosity
  Distribution, ///< psdSizes and psdCumm
};
/// The radii (half the sizes) of a size distribution given as sizes and cumulated fractions,
/// checked, and with `distributeMass` the cumulated fractions by number (massCumm,
/// normalised); sizes scaled down (`scaling` < 1) if `num` > 1 spheres of them cannot fit in
/// `spread` (the box's volume, or area x largest size) at `porosity`, as Yade does.
void sizeDistribution(const std::vector<double>& psdSizes, const std::vector<double>& psdCumm, bool distributeMass,
                      int num, double porosity, double spread, std::vector<double>& psdRadii,
                      std::vector<double>& massCumm, double& scaling)
{
  if (psdSizes.size() != psdCumm.size())
    throw std::invalid_argument("makeCloud: psdSizes and psdCumm must have the same length (" + std::to_string(psdSizes.size())
                                + " != " + std::to_string(psdCumm.size()) + ")");
  if (psdSizes.size() < 2)
    throw std::invalid_argument("makeCloud: psdSizes needs at least 2 sizes");
  if (psdCumm.front() != 0 || psdCumm.back() != 1)
    throw std::invalid_argument("makeCloud: psdCumm must start at exactly 0 and end at exactly 1");
  const std::size_t n = psdSizes.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!(psdSizes[i] > 0))
      throw std::invalid_argument("makeCloud: psdSizes[" + std::to_string(i) + "] must be positive");
    if (i > 0 && (psdSizes[i - 1] > psdSizes[i] || psdCumm[i - 1] > psdCumm[i]))
      throw std::invalid_argument("makeCloud: psdSizes and psdCumm must both be non-decreasing (item " + std::to_string(i) + ")");
    psdRadii.push_back(0.5 * psdSizes[i]);
    // By mass: the number of spheres per size interval, dN = V (1 - n) dP / (4/3 pi r^3),
    // integrated over each interval; normalised below.
    if (distributeMass)
      massCumm.push_back(i == 0 ? 0.0
                                : massCumm[i - 1]
                                      + 3.0 * spread * (1 - porosity) / M_PI * (psdCumm[i] - psdCumm[i - 1])
                                            / (psdSizes[i] - psdSizes[i - 1])
                                            * (std::pow(psdSizes[i - 1], -2) - std::pow(psdSizes[i], -2)));
  }
  if (num > 1)
  {
    // Scale the sizes down if `num` spheres of this distribution cannot fit at `porosity`.
    scaling = 1;
    if (distributeMass)
    {
      if (massCumm.back() < num)
        scaling = std::pow(massCumm.back() / num, 1. / 3.);
    }
    else
    {
      double solid = 0;
      // Yade evaluates 4 / 3 in integer arithmetic (= 1) here; kept, so that the same arguments
      // give the same scaling as in Yade.
      for (std::size_t i = 1; i < n; ++i)
        solid += 4 / 3 * M_PI * (psdCumm[i] - psdCumm[i - 1]) * num * std::pow(0.5 * (psdSizes[i] + psdSizes[i - 1]), 3)
                 * (1 + std::pow(0.5 * (psdSizes[i] - psdSizes[i - 1]), 2));
      const double ratio = solid / ((1 - porosity) * spread);
      if (ratio > 1)
        scaling = std::pow(ratio, -1. / 3.);
    }
    if (scaling < 1)
      for (double& r : psdRadii)
        r *= scaling;
  }
  if (distributeMass)
    for (std::size_t i = 1; i < n; ++i)
      massCumm[i] /= massCumm.back();
}

} // namespace

long SpherePack::makeCloud(const Vec3& mn, const Vec3& mx, double rMean, double rRelFuzz, int num, bool periodic,
                           double porosity, const std::vector<double>& psdSizes, const std::vector<double>& psdCumm,
                           bool distributeMass, int seed, const Mat3& cell)
{
  const bool sheared = cell != Mat3::Zero();
  if (!mn.allFinite())
    throw std::invalid_argument("makeCloud: minCorner must be finite");
  if (sheared)
  {
    if (!periodic)
      throw std::invalid_argument("makeCloud: hSize (a sheared cell) needs periodic=True");
    if (!cell.allFinite() || !(cell.determinant() > 0))
      throw std::invalid_argument("makeCloud: hSize must be finite with a positive determinant (three right-handed edges "
                                  "spanning a volume), its determinant is "
                                  + std::to_string(cell.determinant()));
  }
  else if (!mx.allFinite())
    throw std::invalid_argument("makeCloud: maxCorner must be finite");
  // As Yade, a box whose maxCorner is below minCorner along an axis is filled between the two
  // (its spheres then reach up to a radius beyond the corners); a cell cannot be inverted.
  else if (periodic && ((mx - mn).array() < 0).any())
    throw std::invalid_argument("makeCloud: a periodic cloud needs maxCorner at or above minCorner in every direction");
  std::random_device device;
  std::mt19937 generator(seed >= 0 ? static_cast<std::mt19937::result_type>(seed) : device());
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  const Vec3 size = sheared ? Vec3(cell.colwise().norm().transpose()) : Vec3(mx - mn);
  const double volume = sheared ? cell.determinant() : size[0] * size[1] * size[2];
  // With one size zero two of these terms vanish and the third is the area of the 2D box.
  const double area = std::abs(size[0] * size[2] + size[0] * size[1] + size[1] * size[2]);
  if (porosity <= 0 && rMean <= 0)
    porosity = 0.5;
  RadiusMode mode = RadiusMode::Undefined;
  if (rMean > 0)
    mode = RadiusMode::Mean;
  else if (num > 0 && psdSizes.empty())
  {
    mode = RadiusMode::FromPorosity;
    if (volume < 0) // Yade takes the cube root of the negative volume: a NaN radius
      throw std::invalid_argument("makeCloud: num without rMean needs maxCorner at or above minCorner in every "
                                  "direction (the radius comes from the box's volume)");
    // mean volume of radii uniform in rMean (1 +- z): 4/3 pi rMean^3 (1 + z^2)
    if (volume != 0)
      rMean = std::pow(volume * (1 - porosity) / (M_PI * (4 / 3.) * (1 + rRelFuzz * rRelFuzz) * num), 1 / 3.);
    else
    {
      if (area == 0)
        throw std::invalid_argument("makeCloud: the box has neither a volume nor an area");
      rMean = std::pow(area * (1 - porosity) / (M_PI * (1 + rRelFuzz * rRelFuzz) * num), 0.5);
    }
  }
  std::vector<double> psdRadii, massCumm;
  if (!psdSizes.empty())
  {
    if (mode != RadiusMode::Undefined)
      throw std::invalid_argument("makeCloud: rMean cannot be combined with psdSizes");
    mode = RadiusMode::Distribution;
    sizeDistribution(psdSizes, psdCumm, distributeMass, num, porosity, volume != 0 ? volume : area * psdSizes.back(),
                     psdRadii, massCumm, appliedPsdScaling);
  }
  if (mode == RadiusMode::Undefined)
    throw std::invalid_argument("makeCloud: give rMean, or num (with porosity), or psdSizes and psdCumm");
  if (!(rRelFuzz >= 0 && rRelFuzz < 1) && mode != RadiusMode::Distribution)
    throw std::invalid_argument("makeCloud: rRelFuzz must be in [0, 1), got " + std::to_string(rRelFuzz));

  if (num > maxSpheres)
    throw std::invalid_argument("makeCloud: num = " + std::to_string(num) + " spheres is more than the limit of "
                                + std::to_string(maxSpheres));
  if (num < 0 && mode == RadiusMode::Mean)
  {
    // Filled until a sphere finds no room: at most the spheres a densest packing would hold.
    const double most = volume != 0 ? 0.7405 * std::abs(volume) / (4 / 3. * M_PI * std::pow(rMean, 3))
                                    : 0.9069 * area / (M_PI * rMean * rMean);
    if (most > static_cast<double>(maxSpheres))
      throw std::invalid_argument("makeCloud: the box holds up to " + std::to_string(most) + " spheres of rMean = "
                                  + std::to_string(rMean) + ", more than the limit of " + std::to_string(maxSpheres)
                                  + " (a larger rMean or a num)");
  }
  const int maxTry = 1000;
  const bool cellular = periodic && volume != 0; // a flat periodic box makes no cell, as in Yade
  if (cellular)
    hSize = sheared ? cell : Mat3(size.asDiagonal());
  // A sphere of a periodic cloud must not reach its own images. Radii that follow from the
  // porosity shrink on a retry; radii asked for cannot.
  const PeriodicLattice lattice(cellular ? hSize : Mat3::Identity()); // used only if cellular
  if (cellular && mode != RadiusMode::FromPorosity)
  {
    const double rMax = mode == RadiusMode::Mean ? rMean * (1 + rRelFuzz) : psdRadii.back();
    const double period = lattice.shortestPeriod();
    if (2 * rMax > period)
      throw std::invalid_argument("makeCloud: spheres of radius up to " + std::to_string(rMax)
                                  + " do not fit in the periodic cell: its shortest period is " + std::to_string(period)
                                  + " (a sphere would overlap its own image)");
  }
  double r = 0;
  for (int i = 0; i < num || num < 0; ++i)
  {
    // With num given, radii are deterministic and decreasing; otherwise random.
    const double x = num > 0 ? (static_cast<double>(num) - i + 0.5) / (static_cast<double>(num) + 1.) : uniform(generator);
    double fraction = 0;
    switch (mode)
    {
    case RadiusMode::Mean:
    case RadiusMode::FromPorosity:
      r = distributeMass ? massInterpolation(x, rMean * (1 - rRelFuzz), rMean * (1 + rRelFuzz))
                         : rMean * (2 * (x - .5) * rRelFuzz + 1);
      break;
    case RadiusMode::Distribution:
      if (distributeMass)
      {
        const auto k = static_cast<std::size_t>(pieceOf(x, massCumm, fraction));
        r = massInterpolation(fraction, psdRadii[k], psdRadii[k + 1]);
      }
      else
      {
        const auto k = static_cast<std::size_t>(pieceOf(x, psdCumm, fraction));
        r = psdRadii[k] + fraction * (psdRadii[k + 1] - psdRadii[k]);
      }
      break;
    case RadiusMode::Undefined: break;
    }
    int t = 0;
    for (; t < maxTry; ++t)
    {
      Vec3 c;
      if (!periodic)
      {
        for (int a = 0; a < 3; ++a)
          c[a] = mn[a] + (size[a] != 0 ? (size[a] - 2 * r) * uniform(generator) + r : 0);
      }
      else
      {
        for (int a = 0; a < 3; ++a)
          c[a] = uniform(generator);
        c = sheared ? Vec3(mn + cell * c) : Vec3(Vec3(size.cwiseProduct(c)) + mn);
      }
      bool overlap = cellular && lattice.within(Vec3::Zero(), 2 * r, true);
      for (std::size_t j = 0; j < centers.size() && !overlap; ++j)
      {
        if (sheared)
        {
          overlap = lattice.within(centers[j] - c, radii[j] + r);
          continue;
        }
        Vec3 d;
        if (!periodic)
          d = centers[j] - c;
        else // Yade's arithmetic, so that seeded clouds are Yade's
          for (int a = 0; a < 3; ++a)
            d[a] = size[a] != 0 ? std::min(wrapRelative(c[a], centers[j][a], centers[j][a] + size[a]),
                                           wrapRelative(centers[j][a], c[a], c[a] + size[a]))
                                : 0;
        overlap = std::pow(radii[j] + r, 2) >= d.squaredNorm();
      }
      if (!overlap)
      {
        centers.push_back(c);
        radii.push_back(r);
        break;
      }
    }
    if (t == maxTry)
    {
      if (num > 0 && mode != RadiusMode::Mean)
      {
        // Retry from scratch with a higher porosity: smaller radii.
        centers.clear();
        radii.clear();
        return makeCloud(mn, mx, -1., rRelFuzz, num, periodic, porosity + (1 - porosity) / 10., psdSizes, psdCumm,
                         distributeMass, seed, cell);
      }
      return i;
    }
  }
  return static_cast<long>(centers.size());
}
} // namespace talus::dem
