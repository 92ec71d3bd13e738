#pragma once

// Motion parts of the contact laws: what a law reads of the bodies' motion at a contact besides
// the geometry's kinematics (Contact::shearIncrement, incidentVelocity), made once per contact
// and step and handed to the damping, tangential and moments parts. Each:
//   Motion(Contact&, const StepContext&);   // may move the contact's point to the law's own
#include "dem/laws/ContactLaw.h"

namespace talus::dem::parts
{
/// Nothing beyond the geometry's kinematics.
struct NoMotion
{
  /// Reads nothing.
  NoMotion(const Contact& /*c*/, const StepContext& /*step*/) {}
};
} // namespace talus::dem::parts
