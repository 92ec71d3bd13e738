#pragma once

#include "dem/base/ExactSum.h"
#include "dem/base/types.h"

#include <span>
#include <utility>
#include <vector>

namespace talus::dem
{
class Scene;
struct Contact;

/// Whether this process counts contact `c` in a sum over contacts: a real contact, counted by one
/// process when the scene is split (Domain::countsContact), always when it is whole.
bool countsInSums(const Scene& scene, const Contact& c);

/// Split over processes (Scene::domain), loveWeberStress, contactStiffnessTangent,
/// coordinationNumber, fabricTensor and sphereVolume give the whole scene's value on every
/// process: each process sums the bodies and contacts it counts (Domain::countsBody,
/// countsContact) and the sums are added over the processes (collective: every process calls
/// them; within round-off of the serial values, the shares being added in another order).

/// Yade's unbalancedForce: the mean (or, with useMaxForce, the largest) magnitude of the total
/// force on dynamic bodies, gravity included, divided by the mean magnitude of contact forces.
/// 0 for a scene at equilibrium; NaN when there is no contact force to compare with. Split over
/// processes, the whole scene's, its sums exact: the bits of one process (collective: every
/// process calls it).
/// @param scene the scene, its forces those of the last step
/// @param gravity the acceleration of gravity the integrator adds (sceneGravity(scene) for the
///        scene's own)
/// @param useMaxForce the largest total force instead of the mean
/// @return the ratio, dimensionless
double unbalancedForce(const Scene& scene, const Vec3& gravity, bool useMaxForce = false);

/// Add the force the contacts put on body `row` (the contacts' part of its force, each contact's
/// as the step's gather adds it) to `force` exactly, a sum per component, and with `stiffness`
/// the normal stiffness of those of its contacts carrying a normal force. Split over processes,
/// a body every process holds (a wall) has this process's contacts only: summed exactly over
/// the processes (sumExactly), the shares give the bits of one process.
/// @param scene the scene, its contact index by body that of the last detection
/// @param row the body's row
/// @param force three exact sums, added to (N)
/// @param stiffness added to (N/m), or null
void addContactForce(const Scene& scene, std::size_t row, std::span<ExactSum, 3> force, ExactSum* stiffness = nullptr);

/// Yade's totalForceInVolume: the sum over real contacts of the absolute components of each
/// contact's force (normal + shear), and the contacts' mean isotropic stiffness kn/3 + 2 ks/3.
/// Split over processes, the whole scene's (each contact counted once, the sums exact: the bits of
/// one process; collective).
/// @return the summed absolute force components (N) and the mean stiffness (N/m), -1 without contacts
std::pair<Vec3, double> totalForceInVolume(const Scene& scene);

/// Gravity of the scene's (first) NewtonIntegrator, zero without one: what unbalancedForce
/// needs when an engine calls it.
/// @return the gravity vector (m/s^2)
Vec3 sceneGravity(const Scene& scene);

/// Love-Weber homogenised stress -(1/V) sum over real contacts of f (x) l, with f the force on
/// body 2 and l the branch vector from body 1's centre to body 2's (image) centre (for a wall or
/// facet: from the sphere's closest point on it to its centre); compression is negative, as
/// Yade's getStress. `volume` <= 0 means the periodic cell's volume.
/// @param volume the sample's volume (m^3); <= 0: the periodic cell's
/// @return the stress tensor (Pa)
/// @throws std::invalid_argument if volume <= 0 and the scene is not periodic
Mat3 loveWeberStress(const Scene& scene, double volume = -1);

/// Contact-stiffness tangent operator of the homogenised stress, as a 6x6 Voigt matrix (order
/// xx, yy, zz, yz, xz, xy; shear strains as engineering strains 2 eps_ij), so that a small
/// homogeneous strain increment deps changes loveWeberStress by about C deps when every particle
/// follows the affine field and no contact slides, opens or closes:
///   D_ijkl = (1/V) sum_c [kn n_i n_k + alpha ks (delta_ik - n_i n_k)] l_j l_l,
/// symmetrised in (i,j) and (k,l). kn, ks are the contacts' current (tangent) stiffnesses;
/// alpha = (r1 + r2) / |l| between spheres (the shear increment's ratcheting factor), 1 otherwise. It is
/// the stiffness of the packing without particle relaxation and without the rotation of contact
/// forces (an upper bound of the relaxed response), the operator the seed's FEMxDEM procedure
/// hands to the finite elements. `volume` <= 0 means the periodic cell's volume.
///
/// TangentForm::Yade gives instead the operator of Yade's getStressAndTangent (Shop.cpp, for its
/// FEMxDEM coupling): sum of kn a a^T + ks b b^T with a = sym(n (x) l), b = sym(t (x) l) in Voigt
/// form, t the direction of the current shear force (no shear term while it is zero). It keeps
/// only the shear stiffness along the existing shear force, so it under-estimates the shear
/// response; it is there to reproduce Yade's numbers.
enum class TangentForm
{
  Full,
  Yade
};
/// @param volume the sample's volume (m^3); <= 0: the periodic cell's
/// @param form the full operator or Yade's
/// @return the 6x6 tangent (Pa), Voigt order xx, yy, zz, yz, xz, xy
/// @throws std::invalid_argument if volume <= 0 and the scene is not periodic
Eigen::Matrix<double, 6, 6> contactStiffnessTangent(const Scene& scene, double volume = -1,
                                                    TangentForm form = TangentForm::Full);

/// Yade's avgNumInteractions: 2 Nc / N over live spheres (optionally not counting spheres with
/// no contact, `skipFree`).
/// @param skipFree leave out the spheres with no real contact
/// @return the mean number of real contacts per sphere; 0 without spheres
double coordinationNumber(const Scene& scene, bool skipFree = false);

/// Fabric tensor (1/Nc) sum n (x) n over real sphere-sphere contacts.
/// @return the symmetric fabric tensor, trace 1 (zero without such contacts)
Mat3 fabricTensor(const Scene& scene);

/// Yade's bodyStressTensors: per body, the mean stress in the solid sphere from its contact
/// forces, (1/V) sum over its real contacts of f (x) a, with f the force on it, a the arm from
/// its centre to the contact point and V = 4/3 pi r^3 (exact for a sphere in static
/// equilibrium loaded at points, where it is symmetric; Yade's index order otherwise);
/// compression is negative. Contact moments are not included, as in Yade. Zero for bodies that
/// are not spheres. Indexed by body id (split over processes: by row, right for the bodies the
/// process owns, which have all their contacts there).
/// @return one stress tensor (Pa) per body id
std::vector<Mat3> bodyStressTensors(const Scene& scene);

/// Total volume of the live spheres.
/// @return the volume (m^3), overlaps counted twice
double sphereVolume(const Scene& scene);
} // namespace talus::dem
