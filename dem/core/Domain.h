#pragma once

#include "dem/base/ExactSum.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace talus::dem
{
class Scene;

/// How a scene is split over processes, as the step and the measurements see it. A serial
/// scene has none (Scene::domain is null) and every call site then does what it always did;
/// dem/distributed/ provides the MPI one. The step calls the domain at fixed points (its
/// communication stages) so that no engine calls MPI itself; measurements call its reductions so
/// that a script reads global answers on every process.
class Domain
{
public:
  virtual ~Domain() = default;

  /// The rows the step resets, gathers and integrates: [0, ownedBodies). Detection and contacts
  /// see all rows. The MPI domain interleaves its ghosts (read-only copies of bodies other
  /// processes own) with its own bodies in global-id order, so that every contact has the
  /// orientation and every body sums its contacts in the order of the serial scene (the same
  /// bits): its ownedBodies is every row; the integrator leaves out the rows it does not own
  /// (owns()), whose state their owners send in afterIntegration.
  /// @return the number of rows the per-body stages take
  virtual std::size_t ownedBodies(const Scene& scene) const = 0;

  /// Whether row `row` is this process's body (false: a ghost, not integrated here).
  /// Measurements count owned rows.
  /// @param row a row of scene.bodies
  /// @return true for an owned body (or one every process holds)
  virtual bool owns(std::size_t row) const = 0;

  /// Whether this process computes the contact of rows `row1` and `row2`: one of them is its own
  /// (a contact across two processes is computed by both, each applying the force to its own
  /// body), and a body every process holds (a wall) meets only the bodies owned here.
  /// @param row1, row2 the contact's two rows
  /// @return whether the contact is computed here
  virtual bool computesPair(std::size_t row1, std::size_t row2) const = 0;

  /// Whether sums over bodies (energies, extrema, critical steps) count row `row` here: each
  /// body is counted by one process only. By default the rows this process owns.
  /// @param row a row of scene.bodies
  /// @return true if this process counts the body
  virtual bool countsBody(std::size_t row) const { return owns(row); }

  /// Whether sums over contacts (energies, stresses, fabric) count the contact of rows `row1`
  /// and `row2` here: each contact is counted by one process only, although a contact across
  /// two processes is computed by both. By default every contact this process computes.
  /// @param row1, row2 the contact's two rows
  /// @return true if this process counts the contact
  virtual bool countsContact(std::size_t row1, std::size_t row2) const { return computesPair(row1, row2); }

  /// What `rowOf` returns for a body another process holds, and for an id that names no live
  /// body (never a body of the scene, or erased).
  static constexpr std::int64_t elsewhere = -1, noBody = -2;

  /// The row of body `id` (its id in the scene the user built) on this process, for what acts
  /// on bodies named by id (kinematic and force engines). By default the rows are the ids.
  /// @param id a body id
  /// @return its row here (which may be a ghost: see owns), `elsewhere` or `noBody`
  virtual std::int64_t rowOf(std::int64_t id) const { return id; }

  /// Before the collider re-detects: bodies that left this process's region move to their new
  /// owner with their contacts' state, and the ghost layer is rebuilt (rebalancing when due).
  /// @throws std::runtime_error naming the body when one moved further than the ghost layer allows
  virtual void beforeDetection(Scene& scene) = 0;

  /// After the integration: every ghost takes its owner's new state.
  virtual void afterIntegration(Scene& scene) = 0;

  /// Element-wise sums over processes, in place (energies, unbalanced force, stresses).
  /// @param values this process's values, replaced by the sums; the same length on every process
  virtual void sum(std::span<double> values) const = 0;

  /// The smallest value over processes (critical time steps). Every process must call it.
  /// @param value this process's value
  /// @return the minimum over all processes
  virtual double min(double value) const = 0;

  /// Element-wise minima over processes, in place (maxima as minima of the negated values): the
  /// skin check's displacements in one reduction per step.
  /// @param values this process's values, replaced by the minima; the same length on every process
  virtual void min(std::span<double> values) const = 0;
};

/// Domain::countsBody for a scene split by `domain`, every body when it is not split (null).
inline bool countsBody(const Domain* domain, std::size_t row) { return !domain || domain->countsBody(row); }

/// Sums over the processes of a scene split by `domain` of each process's exact sums, in place
/// (nothing when it is not split, null): the same bits at any process count.
/// @param sums this process's shares, replaced by the totals; as many on every process
inline void sumExactly(const Domain* domain, std::span<ExactSum> sums)
{
  if (!domain)
    return;
  std::vector<double> parts(sums.size() * ExactSum::partCount);
  for (std::size_t k = 0; k < sums.size(); ++k)
    sums[k].parts(std::span<double>(parts).subspan(k * ExactSum::partCount, ExactSum::partCount));
  domain->sum(parts);
  for (std::size_t k = 0; k < sums.size(); ++k)
    sums[k] = ExactSum::fromParts(std::span<const double>(parts).subspan(k * ExactSum::partCount, ExactSum::partCount));
}

/// Domain::countsContact for a scene split by `domain`, every contact when it is not split (null).
inline bool countsContact(const Domain* domain, std::size_t row1, std::size_t row2)
{
  return !domain || domain->countsContact(row1, row2);
}
} // namespace talus::dem
