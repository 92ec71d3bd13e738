#pragma once

#include "dem/interface/RVE.h"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace talus::fem
{
using dem::Mat3;
using dem::Mat6;
using dem::RVE;
using dem::RVEEngines;
using dem::RVEState;
using dem::Vec3;

/// The RVEs of a set of Gauss points, called together (the seed's escript-side calls, batched
/// in C++): every call loops over the RVEs with OpenMP, one RVE per thread at a time (the DEM
/// loops inside an RVE then run on one thread).
///
/// Gradients are `dim x dim` per point, dim = 3, or 2 for plane strain (the RVE is then
/// deformed with zero out-of-plane components). Results use the same dimension: stress dim x dim,
/// tangent in Voigt order (3D: xx, yy, zz, yz, xz, xy; 2D: xx, yy, xy) with engineering shear.
class GaussPointRVEs
{
public:
  /// @param rves one RVE per Gauss point, in the points' order; taken over (owned here)
  /// @throws std::invalid_argument if the list is empty or an entry is null (naming the point)
  explicit GaussPointRVEs(std::vector<std::unique_ptr<RVE>> rves);

  /// The number of Gauss points (RVEs).
  [[nodiscard]] std::size_t size() const { return rves_.size(); }
  /// @param i the Gauss point's index
  /// @return its RVE, owned here (valid while this object lives)
  /// @throws std::out_of_range if i >= size()
  [[nodiscard]] RVE& rve(std::size_t i) { return *rves_.at(i); }

  /// Deform every RVE from its committed state by its displacement gradient (`grads`: points x
  /// dim x dim, row-major) over nSteps DEM steps each (one count for every point, or one per
  /// point: Yade's FEMxDEM scales the steps of each point with the size of its own increment).
  /// @param grads the displacement gradients du/dX relative to each committed configuration
  ///        (dimensionless), size() x dim x dim
  /// @param dim 3, or 2 for plane strain
  /// @param nSteps DEM steps for every point (>= 1); the second form: one count per point, or one
  /// @throws std::invalid_argument for dim other than 2 or 3, a step count < 1, a count mismatch
  ///         or a non-finite gradient, naming the
  ///         Gauss point, before any RVE moves
  /// @throws std::runtime_error naming the Gauss points whose DEM run failed (those RVEs are
  ///         back at their committed state; the others hold their trial state)
  void deform(std::span<const double> grads, int dim, int nSteps);
  void deform(std::span<const double> grads, int dim, std::span<const int> nSteps);
  /// Stress (points x dim x dim) and tangent (points x v x v, v = 6 or 3) of every RVE, in its
  /// current (trial or committed) state; in 2D the in-plane components of the 3D results.
  /// @param stress filled, row-major per point (Pa, compression negative)
  /// @param tangent filled, row-major per point (Pa), Voigt order as above
  /// @param dim 3, or 2 for plane strain
  /// @param form the full contact-stiffness operator or Yade's (see contactStiffnessTangent)
  /// @throws std::invalid_argument for dim other than 2 or 3 or arrays of the wrong size
  void getStressAndTangent(std::span<double> stress, std::span<double> tangent, int dim,
                           dem::TangentForm form = dem::TangentForm::Full) const;
  /// Every RVE's read-outs (RVE::state), in the points' order.
  [[nodiscard]] std::vector<RVEState> states() const;
  /// Make every RVE's trial state its committed one (the FE step converged).
  void commit();
  /// Return every RVE to its committed state (the FE iteration is abandoned).
  void rollback();

private:
  std::vector<std::unique_ptr<RVE>> rves_;
};
} // namespace talus::fem
