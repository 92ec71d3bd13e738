#pragma once

#include "flow/VansParameters.h"

#include <span>

namespace talus::flow
{
/// Mixing length l_m at the mesh nodes z_j (j = 0 .. nCell - 1), where the eddy viscosity
/// nu_t = l_m^2 |du/dz| of the VANS model lives.
///
/// - Prandtl: l_m = kappa z_j.
/// - FreeSurface: l_m = kappa z_j sqrt(1 - z_j/h), h = z_{nCell-1}; zero at the surface.
/// - LiSawamoto: l_m(z_j) = sum_{k<j} kappa (phiMax - phi_k)/phiMax deltaZ, where every cell
///   below the highest one with phi >= phiMax counts as phi = phiMax, so turbulence is fully
///   damped inside the bed and recovers kappa z above it. With no cell at phiMax, nothing is
///   clipped (Yade reads out of its array in that case).
///
/// @param[in] model the closure
/// @param[in] kappa von Karman constant
/// @param[in] phiMax maximum solid fraction (LiSawamoto only)
/// @param[in] z node elevations, z_0 = 0, step deltaZ (nCell values)
/// @param[in] deltaZ mesh step
/// @param[in] phiPart solid fraction per cell (nCell values; LiSawamoto only)
/// @param[out] lm mixing length per node (nCell values); lm[0] = 0
/// @pre z, phiPart and lm have the same size, at least 2
void mixingLength(MixingLengthModel model, double kappa, double phiMax, std::span<const double> z,
                  double deltaZ, std::span<const double> phiPart, std::span<double> lm);
} // namespace talus::flow
