#pragma once
// The message protocol between the DEM process (coupling/) and the OpenFOAM coupling solvers
// (foam-solvers/). This header is the protocol's description: plain constants, no OpenFOAM and
// no Talus types, so both sides include it without depending on each other's code.
//
// Processes: P_DEM DEM processes (the DEM's communicator: one process, or every process of a
// DEM decomposed over MPI ranks; "DEM rank d" below is its rank there) and P fluid ranks started
// by them with MPI_Comm_spawn, collective over the DEM processes (root: DEM rank 0); every message
// below travels on the intercommunicator (the DEM side's result of MPI_Comm_spawn, the fluid
// side's MPI_Comm_get_parent). Fluid ranks are addressed by their rank in the spawned world
// (0 .. P-1), DEM ranks by theirs in the DEM's communicator (0 .. P_DEM-1). All messages are bulk
// arrays, whatever the particle count. Each fluid rank gets only the particles inside its
// sub-mesh's bounding box widened by its margin (inBox below, the same test on both sides), so
// the data per rank is O(N/P) plus a halo; each particle is sent by one DEM rank only (the rank
// owning it), and a DEM rank exchanges particles only with the fluid ranks it has particles for
// (rank 0 with every fluid rank: it carries the commands and collects the fluid ranks' reports).
// The fluid ranks settle the particles they share (ownership, envelope sums) with one message
// per neighbouring rank per reduction.
//
// 1. Handshake (once, before the fluid's first step), between DEM rank 0 and every fluid rank
//    (DEM rank 0 passes what it learns on to the other DEM ranks)
//    DEM -> every fluid rank, tag kTagHello:   int[kHelloInts] = {kMagic, kVersion, nParticles,
//                                               pid, hostHash(hostname)}
//                             tag kTagHelloD:  double[kHelloDoubles] = {rhoFluid [kg/m3],
//                                               nu [m2/s], gx, gy, gz [m/s2], couplingInterval [s]}
//    every fluid rank -> DEM, tag kTagPid:     int[2] = {pid, hostHash(hostname)}, sent as soon
//                                               as the Hello arrives, before the case is read
//    every fluid rank -> DEM, tag kTagBox:     double[kBoxDoubles] = {xmin, ymin, zmin, xmax, ymax,
//                                               zmax, margin}: its sub-mesh's bounding box and how
//                                               far beyond it particles still concern it (the
//                                               envelope's cut-off), sent once the case is read
//    fluid rank 0 -> DEM, tag kTagHelloReply:  int[kReplyInts] = {kMagic, kVersion, status, nProcs,
//                                               nCells (global)}
//                         tag kTagHelloReplyD: double[kReplyDoubles] = {deltaT [s], rho, nu,
//                                               the particle Reynolds number up to which
//                                               the solver's drag law holds}
//                         tag kTagMessage:     char[kMessageChars], NUL-terminated reason
//                                               (empty if status == kStatusOk)
//    The process ids let each side notice within a fraction of a second that a process on the
//    same host has died (kill(pid, 0)), instead of waiting for the timeout.
//    The fluid side compares magic, version, rho, nu and gravity with its case (relative tolerance
//    kMatchTolerance) and answers kStatusMismatch with the reason; both sides then disconnect and
//    stop with that message. Otherwise the DEM side may still refuse a fluid deltaT larger than
//    the coupling interval: it then sends kCommandStop.
//
// 2. Each fluid step (the DEM drives the fluid's time loop)
//    DEM rank 0 -> every fluid rank, tag kTagCommand: int[commandInts(P_DEM)] = {kCommandStep |
//             kCommandStop, n, n_0, ..., n_(P_DEM-1)}: n the number of particles for that rank
//             (those inside its widened box), n_d of them from DEM rank d (the DEM ranks tell
//             rank 0 their counts first, among themselves)
//    if kCommandStep:
//      DEM rank d -> the fluid rank, tag kTagParticles, if n_d > 0 or d = 0:
//             double[kParticleDoubles * n_d], per particle {x, y, z, vx, vy, vz, radius, index},
//             in increasing index; the index is a particle's own, unique over the DEM ranks and
//             the same from exchange to exchange (the coupled particle's number in one DEM
//             process, its body id in a decomposed DEM). The fluid rank orders the particles of
//             all its senders by index (what it computes does not depend on the DEM's ranks).
//      the fluid rank -> every DEM rank d that sent it particles (d = 0 always), tag kTagForces:
//             double[kReplyHeader + kForceDoubles * n_d]:
//             {status (kStatusOk), the largest particle Reynolds number on the rank, messages
//             this rank sent to other fluid ranks in this exchange, the wall time [s] of this
//             rank's previous exchange (from the command's arrival to the forces sent: receiving
//             the particles, locating them, the forces, the halo messages, the reply), the wall
//             time [s] of its previous fluid step (solution and output), then the same two as
//             the rank's CPU time [s]; all 0 before the first, and the previous ones because a
//             reply cannot carry the time of its own sending}, then per particle, in the order DEM
//             rank d sent them, {fx, fy, fz, owned, beta,
//             ufx, ufy, ufz}: the hydrodynamic force on the particle from the one rank that
//             owns the particle's cell (the lowest rank finding it), zeros and owned = 0 on the
//             other ranks; the drag in it is
//             beta (uf - u_p) with u_p the velocity sent, so that the DEM side may re-evaluate it
//             with the particle's current velocity at each of its sub-steps. A particle owned nowhere has left the mesh (the DEM
//             ranks, which learn it together, then send kCommandStop and report it).
//    After the reply the fluid advances one deltaT with the reaction of the drag as a source.
//    kCommandStop: the fluid writes its fields, disconnects and exits.
//    kStatusError is reserved for fluid-side errors reported in the reply (not sent yet: a
//    failing solver exits, and the DEM notices through its pid or the timeout).
//
// Timeouts: each side waits at most a configured time for the other (DEM: FoamCoupling.timeout,
// fluid: the -couplingTimeout option, which FoamCoupling sets to its own) and then aborts every
// process with a message. The fluid waits for the DEM's next command from its reply on; a DEM
// that sends nothing for longer (stuck between two exchanges, or stopped) is woken (SIGCONT, same
// host) and ends itself: its watchdog thread counts the same silence and, like its waits, tells
// the fluid's timeout from a fluid rank that died.
namespace talus::foam_protocol
{
constexpr int kMagic = 0x54414c53; // "TALS"
constexpr int kVersion = 5;

constexpr int kTagHello = 6101;
constexpr int kTagHelloD = 6102;
constexpr int kTagHelloReply = 6103;
constexpr int kTagHelloReplyD = 6104;
constexpr int kTagMessage = 6105;
constexpr int kTagCommand = 6106;
constexpr int kTagParticles = 6107;
constexpr int kTagForces = 6108;
constexpr int kTagPid = 6109;
constexpr int kTagBox = 6110;
// Between fluid ranks (their own MPI_COMM_WORLD): partial sums over shared particles.
constexpr int kTagHalo = 6111;

constexpr int kHelloInts = 5;
constexpr int kHelloDoubles = 6;
constexpr int kReplyInts = 5;
constexpr int kReplyDoubles = 4;
constexpr int kMessageChars = 1024;
constexpr int kParticleDoubles = 8;
constexpr int kForceDoubles = 8;
constexpr int kReplyHeader = 7;
constexpr int kBoxDoubles = 7;

constexpr int kStatusOk = 0;
constexpr int kStatusMismatch = 1;
constexpr int kStatusError = 2;

constexpr int kCommandStop = 0;
constexpr int kCommandStep = 1;

/// Length of a command (kTagCommand) with `demRanks` DEM ranks.
constexpr int commandInts(int demRanks)
{
  return 2 + demRanks;
}

/// A non-negative hash of a host name (FNV-1a), to tell whether a peer runs on this host.
/// @param name the host name, null-terminated
/// @return the hash, in [0, 2^31)
inline int hostHash(const char* name)
{
  unsigned h = 2166136261u;
  for (const char* c = name; *c; ++c)
    h = (h ^ static_cast<unsigned char>(*c)) * 16777619u;
  return static_cast<int>(h & 0x7fffffffu);
}

/// Whether the point (x, y, z) concerns a fluid rank whose box is {xmin, ymin, zmin, xmax, ymax,
/// zmax, margin}. Both sides decide with this function, on the same numbers.
/// @param box the rank's 7 values
/// @param x, y, z the point (m)
/// @return true inside the box widened by the margin, faces included
inline bool inBox(const double* box, double x, double y, double z)
{
  const double m = box[6];
  return x >= box[0] - m && x <= box[3] + m && y >= box[1] - m && y <= box[4] + m &&
         z >= box[2] - m && z <= box[5] + m;
}

/// Relative tolerance of the handshake's comparison of fluid properties and gravity.
constexpr double kMatchTolerance = 1e-9;
} // namespace talus::foam_protocol
