#pragma once

// The bond part's strength in shear (cohesion with breakage; its state is BondState in
// core/ContactExtra.h): what the Coulomb cap (Coulomb.h) caps a bonded contact's shear force at,
// and a broken one's.
#include <algorithm>

namespace talus::dem::parts
{
/// Mohr-Coulomb with a tension cut-off: the bond's cohesion (a force) plus fn tan(phi), fn the
/// signed normal force, never below 0; `cohesionOnly` (Yade's cohesionDisablesFriction): the
/// cohesion alone while there is one.
inline double bondedShearStrength(double cohesion, double fn, double tanPhi, bool cohesionOnly = false)
{
  double strength = cohesion;
  if (!cohesionOnly || cohesion == 0)
    strength += fn * tanPhi;
  return std::max(0.0, strength);
}

/// Friction alone (no bond, or a broken one): fn tan(phi) when pressed, 0 when pulled.
inline double frictionStrength(double fn, double tanPhi) { return std::max(0.0, fn * tanPhi); }
} // namespace talus::dem::parts
