#include "coupling/FoamLink.h"

#include "coupling/FoamProtocol.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <cerrno>
#include <csignal>
#include <unistd.h>

namespace talus::coupling
{
namespace proto = talus::foam_protocol;
namespace fs = std::filesystem;

namespace
{
bool mpiStartedHere = false;

void ensureMpi()
{
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised)
  {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SINGLE, &provided);
    mpiStartedHere = true;
  }
}

double threadCpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double steadySeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int thisHost()
{
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return proto::hostHash(name);
}

/// Errors that can be known before any process is started.
void checkCase(const FoamSettings& s)
{
  if (!fs::is_regular_file(s.solver))
    throw std::runtime_error("FoamCoupling: solver executable '" + s.solver + "' not found");
  const fs::path dir(s.caseDir);
  for (const char* f : {"system/controlDict", "system/fvSchemes", "system/fvSolution",
                        "constant/transportProperties", "constant/g"})
    if (!fs::is_regular_file(dir / f))
      throw std::runtime_error("FoamCoupling: case '" + s.caseDir + "' has no " + f);
  if (s.nProcs < 1)
    throw std::runtime_error("FoamCoupling: nProcs must be at least 1, got " + std::to_string(s.nProcs));
  if (s.nProcs == 1 && !fs::is_directory(dir / "constant/polyMesh"))
    throw std::runtime_error("FoamCoupling: case '" + s.caseDir + "' has no mesh (run blockMesh)");
  for (int p = 0; s.nProcs > 1 && p < s.nProcs; ++p)
    if (!fs::is_directory(dir / ("processor" + std::to_string(p))))
      throw std::runtime_error("FoamCoupling: case '" + s.caseDir + "' is not decomposed into " +
                               std::to_string(s.nProcs) + " (no processor" + std::to_string(p) +
                               "; run decomposePar)");
  if (!(s.rhoFluid > 0) || !(s.nu > 0) || !(s.timeout > 0) || s.couplingInterval < 0)
    throw std::runtime_error("FoamCoupling: rhoFluid, nu and timeout must be positive and "
                             "couplingInterval not negative");
}
} // namespace

FoamLink::FoamLink(const FoamSettings& settings, int nParticles)
  : settings_(settings), nParticles_(nParticles)
{
  checkCase(settings_);
  if (nParticles < 0)
    throw std::runtime_error("FoamCoupling: negative particle count");
  ensureMpi();
  if (settings_.demAcrossProcesses)
    MPI_Comm_dup(MPI_COMM_WORLD, &dem_); // the coupling's own collectives, apart from the DEM's
  MPI_Comm_rank(dem_, &demRank_);
  MPI_Comm_size(dem_, &demRanks_);

  std::string timeout = std::to_string(settings_.timeout);
  std::string command = settings_.solver;
  std::vector<char*> argv;
  if (!settings_.environment.empty())
  {
    command = "/usr/bin/env"; // which then runs the solver in this process, with the settings
    for (auto& setting : settings_.environment)
      argv.push_back(setting.data());
    argv.push_back(settings_.solver.data());
  }
  for (char* a : {const_cast<char*>("-case"), settings_.caseDir.data(), const_cast<char*>("-couplingTimeout"),
                  timeout.data()})
    argv.push_back(a);
  if (settings_.nProcs > 1)
    argv.push_back(const_cast<char*>("-parallel"));
  argv.push_back(nullptr);
  std::vector<int> errors(static_cast<std::size_t>(settings_.nProcs));
  MPI_Comm_set_errhandler(dem_, MPI_ERRORS_RETURN);
  const int rc = MPI_Comm_spawn(command.c_str(), argv.data(), settings_.nProcs,
                                MPI_INFO_NULL, 0, dem_, &inter_, errors.data());
  if (rc != MPI_SUCCESS || inter_ == MPI_COMM_NULL)
  {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(rc, text, &length);
    throw std::runtime_error("FoamCoupling: MPI_Comm_spawn of " + std::to_string(settings_.nProcs) +
                             " x '" + settings_.solver + "' failed: " + std::string(text, static_cast<std::size_t>(length)) +
                             " (more ranks than slots? set OMPI_MCA_rmaps_base_oversubscribe=1)");
  }
  MPI_Comm_remote_size(inter_, &fluidProcs_);

  const int hello[proto::kHelloInts] = {proto::kMagic, proto::kVersion, nParticles,
                                       static_cast<int>(getpid()), thisHost()};
  const double helloD[proto::kHelloDoubles] = {settings_.rhoFluid, settings_.nu,
                                               settings_.gravity[0], settings_.gravity[1],
                                               settings_.gravity[2], settings_.couplingInterval};
  sendAll(hello, proto::kHelloInts, MPI_INT, proto::kTagHello, "the handshake");
  sendAll(helloD, proto::kHelloDoubles, MPI_DOUBLE, proto::kTagHelloD, "the handshake");

  int reply[proto::kReplyInts];
  double replyD[proto::kReplyDoubles];
  std::vector<char> message(proto::kMessageChars, '\0');
  // The fluid ranks' pids come first (before they read the case), so that a solver dying on a
  // bad case file is noticed at once rather than after the timeout.
  std::vector<int> pids(2 * static_cast<std::size_t>(fluidProcs_));
  boxes_.assign(proto::kBoxDoubles * static_cast<std::size_t>(fluidProcs_), 0.0);
  if (demRank_ == 0)
  {
    std::vector<MPI_Request> pidRequests(static_cast<std::size_t>(fluidProcs_));
    for (int p = 0; p < fluidProcs_; ++p)
      MPI_Irecv(&pids[2 * static_cast<std::size_t>(p)], 2, MPI_INT, p, proto::kTagPid, inter_,
                &pidRequests[static_cast<std::size_t>(p)]);
    wait(pidRequests, "the fluid ranks' process ids");
    for (int p = 0; p < fluidProcs_; ++p)
      if (pids[2 * static_cast<std::size_t>(p) + 1] == thisHost())
        peers_.push_back({p, pids[2 * static_cast<std::size_t>(p)]});

    std::vector<MPI_Request> rq(3 + static_cast<std::size_t>(fluidProcs_));
    MPI_Irecv(reply, proto::kReplyInts, MPI_INT, 0, proto::kTagHelloReply, inter_, &rq[0]);
    MPI_Irecv(replyD, proto::kReplyDoubles, MPI_DOUBLE, 0, proto::kTagHelloReplyD, inter_, &rq[1]);
    MPI_Irecv(message.data(), proto::kMessageChars, MPI_CHAR, 0, proto::kTagMessage, inter_, &rq[2]);
    for (int p = 0; p < fluidProcs_; ++p)
      MPI_Irecv(&boxes_[proto::kBoxDoubles * static_cast<std::size_t>(p)], proto::kBoxDoubles, MPI_DOUBLE, p,
                proto::kTagBox, inter_, &rq[3 + static_cast<std::size_t>(p)]);
    wait(rq, "the fluid side's handshake (is the case readable? see the solver's output)");
  }
  shareHandshake(pids, reply, replyD, message);
  message.back() = '\0';

  std::string why;
  if (reply[0] != proto::kMagic || reply[1] != proto::kVersion)
    why = "protocol version mismatch: DEM side " + std::to_string(proto::kVersion) + ", solver " +
          std::to_string(reply[1]);
  else if (reply[2] != proto::kStatusOk)
    why = message.data();
  fluidDt_ = replyD[0];
  dragReynoldsLimit_ = replyD[3];
  nCells_ = reply[4];
  if (why.empty() && settings_.couplingInterval > 0 &&
      fluidDt_ > settings_.couplingInterval * (1 + 1e-12))
  {
    std::ostringstream s;
    s << "the fluid time step " << fluidDt_ << " s (system/controlDict deltaT) is larger than "
      << "the coupling interval " << settings_.couplingInterval << " s";
    why = s.str();
    // The fluid waits for a command: stop it cleanly.
    std::vector<int> stopCommand(static_cast<std::size_t>(proto::commandInts(demRanks_)), 0);
    stopCommand[0] = proto::kCommandStop;
    sendAll(stopCommand.data(), proto::commandInts(demRanks_), MPI_INT, proto::kTagCommand, "the stop command");
  }
  if (!why.empty())
  {
    MPI_Comm_disconnect(&inter_);
    if (dem_ != MPI_COMM_SELF)
      MPI_Comm_free(&dem_);
    throw std::runtime_error("FoamCoupling: " + why);
  }
  replies_.assign(static_cast<std::size_t>(fluidProcs_), {});
  sent_.assign(static_cast<std::size_t>(fluidProcs_), {});
  members_.assign(static_cast<std::size_t>(fluidProcs_), {});
  memberCount_.assign(static_cast<std::size_t>(fluidProcs_), 0);
  heard_ = steadySeconds();
  watchdog_ = std::thread([this] { watch(); });
}

FoamLink::~FoamLink()
{
  try
  {
    stop();
  }
  catch (...)
  {
    // A destructor must not throw; stop() aborts on a silent fluid side anyway.
  }
}

void FoamLink::wait(std::span<MPI_Request> requests, const char* what)
{
  waiting_ = true;
  double start = steadySeconds();
  double previous = start;
  double lastLivenessCheck = start;
  auto pause = std::chrono::microseconds(20);
  while (true)
  {
    int done = 0;
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done)
    {
      waiting_ = false;
      return;
    }
    const double now = steadySeconds();
    if (now - previous > settings_.timeout)
      start = now; // this process was paused: the fluid was not the one keeping it waiting
    notePause(now, previous);
    if (now - lastLivenessCheck > 0.1)
    {
      lastLivenessCheck = now;
      for (const auto& peer : peers_)
        if (kill(peer.pid, 0) != 0 && errno == ESRCH)
          fluidRankDied(peer.rank, peer.pid, what);
    }
    if (now - start > settings_.timeout)
    {
      std::fprintf(stderr,
                   "FoamCoupling: waited %g s for %s from the fluid solver '%s': it is gone or "
                   "stuck; aborting every process of the coupled run\n",
                   settings_.timeout, what, settings_.solver.c_str());
      std::fflush(stderr);
      MPI_Abort(inter_, 3);
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(1000));
  }
}

void FoamLink::notePause(double now, double& previous)
{
  if (now - previous > settings_.timeout)
  {
    pauseSeconds_ = now - previous;
    pauseEnded_ = now;
  }
  previous = now;
}

bool FoamLink::fluidTimedOut(double now) const
{
  // A pause of this process longer than the timeout, ended less than a timeout ago, explains a
  // fluid that gave up; so does a command sent (or still unsent) more than a timeout after the
  // last reply.
  const double pauseEnded = pauseEnded_;
  if (pauseEnded > 0 && now - pauseEnded < settings_.timeout)
    return true;
  return silence(now) > settings_.timeout;
}

double FoamLink::silence(double now) const
{
  return (waiting_ ? sentAt_.load() : now) - heard_;
}

void FoamLink::fluidRankDied(int rank, int pid, const char* what)
{
  const double now = steadySeconds();
  if (fluidTimedOut(now))
    fluidGaveUp(std::max(silence(now), pauseSeconds_.load()));
  endRun(4, "FoamCoupling: fluid rank " + std::to_string(rank) + " (pid " + std::to_string(pid) + ") of '" +
                settings_.solver + "' has died while the DEM waited for " + what +
                "; aborting every process of the coupled run");
}

void FoamLink::fluidGaveUp(double silentSeconds)
{
  std::ostringstream s;
  s << "FoamCoupling: the fluid solver '" << settings_.solver << "' timed out: this DEM process sent it "
    << "nothing for " << silentSeconds << " s, longer than the timeout of " << settings_.timeout
    << " s (FoamCoupling timeout) after which the fluid stops waiting (the DEM was stuck in a step, "
    << "a hook or a PyRunner between two exchanges, or stopped); stopping every process of the "
    << "coupled run";
  endRun(3, s.str());
}

void FoamLink::endRun(int code, const std::string& message)
{
  // The main thread and the watchdog may both find the end: one message, one exit.
  static std::atomic_flag ending = ATOMIC_FLAG_INIT;
  if (ending.test_and_set())
    while (true)
      std::this_thread::sleep_for(std::chrono::seconds(1));
  // The fluid ranks' last words reach this process's terminal through Open MPI's threads here:
  // a moment for them to arrive before the run ends.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  std::fprintf(stderr, "%s\n", message.c_str());
  std::fflush(stderr);
  if (std::this_thread::get_id() != watchdog_.get_id())
    MPI_Abort(inter_, code);
  // No MPI call from a second thread (MPI_THREAD_SINGLE): the process ends, and Open MPI's
  // daemon, which watches it, ends the fluid ranks left.
  std::_Exit(code);
}

void FoamLink::watch()
{
  double previous = steadySeconds();
  std::unique_lock lock(watchdogMutex_);
  while (!watchdogWake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return watchdogStop_; }))
  {
    const double now = steadySeconds();
    notePause(now, previous);
    if (!waiting_ && now - heard_ > settings_.timeout)
      fluidGaveUp(now - heard_);
    for (const auto& peer : peers_)
      if (kill(peer.pid, 0) != 0 && errno == ESRCH)
        fluidRankDied(peer.rank, peer.pid, waiting_ ? "the forces" : "nothing (between two exchanges)");
  }
}

void FoamLink::stopWatchdog()
{
  if (!watchdog_.joinable())
    return;
  {
    const std::lock_guard lock(watchdogMutex_);
    watchdogStop_ = true;
  }
  watchdogWake_.notify_all();
  watchdog_.join();
}

void FoamLink::shareHandshake(std::vector<int>& pids, int* reply, double* replyD, std::vector<char>& message)
{
  if (demRanks_ == 1)
    return;
  MPI_Bcast(pids.data(), static_cast<int>(pids.size()), MPI_INT, 0, dem_);
  MPI_Bcast(boxes_.data(), static_cast<int>(boxes_.size()), MPI_DOUBLE, 0, dem_);
  MPI_Bcast(reply, proto::kReplyInts, MPI_INT, 0, dem_);
  MPI_Bcast(replyD, proto::kReplyDoubles, MPI_DOUBLE, 0, dem_);
  MPI_Bcast(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, dem_);
  if (demRank_ != 0)
    for (int p = 0; p < fluidProcs_; ++p)
      if (pids[2 * static_cast<std::size_t>(p) + 1] == thisHost())
        peers_.push_back({p, pids[2 * static_cast<std::size_t>(p)]});
}

void FoamLink::sendAll(const void* data, int count, MPI_Datatype type, int tag, const char* what)
{
  if (demRank_ != 0)
    return;
  std::vector<MPI_Request> rq(static_cast<std::size_t>(fluidProcs_));
  for (int p = 0; p < fluidProcs_; ++p)
    MPI_Isend(data, count, type, p, tag, inter_, &rq[static_cast<std::size_t>(p)]);
  wait(rq, what);
}

double FoamLink::exchange(std::span<const double> positions, std::span<const double> velocities,
                          std::span<const double> radii, std::span<double> forces, std::span<double> beta,
                          std::span<double> fluidVelocities, std::span<const std::int64_t> indices)
{
  if (!running())
    throw std::runtime_error("FoamCoupling: the fluid solver is not running");
  const std::size_t n = radii.size();
  if ((demRanks_ == 1 && n != static_cast<std::size_t>(nParticles_)) || positions.size() != 3 * n ||
      velocities.size() != 3 * n || forces.size() != 3 * n || beta.size() != n || fluidVelocities.size() != 3 * n ||
      (!indices.empty() && indices.size() != n) || (demRanks_ > 1 && indices.size() != n))
    throw std::runtime_error("FoamCoupling: particle arrays do not match the " + std::to_string(nParticles_) +
                             " particles of the handshake" +
                             (demRanks_ > 1 ? " (or each other, or have no indices)" : ""));
  if (const double silent = steadySeconds() - heard_; silent > settings_.timeout)
    fluidGaveUp(silent); // sending would only find the fluid gone
  const auto start = std::chrono::steady_clock::now();
  // Each fluid rank gets the particles inside its widened box only (FoamProtocol.h, inBox).
  // The arrays keep room for every particle (no allocation, no capacity test per value, which
  // made push_back a visible part of an exchange; docs/coupling.md, "Measurements behind the
  // code").
  counts_.resize(static_cast<std::size_t>(fluidProcs_));
  for (int p = 0; p < fluidProcs_; ++p)
  {
    const double* box = &boxes_[proto::kBoxDoubles * static_cast<std::size_t>(p)];
    auto& members = members_[static_cast<std::size_t>(p)];
    auto& data = sent_[static_cast<std::size_t>(p)];
    members.resize(n);
    data.resize(proto::kParticleDoubles * n);
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double* x = &positions[3 * i];
      if (!proto::inBox(box, x[0], x[1], x[2]))
        continue;
      double* d = &data[proto::kParticleDoubles * count];
      const double* v = &velocities[3 * i];
      d[0] = x[0], d[1] = x[1], d[2] = x[2];
      d[3] = v[0], d[4] = v[1], d[5] = v[2];
      d[6] = radii[i];
      d[7] = static_cast<double>(indices.empty() ? static_cast<std::int64_t>(i) : indices[i]);
      members[count++] = i;
    }
    memberCount_[static_cast<std::size_t>(p)] = count;
    counts_[static_cast<std::size_t>(p)] = static_cast<int>(count);
  }
  // DEM rank 0 tells each fluid rank how many particles each DEM process sends it.
  const auto procs = static_cast<std::size_t>(fluidProcs_);
  allCounts_.resize(procs * static_cast<std::size_t>(demRanks_));
  if (demRanks_ > 1)
    MPI_Gather(counts_.data(), fluidProcs_, MPI_INT, allCounts_.data(), fluidProcs_, MPI_INT, 0, dem_);
  else
    allCounts_ = counts_;
  const auto commandSize = static_cast<std::size_t>(proto::commandInts(demRanks_));
  std::vector<int> commands(demRank_ == 0 ? procs * commandSize : 0);
  std::vector<MPI_Request> rq;
  rq.reserve(3 * procs);
  long doubles = 0;
  long messages = 0;
  stats_.fluidPeers = 0;
  for (std::size_t p = 0; demRank_ == 0 && p < procs; ++p)
  {
    int* command = &commands[p * commandSize];
    command[0] = proto::kCommandStep;
    command[1] = 0;
    for (std::size_t d = 0; d < static_cast<std::size_t>(demRanks_); ++d)
    {
      command[2 + d] = allCounts_[d * procs + p];
      command[1] += command[2 + d];
    }
    rq.emplace_back();
    MPI_Isend(command, static_cast<int>(commandSize), MPI_INT, static_cast<int>(p), proto::kTagCommand, inter_,
              &rq.back());
    ++messages;
  }
  // A DEM process exchanges with the fluid ranks it has particles for; rank 0 with all of them.
  const auto exchanges = [&](std::size_t p) { return demRank_ == 0 || memberCount_[p] > 0; };
  for (std::size_t p = 0; p < procs; ++p)
  {
    if (!exchanges(p))
      continue;
    const auto count = memberCount_[p];
    auto& reply = replies_[p];
    reply.resize(proto::kReplyHeader + proto::kForceDoubles * count);
    rq.emplace_back();
    MPI_Irecv(reply.data(), static_cast<int>(reply.size()), MPI_DOUBLE, static_cast<int>(p), proto::kTagForces,
              inter_, &rq.back());
    const auto sentDoubles = static_cast<int>(proto::kParticleDoubles * count);
    rq.emplace_back();
    MPI_Isend(sent_[p].data(), sentDoubles, MPI_DOUBLE, static_cast<int>(p), proto::kTagParticles, inter_,
              &rq.back());
    messages += 2;
    doubles += static_cast<long>(sentDoubles + reply.size());
    ++stats_.fluidPeers;
  }
  const auto sent = std::chrono::steady_clock::now();
  const double sentCpu = threadCpuSeconds();
  sentAt_ = steadySeconds();
  wait(rq, "the forces");
  heard_ = steadySeconds();
  const auto received = std::chrono::steady_clock::now();
  stats_.waitCpuSeconds = threadCpuSeconds() - sentCpu;

  double maxRe = 0;
  long fluidMessages = 0;
  stats_.fluidExchangeSeconds = stats_.fluidStepSeconds = 0;
  stats_.fluidExchangeCpuSeconds = stats_.fluidStepCpuSeconds = 0;
  owned_.resize(n);
  // The first rank's values are written over every particle (zeros where it was sent none),
  // the other ranks' added to them: no pass zeroing the 8 N doubles first (a pass over memory
  // the sums write anyway).
  static constexpr std::array<double, proto::kForceDoubles> nothing{};
  const auto put = [&](std::size_t i, const double* f, bool add) {
    for (std::size_t k = 0; k < 3; ++k)
    {
      forces[3 * i + k] = (add ? forces[3 * i + k] : 0.0) + f[k];
      fluidVelocities[3 * i + k] = (add ? fluidVelocities[3 * i + k] : 0.0) + f[5 + k];
    }
    owned_[i] = (add ? owned_[i] : 0.0) + f[3];
    beta[i] = (add ? beta[i] : 0.0) + f[4];
  };
  bool first = true;
  for (std::size_t p = 0; p < procs; ++p)
  {
    if (!exchanges(p))
      continue;
    const auto& reply = replies_[p];
    const auto& members = members_[p];
    const auto count = memberCount_[p];
    maxRe = std::max(maxRe, reply[1]);
    fluidMessages += std::lround(reply[2]);
    stats_.fluidExchangeSeconds = std::max(stats_.fluidExchangeSeconds, reply[3]);
    stats_.fluidStepSeconds = std::max(stats_.fluidStepSeconds, reply[4]);
    stats_.fluidExchangeCpuSeconds = std::max(stats_.fluidExchangeCpuSeconds, reply[5]);
    stats_.fluidStepCpuSeconds = std::max(stats_.fluidStepCpuSeconds, reply[6]);
    const double* values = &reply[proto::kReplyHeader];
    if (first)
      for (std::size_t i = 0, j = 0; i < n; ++i)
      {
        const bool given = j < count && members[j] == i;
        put(i, given ? values + proto::kForceDoubles * j++ : nothing.data(), false);
      }
    else
      for (std::size_t j = 0; j < count; ++j)
        put(members[j], values + proto::kForceDoubles * j, true);
    first = false;
  }
  for (std::size_t i = 0; first && i < n; ++i) // no fluid rank's box holds a particle here
    put(i, nothing.data(), false);
  if (demRanks_ > 1)
    MPI_Allreduce(MPI_IN_PLACE, &maxRe, 1, MPI_DOUBLE, MPI_MAX, dem_);
  stats_.messages = messages + fluidMessages;
  stats_.demDoubles = doubles;
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats_.waitSeconds = std::chrono::duration<double>(received - sent).count();
  if (const std::string lost = lostParticle(positions, indices); !lost.empty())
  {
    stop();
    throw std::runtime_error("FoamCoupling: particle " + lost + " is outside the fluid mesh of case '" +
                             settings_.caseDir + "'; the fluid solver was stopped");
  }
  return maxRe;
}

std::string FoamLink::lostParticle(std::span<const double> positions, std::span<const std::int64_t> indices)
{
  // The lowest index lost here, then over the DEM processes, and its position from its process.
  const auto n = owned_.size();
  std::size_t k = n;
  for (std::size_t i = 0; i < n && k == n; ++i)
    if (owned_[i] < 0.5)
      k = i;
  const auto indexOf = [&](std::size_t i) { return indices.empty() ? static_cast<std::int64_t>(i) : indices[i]; };
  std::int64_t lowest = k < n ? indexOf(k) : std::numeric_limits<std::int64_t>::max();
  if (demRanks_ > 1)
    MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_INT64_T, MPI_MIN, dem_);
  if (lowest == std::numeric_limits<std::int64_t>::max())
    return {};
  std::array<double, 3> x{};
  if (k < n && indexOf(k) == lowest)
    x = {positions[3 * k], positions[3 * k + 1], positions[3 * k + 2]};
  if (demRanks_ > 1)
    MPI_Allreduce(MPI_IN_PLACE, x.data(), 3, MPI_DOUBLE, MPI_SUM, dem_);
  std::ostringstream s;
  s << lowest << " at (" << x[0] << ", " << x[1] << ", " << x[2] << ")";
  return s.str();
}

void FoamLink::stop()
{
  stopWatchdog(); // the fluid ranks are about to exit
  if (!running())
    return;
  std::vector<int> command(static_cast<std::size_t>(proto::commandInts(demRanks_)), 0);
  command[0] = proto::kCommandStop;
  sendAll(command.data(), proto::commandInts(demRanks_), MPI_INT, proto::kTagCommand, "the stop command");
  MPI_Comm_disconnect(&inter_);
  if (dem_ != MPI_COMM_SELF)
    MPI_Comm_free(&dem_);
}

void addForceChange(std::span<const double> forces, std::span<const double> applied,
                    std::span<const std::int64_t> ids, std::span<double> persistent, std::span<double> step)
{
  if (forces.size() != 3 * ids.size() || applied.size() != forces.size() || step.size() != persistent.size())
    throw std::invalid_argument("addForceChange: the forces, the applied forces and the ids differ in size, or "
                                "the persistent and the step forces do");
  // Every id checked before anything changes.
  const auto bodies = static_cast<std::int64_t>(persistent.size() / 3);
  for (const std::int64_t id : ids)
    if (id < 0 || id >= bodies)
      throw std::invalid_argument("addForceChange: id " + std::to_string(id) + " is not a body");
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    const auto row = 3 * static_cast<std::size_t>(ids[i]);
    for (std::size_t k = 0; k < 3; ++k)
    {
      const double change = forces[3 * i + k] - applied[3 * i + k];
      persistent[row + k] += change;
      step[row + k] += change;
    }
  }
}

void finalizeMpi()
{
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (mpiStartedHere && !finalised)
    MPI_Finalize();
}
} // namespace talus::coupling
