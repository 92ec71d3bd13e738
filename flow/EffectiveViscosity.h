#pragma once

#include "flow/VansParameters.h"

#include <span>

namespace talus::flow
{
/// Effective kinematic viscosity of the fluid phase at the mesh nodes (j = 0 .. nCell - 1).
///
/// The solid fraction at node j is the mean of the two cells around it, phi_j = (phi_{j-1} +
/// phi_j)/2; node 0 uses its cell's value. Einstein: nu (1 + 2.5 phi_j); PowerLaw:
/// nu (1 - phi_j)^-2.8, node 0 keeping Einstein's form as in Yade.
///
/// @param[in] model the closure
/// @param[in] nu kinematic viscosity of the pure fluid
/// @param[in] phiPart solid fraction per cell (nCell values)
/// @param[out] nuEff effective viscosity per node (nCell values)
/// @pre phiPart and nuEff have the same size, at least 2; every phi < 1
void effectiveViscosity(EffectiveViscosityModel model, double nu, std::span<const double> phiPart,
                        std::span<double> nuEff);
} // namespace talus::flow
