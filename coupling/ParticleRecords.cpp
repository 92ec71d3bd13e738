#include "coupling/ParticleRecords.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace talus::coupling
{
namespace
{
void checkIncreasing(std::span<const std::int64_t> ids, const char* what)
{
  if (std::adjacent_find(ids.begin(), ids.end(), std::greater_equal<>()) != ids.end())
    throw std::invalid_argument(std::string("ParticleRecords.") + what + ": the ids must be increasing");
}
} // namespace

ParticleRecords::ParticleRecords(int width) : width_(width)
{
  if (width < 1)
    throw std::invalid_argument("ParticleRecords: width must be at least 1, got " + std::to_string(width));
  MPI_Comm_dup(MPI_COMM_WORLD, &comm_); // its own messages, apart from the DEM's and the link's
}

ParticleRecords::~ParticleRecords()
{
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised && comm_ != MPI_COMM_NULL)
    MPI_Comm_free(&comm_);
}

void ParticleRecords::store(std::span<const std::int64_t> ids, std::span<const double> values)
{
  if (values.size() != ids.size() * static_cast<std::size_t>(width_))
    throw std::invalid_argument("ParticleRecords.store: " + std::to_string(values.size()) + " values for " +
                                std::to_string(ids.size()) + " particles of " + std::to_string(width_));
  checkIncreasing(ids, "store");
  ids_.assign(ids.begin(), ids.end());
  values_.assign(values.begin(), values.end());
}

void ParticleRecords::handOver(std::span<const std::int64_t> ids)
{
  checkIncreasing(ids, "handOver");
  const auto w = static_cast<std::size_t>(width_);
  // The records of particles no longer here go to every process (few: those that crossed a
  // boundary since the last exchange); each takes those of its newcomers.
  std::vector<std::int64_t> leftIds;
  std::vector<double> leftValues;
  for (std::size_t k = 0; k < ids_.size(); ++k)
    if (!std::binary_search(ids.begin(), ids.end(), ids_[k]))
    {
      leftIds.push_back(ids_[k]);
      leftValues.insert(leftValues.end(), values_.begin() + static_cast<std::ptrdiff_t>(k * w),
                        values_.begin() + static_cast<std::ptrdiff_t>((k + 1) * w));
    }
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(static_cast<std::size_t>(ranks) + 1, 0);
  const int mine = static_cast<int>(leftIds.size());
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  std::partial_sum(counts.begin(), counts.end(), starts.begin() + 1);
  std::vector<std::int64_t> movedIds(static_cast<std::size_t>(starts.back()));
  MPI_Allgatherv(leftIds.data(), mine, MPI_INT64_T, movedIds.data(), counts.data(), starts.data(), MPI_INT64_T,
                 comm_);
  for (auto& c : counts)
    c *= width_;
  for (auto& s : starts)
    s *= width_;
  std::vector<double> movedValues(static_cast<std::size_t>(starts.back()));
  MPI_Allgatherv(leftValues.data(), mine * width_, MPI_DOUBLE, movedValues.data(), counts.data(), starts.data(),
                 MPI_DOUBLE, comm_);
  lastSent_ = mine;

  std::vector<std::size_t> order(movedIds.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return movedIds[a] < movedIds[b]; });
  std::vector<double> values(ids.size() * w, 0.0);
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    const double* from = nullptr;
    if (const auto here = std::lower_bound(ids_.begin(), ids_.end(), ids[i]); here != ids_.end() && *here == ids[i])
      from = &values_[static_cast<std::size_t>(here - ids_.begin()) * w];
    else if (const auto moved = std::lower_bound(order.begin(), order.end(), ids[i],
                                                 [&](std::size_t k, std::int64_t id) { return movedIds[k] < id; });
             moved != order.end() && movedIds[*moved] == ids[i])
      from = &movedValues[*moved * w];
    if (from != nullptr)
      std::copy_n(from, w, &values[i * w]);
  }
  ids_.assign(ids.begin(), ids.end());
  values_ = std::move(values);
}
} // namespace talus::coupling
