#pragma once

#include "dem/core/Bodies.h"
#include "dem/core/Cell.h"
#include "dem/core/Contacts.h"
#include "dem/core/Domain.h"
#include "dem/core/EnergyTracker.h"
#include "dem/core/Engine.h"
#include "dem/core/Material.h"
#include "dem/core/StepLoop.h"

#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <memory>
#include <string>
#include <vector>

namespace talus::dem
{
/// A DEM simulation (Yade's Scene / Omega): bodies, materials, contacts, engines, clock.
class Scene
{
public:
  Bodies bodies;
  /// A deque: references to a material stay valid when more are added (Python holds them).
  std::deque<Material> materials;
  Contacts contacts;
  std::vector<std::shared_ptr<Engine>> engines;

  /// The split over processes (null: the whole scene is here). See Domain.
  std::shared_ptr<Domain> domain;
  /// The rows the step resets, gathers and integrates (Domain::ownedBodies; all rows when serial).
  std::size_t ownedBodies() const { return domain ? domain->ownedBodies(*this) : bodies.size(); }

  /// Energy tracking (O.trackEnergy / O.energy); off by default.
  EnergyTracker energy;

  /// Time every engine's stages per step (Yade's O.timingEnabled; talus.dem.analysis.timing.stats()
  /// prints them); off by default. Timing does not change how the step runs.
  bool timingEnabled = false;

  bool periodic = false; ///< space is the periodic repetition of `cell`
  Cell cell;

  /// A contact whose penetration exceeds this fraction of the smaller radius stops the run with
  /// an error (the time step is too large or the packing was set up overlapping); 0 disables.
  double maxOverlapRatio = 0.5;
  /// What such a contact does: stop the run with an error (Talus's default), or, as Yade does
  /// (which has no such check), let it go on, counted in overlapSteps and described by
  /// firstOverlap (the first one), which the Python layer turns into a warning.
  bool overlapStops = true;
  std::int64_t overlapSteps = 0; ///< steps that had such a contact while overlapStops was false
  std::string firstOverlap;      ///< the report of the first of them
  /// While energy is tracked, a total energy grown by more than this fraction of the energy that
  /// flowed (checked every energyGrowthCheckPeriod steps) stops the run with an error; 0 (the
  /// default) disables: energy put in by what the tracker does not see (a coupling's external
  /// forces, growing particles) would count as growth. Closed balances stay within about 1 %.
  double maxEnergyGrowth = 0;

  double dt = 1e-8;       ///< time step
  double time = 0;        ///< simulated time
  std::int64_t iter = 0;  ///< completed steps
  /// Incremented whenever bodies are added or erased, so the collider knows to re-detect.
  std::int64_t bodiesVersion = 0;
  /// Incremented whenever a body's mass, inertia, blocked DOFs or dynamic flag change, so
  /// engines caching them (the integrator's inverse masses) refresh.
  std::int64_t bodyPropertiesVersion = 0;

  /// Add a material after checking it.
  /// @return its index, for the bodies' `material`
  /// @throws std::invalid_argument naming the material and the parameter out of range
  int addMaterial(const Material& material);
  /// Add a sphere with mass and inertia from its material's density.
  /// @param center, radius where and how large (m)
  /// @param material index into `materials`
  /// @return the new body's id
  /// @throws std::invalid_argument naming the offending value (radius, centre, material)
  BodyId addSphere(const Vec3& center, double radius, int material);
  /// Add an infinite wall x[axis] = position, interacting on side `sense` (-1, 0, +1); fixed.
  /// In a periodic scene a wall meets the bodies themselves, never their periodic images: put it
  /// across a direction in which the cell is wider than the sample (a bed in a tall cell, the
  /// side walls of a channel in a wide one), as Yade's periodic scenes with walls do.
  /// @param position the wall's coordinate along `axis` (m)
  /// @param axis 0, 1 or 2 for x, y, z: the wall's normal
  /// @param sense +1 or -1: only bodies on that side of the wall touch it; 0: both sides
  /// @param material index into `materials`
  /// @return the new body's id
  /// @throws std::invalid_argument naming the wall for an axis not 0, 1 or 2, a sense not -1, 0
  ///         or 1, a position not finite or an unknown material
  BodyId addWall(double position, int axis, int sense, int material);
  /// Add a fixed triangular facet with vertices a, b, c (world coordinates); the body sits at
  /// the incentre, the normal is (b - a) x (c - a) normalised.
  /// @param a, b, c the vertices (m)
  /// @param material index into `materials`
  /// @param bounded false: Yade's noBound, the collider never pairs it (a factory's surface)
  /// @return the new body's id
  /// @throws std::invalid_argument if the triangle is degenerate or not finite, or the material
  ///         unknown
  BodyId addFacet(const Vec3& a, const Vec3& b, const Vec3& c, int material, bool bounded = true);
  /// Add a box of half-sizes `extents` centred at `center`, turned by `orientation`; mass and
  /// inertia from its material's density. Dynamic unless `fixed`.
  /// @param center, extents, orientation the centre (m), half-sizes along the box's axes (m,
  ///        >= 0) and the turn from world axes (any non-zero quaternion, normalised)
  /// @param material index into `materials`
  /// @param fixed not moved by forces (blocked in every DOF)
  /// @return the new body's id
  /// @throws std::invalid_argument naming the offending value
  BodyId addBox(const Vec3& center, const Vec3& extents, const Quat& orientation, int material, bool fixed);
  /// Add a Potential Block (Yade's PotentialBlock): the planes a_i x + b_i y + c_i z <= d_i + r
  /// (see makePotentialBlock), turned by `orientation` about its centroid, which is placed at
  /// `center` (null: where the planes put it). Volume, mass and principal inertia are computed;
  /// the body's frame is the principal frame. Dynamic unless `fixed`.
  /// @param a, b, c, d, r, R, isBoundary the planes and their parameters, as makePotentialBlock
  /// @param center where the centroid goes (m); null: where the planes put it
  /// @param orientation turn about the centroid (non-zero quaternion)
  /// @param material index into `materials`
  /// @param fixed not moved by forces
  /// @return the new body's id
  /// @throws std::invalid_argument naming the block ("PotentialBlock #id") and the bad value;
  ///         std::runtime_error if Talus was built without CLP
  BodyId addPotentialBlock(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
                           const std::vector<double>& d, double r, double R, bool isBoundary, const Vec3* center,
                           const Quat& orientation, int material, bool fixed);
  /// Add a Potential Particle (Yade's PotentialParticle; see makePotentialParticle): its shape
  /// frame (the planes' frame) placed at `position` and turned by `orientation`, as Yade's
  /// state.pos and state.ori. Volume, mass and principal inertia are computed; the body's
  /// frame is the principal frame at the centroid. Dynamic unless `fixed`.
  /// @param a, b, c, d, r, k, R, isBoundary the planes and their parameters, as makePotentialParticle
  /// @param position, orientation the shape frame's origin (m) and turn (non-zero quaternion)
  /// @param material index into `materials`
  /// @param fixed not moved by forces
  /// @return the new body's id
  /// @throws std::invalid_argument naming the particle ("PotentialParticle #id") and the bad value
  BodyId addPotentialParticle(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
                              const std::vector<double>& d, double r, double k, double R, bool isBoundary,
                              const Vec3& position, const Quat& orientation, int material, bool fixed);
  /// Make the bodies `members` (spheres, facets, boxes) a clump (Yade's O.bodies.clump): a rigid
  /// body at their centroid with principal axes and moments of their union; returns the
  /// clump's id. Members are summed whole (Yade's default), or, with `discretization` > 0 and
  /// overlapping spheres, the spheres' union is integrated on a grid whose cell is the shortest
  /// side of their bounding box / discretization (Yade's discretization). A member of another
  /// clump leaves it, as in Yade.
  /// @param members the member ids (at least one, none twice)
  /// @param discretization grid cells along the shortest side of the spheres' bounding box; 0:
  ///        members summed whole
  /// @return the clump's id (a new body)
  /// @throws std::invalid_argument naming a member of another shape, for no member, a member
  ///         listed twice, discretization < 0 or members without mass
  BodyId addClump(std::vector<BodyId> members, int discretization = 0);
  /// Yade's addToClump: `ids` join `clump`; a clump among them (or the clump of a member among
  /// them) joins with all its members and is erased. The clump's properties are recomputed.
  /// @param clump the id of a live clump
  /// @param ids the bodies joining it
  /// @param discretization as addClump's
  /// @throws std::invalid_argument for a body already in `clump` or of another shape, or
  ///         discretization < 0
  void addToClump(BodyId clump, const std::vector<BodyId>& ids, int discretization = 0);
  /// Yade's releaseFromClump: `member` leaves `clump` (which keeps at least 2 members) and
  /// moves on its own; the clump's properties are recomputed.
  /// @param member the body leaving
  /// @param clump its clump's id
  /// @param discretization as addClump's
  /// @throws std::invalid_argument if `member` is not a member of `clump`, the clump would keep
  ///         fewer than 2 members, or discretization < 0
  void releaseFromClump(BodyId member, BodyId clump, int discretization = 0);
  /// Recompute a clump's centroid, mass, principal inertia and member placement from its
  /// members' current state (the clump is left at rest).
  /// @param clump the id of a live clump
  /// @param discretization as addClump's
  /// @throws std::invalid_argument if the members have no mass
  void updateClump(BodyId clump, int discretization = 0);
  /// The members and their placement of a live clump.
  /// @param clump the clump's id
  /// @return its shape, stored in `bodies` (valid until clumps are added or erased)
  /// @throws std::out_of_range for an id that is not a live body
  /// @throws std::invalid_argument if `clump` is not a clump
  ClumpShape& clumpShape(BodyId clump);
  /// Make space periodic (or not). Positions stay as they are (the cell need not hold them,
  /// as in Yade); spheres, clumps, walls, facets and boxes can be periodic.
  /// @param on periodic or not
  /// @throws std::invalid_argument naming a Potential Block or Particle
  void setPeriodic(bool on);
  /// Set the cell's edges (columns of h); the cell must be non-degenerate with positive volume.
  /// @param h the cell's edge vectors as columns (m)
  /// @throws std::invalid_argument if h is not finite or its determinant not positive
  void setCellSize(const Mat3& h);

  /// Set the blocked degrees of freedom of a body (Dof bits).
  /// @param id a live body
  /// @param mask Dof bits (1, 2, 4: x, y, z translations; 8, 16, 32: rotations); a blocked DOF
  ///        keeps its velocity
  /// @throws std::out_of_range for an id that is not a live body
  /// @throws std::invalid_argument for a mask outside 0..63
  void setBlockedDofs(BodyId id, std::uint8_t mask);
  /// Make a body dynamic (moved by forces) or not (moved only by its imposed velocity).
  /// @param id a live body
  /// @param dynamic moved by forces
  /// @throws std::out_of_range for an id that is not a live body
  void setDynamic(BodyId id, bool dynamic);
  /// Replace a body's mass (kg) and principal inertia (kg m^2), as Yade's `state.mass = ...`.
  /// @throws std::out_of_range for an id that is not a live body
  /// @throws std::invalid_argument for a negative or non-finite value
  /// @param id a live body
  /// @param mass (kg), >= 0
  void setMass(BodyId id, double mass);
  /// @param id a live body
  /// @param inertia principal moments in the body's frame (kg m^2), each >= 0
  /// @throws std::out_of_range for an id that is not a live body
  /// @throws std::invalid_argument for a negative or non-finite value
  void setInertia(BodyId id, const Vec3& inertia);
  /// Remove a body and its contacts; its id is not reused (Yade's O.bodies.erase). Erasing a
  /// clump frees its members (or erases them too with `eraseClumpMembers`); erasing a member
  /// removes it from its clump, which keeps its mass, inertia and the other members' placement
  /// (as in Yade) and goes with its last member.
  /// @param id a live body
  /// @param eraseClumpMembers for a clump: erase its members too instead of freeing them
  /// @throws std::out_of_range for an id that is not a live body
  void erase(BodyId id, bool eraseClumpMembers = false);
  /// Remove every body and contact (Yade's O.bodies.clear): ids start again at 0. Materials,
  /// engines, the cell and the clock stay; engines holding body ids keep them, as in Yade.
  void clearBodies();
  /// Remove the contact of a pair (either order) with its state, as Yade's
  /// O.interactions.erase; the collider finds the pair again if it is still in the skin.
  /// @param id1, id2 the pair's body ids, either order
  /// @return whether there was one
  bool eraseContact(BodyId id1, BodyId id2);

  /// Run all engines once and advance the clock (with subStepping: one sub-step, see subStep).
  /// If an engine throws, the step is left half done. After an engine that leaves the scene
  /// whole (Engine::resumableAfterError: a PyRunner's Python error) the next step() or run()
  /// finishes that step from the engine after it, as the sub-steps of Yade's loop. After any
  /// other (contact histories updated, some bodies moved) the scene refuses further steps,
  /// naming the failure, until a checkpoint is loaded (which calls clearFailedStep()).
  /// @throws std::runtime_error after a failed step, or when called from inside a step (a
  ///         PyRunner asking for a step); whatever an engine throws is passed on
  void step();
  /// Forget a failed or unfinished step: the scene's state was replaced (a checkpoint was loaded).
  void clearFailedStep()
  {
    failedStep_.clear();
    subStep = -1;
  }

  /// Yade's sub-stepping (O.subStepping, O.subStep): with subStepping each step() runs one
  /// sub-step: -1 the step's start, then each engine, then (subStep == engines.size()) the end,
  /// which advances the clock. subStep is the sub-step to run next, -1 between steps; a step
  /// run whole has subStep 0 while its engines run. Turning subStepping off mid-step makes the
  /// next step() finish that step.
  int subStep = -1;
  bool subStepping = false;
  /// Engines set while a step runs (Yade's O._nextEngines): they replace `engines` when the
  /// next step starts, so that the running list is never changed under its loop.
  std::optional<std::vector<std::shared_ptr<Engine>>> nextEngines;
  /// Set the engines: at once between steps, else (subStep >= 0) as nextEngines.
  /// @param list the new engine list (shared: the caller may keep references to its engines)
  void setEngines(std::vector<std::shared_ptr<Engine>> list);
  /// Run `steps` steps (all steps until pause() if negative), stopping early after a step in
  /// which pause() was called. `poll` (optional) runs every 64 steps, e.g. to notice Ctrl-C.
  /// @param steps the number of steps; negative: until pause()
  /// @param poll called every 64 steps (may throw to stop the run, e.g. on Ctrl-C); empty: none
  /// @throws std::runtime_error as step() does
  void run(std::int64_t steps, const std::function<void()>& poll = {});
  /// Ask a running run() to stop after the current step (Yade's O.pause, e.g. from a PyRunner).
  void pause() { pauseRequested_ = true; }

  /// Yade's PWaveTimeStep: min over spheres of r sqrt(density / young).
  [[nodiscard]] double pWaveTimeStep() const;
  /// The free, moving sphere whose P-wave step r sqrt(density / young) is the smallest among
  /// those whose material's contact stiffness comes from young (not ViscElMat's tc or kn
  /// forms): the bound O.dt is checked against before contacts exist. id -1 if none.
  struct StiffestSphere
  {
    double step = std::numeric_limits<double>::infinity();
    BodyId id = -1;
  };
  /// @return the sphere and its step (s); id -1 and an infinite step if none
  [[nodiscard]] StiffestSphere stiffestSphere() const;
  /// Critical step of the stiffest contact alone, min over real contacts of
  /// 2 sqrt(m_reduced / kn) (a lower bound is what matters: packings need less, ~0.3 x P-wave).
  [[nodiscard]] double contactTimeStep() const;

  /// @param id any id
  /// @throws std::out_of_range naming the id if it is not a live body
  void checkBody(BodyId id) const;

  /// The rows an engine acting on the bodies `ids` (by the ids the user gave) acts on here: the
  /// ids themselves in a whole scene; split over processes, the rows of the bodies this process
  /// owns (walls and facets on every process), each other body left to the process owning it.
  /// @param ids body ids
  /// @param engine the engine, named in the error
  /// @return the rows, in the order of `ids`
  /// @throws std::out_of_range naming the engine and the id for an id that is not a live body
  [[nodiscard]] std::vector<BodyId> rowsActedOn(const std::vector<BodyId>& ids, const std::string& engine) const;

  /// How the engines run in a step (dem/step/'s scheduler).
  /// @return the scene's step loop, made on first use and owned by the scene
  [[nodiscard]] StepLoop& stepLoop() { return stepLoop_.get(); }

private:
  bool pauseRequested_ = false;
  bool stepping_ = false; ///< a step is running (its engines may not start another)
  StepLoopHolder stepLoop_;
  /// step() without forgetting what the step loop prepared for the next step (run()'s steps,
  /// between which nothing else touches the scene).
  void advance();
  /// Engine k (skipped if dead). If it throws, the step is marked for finishing from engine
  /// k + 1 or as failed (see step()).
  void runEngine(std::size_t k);
  /// The rest of a step: the energy check, then the clock.
  void endStep();
  std::string failedStep_; ///< message of the step that threw (transient), empty if none
  /// @throws std::invalid_argument (starting with `which`) unless `id` can be a clump member
  void checkClumpable(const std::string& which, BodyId id) const;
  /// Take an erased member out of its clump, which keeps its mass properties (Yade's erase);
  /// a clump left without members is erased too.
  void eraseClumpMember(BodyId member);
};
} // namespace talus::dem
