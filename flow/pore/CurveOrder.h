#pragma once
// A local order of the pores: along a Morton (Z-order) curve through their centres, so that pores
// close in space come close in the order. The pore ids stay CGAL's cell order (Yade's: users,
// the two-phase engine and Yade-side tests see them), which follows the insertion history and is
// scattered in space when the spheres enter one by one in Yade's order; the pressure solver numbers
// its rows in this order instead, which keeps the multigrids' reads in the caches (the geometry's
// loops stay in CGAL's order, local enough for them: docs/flow.md, "The solvers' rows along a curve").
#include "flow/pore/PoreNetwork.h"

#include <cstdint>
#include <vector>

namespace talus::flow::pore
{
/// The Morton key of x in the box [lo, hi] (clamped to it), `bits` bits a coordinate
/// (interleaved: x in the lowest bit), bits <= 21.
/// @param x the point
/// @param lo, hi the box's corners
/// @param bits the resolution along each axis
/// @return the key, < 2^(3 bits)
std::uint64_t mortonKey(const Vec3& x, const Vec3& lo, const Vec3& hi, int bits = 21);

/// The pore indices along a Morton curve through the pore centres in the box of the real spheres
/// (centres outside it, of pores between fictitious spheres, clamped to it), ties by index: a
/// permutation of 0 .. pores - 1, the same for the same network.
/// @param net a network with its pore centres
/// @return net.pores.size() indices
std::vector<int> poresAlongCurve(const PoreNetwork& net);
} // namespace talus::flow::pore
