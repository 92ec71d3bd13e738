#pragma once

namespace talus::flow
{
/// Darcy friction factor of the side walls of a channel, for the wall-friction sink term of the
/// VANS model: the fixed point of
///
///     f = (2 ln(Re sqrt(f)) + 0.32)^-2,   Re = max(1e-10, |u| W / nu),
///
/// iterated from f = 0.32^-2 until the relative change is below 1e-2, and 0 if 100 iterations
/// do not get there. This is Graf & Altinakar's smooth-wall law exactly as Yade 2023.02a
/// evaluates it (natural logarithm, no Re/4), so that results can be compared with Yade; later
/// Yade versions write 2 log10(Re sqrt(f)/4) + 0.32 instead.
///
/// @param[in] reynolds the channel Reynolds number |u| W / nu (clamped below at 1e-10)
/// @return the friction factor f (not yet multiplied by fluidFrictionCoef)
[[nodiscard]] double wallFrictionFactor(double reynolds);
} // namespace talus::flow
