#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace talus::coupling
{
/// What a coupling keeps per particle between two exchanges (the force it applied, the drag's
/// coefficient and the velocity it was computed with) when the DEM is decomposed over the
/// processes of MPI_COMM_WORLD: each process keeps the records of its own particles, and a
/// particle that has moved to another process since (the DEM migrates bodies at its
/// re-detections) takes its record along at the next handOver, as the DEM's own per-body arrays
/// travel with their bodies. Memory per process: its particles, plus those that moved.
class ParticleRecords
{
public:
  /// @param width values per particle
  /// @throws std::invalid_argument if width < 1
  explicit ParticleRecords(int width);
  ~ParticleRecords();
  ParticleRecords(const ParticleRecords&) = delete;
  ParticleRecords& operator=(const ParticleRecords&) = delete;

  /// The records become `values` (width per particle) of the particles `ids` (increasing).
  /// @throws std::invalid_argument on a size mismatch or ids not increasing
  void store(std::span<const std::int64_t> ids, std::span<const double> values);

  /// Collective over the processes: afterwards the records are those of the particles `ids`
  /// (this process's particles now, increasing), each from the process that held it (zeros for
  /// a particle no process has a record of).
  /// @throws std::invalid_argument for ids not increasing
  void handOver(std::span<const std::int64_t> ids);

  /// The particles' ids and their records (width values each), in the same order.
  [[nodiscard]] const std::vector<std::int64_t>& ids() const { return ids_; }
  [[nodiscard]] const std::vector<double>& values() const { return values_; }
  [[nodiscard]] int width() const { return width_; }
  /// Records this process sent to the others at the last handOver.
  [[nodiscard]] long lastSent() const { return lastSent_; }

private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int width_;
  std::vector<std::int64_t> ids_;
  std::vector<double> values_;
  long lastSent_ = 0;
};
} // namespace talus::coupling
