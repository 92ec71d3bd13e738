#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mpi.h>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace talus::coupling
{
/// What the DEM side states about the coupled run; the fluid side checks it against its case.
struct FoamSettings
{
  std::string solver;        ///< executable path of the OpenFOAM coupling solver
  std::string caseDir;       ///< OpenFOAM case folder (decomposed into nProcs if nProcs > 1)
  int nProcs = 1;            ///< fluid ranks; > 1 runs the solver with -parallel
  double rhoFluid = 0;       ///< fluid density [kg/m3], must equal transportProperties rho
  double nu = 0;             ///< kinematic viscosity [m2/s], must equal transportProperties nu
  std::array<double, 3> gravity{}; ///< must equal constant/g
  double couplingInterval = 0;     ///< [s]; 0: one exchange per fluid step
  /// Longest wait [s] of either side for the other before the run is stopped: the DEM for the
  /// fluid's forces, the fluid for the DEM's next command (-couplingTimeout).
  double timeout = 60;
  /// The DEM runs decomposed over every process of MPI_COMM_WORLD (talus run under mpirun):
  /// the solver ranks are started by all of them together, and each exchanges its own
  /// particles (FoamProtocol.h). Otherwise this process is the whole DEM.
  bool demAcrossProcesses = false;
  /// NAME=value settings the solver ranks get besides their inherited environment (started
  /// through env(1)); under mpirun they inherit mpirun's environment, not this process's.
  std::vector<std::string> environment;
};

/// What the last exchange cost.
struct ExchangeStats
{
  long messages = 0;    ///< point-to-point messages: 3 per fluid rank with the DEM + between fluid ranks
  long demDoubles = 0;  ///< doubles sent and received by the DEM process
  int fluidPeers = 0;   ///< fluid ranks this DEM process exchanged particles with
  double seconds = 0;   ///< wall time of the exchange seen by the DEM (sending to last reply)
  double waitSeconds = 0; ///< of which waiting for the replies (the rest is the DEM's own work)
  double waitCpuSeconds = 0; ///< CPU time of this thread while it waited (polling)
  /// The fluid ranks' previous exchange (command received to forces sent) and previous fluid
  /// step, the slowest rank's; 0 at the first exchange (FoamProtocol.h, kTagForces).
  double fluidExchangeSeconds = 0;
  double fluidStepSeconds = 0;
  /// The same as CPU time of the rank.
  double fluidExchangeCpuSeconds = 0;
  double fluidStepCpuSeconds = 0;
};

/// The DEM side of the link with an OpenFOAM coupling solver (protocol: coupling/FoamProtocol.h).
/// The constructor spawns the solver ranks and does the handshake; each exchange() sends each
/// fluid rank the particles inside its sub-mesh's widened box and gets one force array back from
/// each (2P + P messages; the fluid ranks add one message per neighbour and reduction).
/// With a decomposed DEM (FoamSettings::demAcrossProcesses) every DEM process holds a link:
/// the constructor, exchange() and stop() are collective over the DEM processes; DEM rank 0
/// does the handshake and sends the commands, and each process exchanges its own particles with
/// the fluid ranks whose boxes hold some of them only (rank 0 with every fluid rank).
/// A fluid side gone silent for `timeout` seconds aborts every process with a message. The other
/// way round, the fluid gives up on a DEM process that sends nothing for `timeout` seconds
/// (stuck between two exchanges, or stopped); a watchdog thread of this process then stops it
/// too, saying so, rather than leaving it to find a dead fluid at its next exchange.
class FoamLink
{
public:
  /// Spawns the solver and checks the case against `settings`.
  /// @param settings the solver, its case and what the DEM side states about it
  /// @param nParticles the coupled particles, the same at every exchange (of the whole DEM when
  ///        it is decomposed: each process then exchanges a varying part of them)
  /// @throws std::runtime_error naming the setting or the file: a solver or case file missing,
  ///         a case not meshed or not decomposed into nProcs, a setting out of range, the spawn
  ///         failed, or the fluid side's reason on a mismatch with its case
  FoamLink(const FoamSettings& settings, int nParticles);
  ~FoamLink();
  FoamLink(const FoamLink&) = delete;
  FoamLink& operator=(const FoamLink&) = delete;

  /// The fluid's time step (s), as its case sets it (read at the handshake).
  [[nodiscard]] double fluidDt() const { return fluidDt_; }
  /// The particle Reynolds number up to which the solver's drag law (its dragModel) holds.
  [[nodiscard]] double dragReynoldsLimit() const { return dragReynoldsLimit_; }
  [[nodiscard]] int fluidProcs() const { return fluidProcs_; }
  [[nodiscard]] long nCells() const { return nCells_; }
  [[nodiscard]] int nParticles() const { return nParticles_; }
  [[nodiscard]] bool running() const { return inter_ != MPI_COMM_NULL; }
  [[nodiscard]] const ExchangeStats& lastExchange() const { return stats_; }
  /// Each fluid rank's {xmin, ymin, zmin, xmax, ymax, zmax, margin}.
  [[nodiscard]] const std::vector<double>& boxes() const { return boxes_; }

  /// One fluid step: sends positions (3N), velocities (3N) and radii (N) of this process's
  /// particles (N = nParticles() unless the DEM is decomposed); writes the
  /// hydrodynamic force on each particle into `forces` (3N), its drag coefficient beta (N) and
  /// the fluid velocity the drag uses (3N): the drag in `forces` is beta (uf - v) with the
  /// velocities sent. The fluid then advances one step.
  /// @param positions, velocities 3 values per particle [m], [m/s]
  /// @param radii one value per particle [m]
  /// @param forces 3 values per particle, written [N]
  /// @param beta one value per particle, written [kg/s]
  /// @param fluidVelocities 3 values per particle, written [m/s]
  /// @param indices each particle's index for the fluid (FoamProtocol.h: unique over the DEM
  ///        processes, increasing); empty: 0 .. N-1 (one DEM process only)
  /// @return the largest particle Reynolds number seen by the fluid (over every DEM process)
  /// @throws std::runtime_error if the fluid is not running, the arrays do not hold
  ///         nParticles() particles (or, decomposed, do not agree in size, or no indices), or a
  ///         particle is outside the fluid mesh (the fluid is stopped; on every DEM process,
  ///         with the same message)
  double exchange(std::span<const double> positions, std::span<const double> velocities,
                  std::span<const double> radii, std::span<double> forces, std::span<double> beta,
                  std::span<double> fluidVelocities, std::span<const std::int64_t> indices = {});

  /// Tells the fluid to write its fields and exit, then disconnects. Idempotent.
  void stop();

private:
  void wait(std::span<MPI_Request> requests, const char* what);
  /// The watchdog thread's loop: every 0.1 s, whether the fluid has given up on this process
  /// (its silence or its own stop longer than the timeout) or a fluid rank on this host died.
  void watch();
  void stopWatchdog();
  /// Why the fluid rank `peer` has died: its timeout (this process silent or stopped for longer
  /// than it) or something else. Prints it and ends this process (exit code 3 or 4).
  [[noreturn]] void fluidRankDied(int rank, int pid, const char* what);
  /// This process sent the fluid nothing for longer than the timeout: the fluid has given up.
  [[noreturn]] void fluidGaveUp(double silentSeconds);
  /// Whether the fluid's timeout explains a dead fluid at time `now` (steady seconds).
  [[nodiscard]] bool fluidTimedOut(double now) const;
  /// How long the fluid has waited for this process at `now`, as far as this process knows.
  [[nodiscard]] double silence(double now) const;
  /// Prints `message` and ends this process and the coupled run.
  [[noreturn]] void endRun(int code, const std::string& message);
  /// Records a pause of this process (stopped, or starved of CPU) longer than the timeout.
  void notePause(double now, double& previous);
  /// From DEM rank 0 (which speaks for the DEM) to every fluid rank; nothing elsewhere.
  void sendAll(const void* data, int count, MPI_Datatype type, int tag, const char* what);
  /// The handshake's results from DEM rank 0 to the other DEM processes.
  void shareHandshake(std::vector<int>& pids, int* reply, double* replyD, std::vector<char>& message);
  /// The lowest index of a particle outside the mesh on any DEM process, with its position, or
  /// an empty string if none (collective when decomposed).
  std::string lostParticle(std::span<const double> positions, std::span<const std::int64_t> indices);

  FoamSettings settings_;
  MPI_Comm inter_ = MPI_COMM_NULL;
  MPI_Comm dem_ = MPI_COMM_SELF; ///< the DEM's processes (a duplicate of MPI_COMM_WORLD when decomposed)
  int demRank_ = 0, demRanks_ = 1;
  std::vector<int> counts_;   ///< per fluid rank: this process's particles for it
  std::vector<int> allCounts_; ///< DEM rank 0: per DEM rank, its counts_
  int fluidProcs_ = 0;
  int nParticles_ = 0;
  long nCells_ = 0;
  double fluidDt_ = 0;
  double dragReynoldsLimit_ = 0;
  std::vector<double> boxes_;
  std::vector<std::vector<double>> sent_;                ///< per fluid rank: its particles
  std::vector<std::vector<std::size_t>> members_;        ///< per fluid rank: their indices
  std::vector<std::size_t> memberCount_;                 ///< per fluid rank: how many (the arrays hold room for all)
  std::vector<double> owned_;                            ///< per particle: how many ranks own it
  std::vector<std::vector<double>> replies_;
  ExchangeStats stats_;
  struct Peer
  {
    int rank;
    int pid;
  };
  std::vector<Peer> peers_; ///< fluid ranks on this host, watched while waiting
  // Steady-clock seconds of the last reply from the fluid and of the last command sent, whether
  // the main thread is waiting for the fluid, and when a pause of this process longer than the
  // timeout ended (0: none): what the watchdog judges the fluid's timeout by.
  std::atomic<double> heard_{0};
  std::atomic<double> sentAt_{0};
  std::atomic<bool> waiting_{false};
  std::atomic<double> pauseEnded_{0};
  std::atomic<double> pauseSeconds_{0};
  std::thread watchdog_;
  std::mutex watchdogMutex_;
  std::condition_variable watchdogWake_;
  bool watchdogStop_ = false;
};

/// An exchange's change of the fluid forces applied to the bodies: for each coupled particle i
/// (body ids[i]) the change forces[i] - applied[i] (3 doubles each) is added to the body's
/// persistent force and to this step's accumulator (`persistent`, `step`: 3 doubles per body,
/// by body id; the ForceResetter has already filled the accumulator from the persistent
/// forces). One pass over the particles instead of three NumPy operations, each a pass of its
/// own over arrays it allocates (docs/coupling.md, "Measurements behind the code"). The same
/// sums, the same bits.
/// @param forces, applied 3 values per coupled particle [N]
/// @param ids the coupled particles' body ids
/// @param persistent, step 3 values per body, added to
/// @throws std::invalid_argument if the sizes differ or an id is not a body
void addForceChange(std::span<const double> forces, std::span<const double> applied,
                    std::span<const std::int64_t> ids, std::span<double> persistent, std::span<double> step);

/// Finalizes MPI if this library started it (call once at interpreter exit).
void finalizeMpi();
} // namespace talus::coupling
