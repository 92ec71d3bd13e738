#pragma once

#include "dem/base/types.h"

#include <cstdint>
#include <tuple>
#include <utility>

namespace talus::dem
{
/// One field of a contact-law part's state, declared once beside the field: the checkpoint
/// stores it as /contacts/extra/<name>, Python shows it under `python` (Yade's attribute name),
/// and whatever moves contacts (the collider's merge, a migration between processes) copies
/// the whole ContactExtra. Types: double, Vec3, Quat, std::uint8_t.
template <class Part, class T>
struct StateField
{
  const char* name;         ///< the C++ member's name, the checkpoint's dataset
  T Part::*member;
  const char* python;       ///< the key of talus._dem.contact_extra (Yade's name)
  bool flag = false;        ///< a byte holding yes/no (a bool in Python)
  bool stored = true;       ///< checkpointed; false: the geometry sets it again at every step

  /// The same field shown in Python under Yade's name.
  /// @param yadeName the Python key (a string literal: the pointer is kept)
  /// @return a copy with `python` replaced
  [[nodiscard]] constexpr StateField yade(const char* yadeName) const
  {
    StateField f = *this;
    f.python = yadeName;
    return f;
  }
  /// The same field, not checkpointed (the contact geometry recomputes it before any law reads it).
  [[nodiscard]] constexpr StateField transient() const
  {
    StateField f = *this;
    f.stored = false;
    return f;
  }
};

/// A field of a part's state (Part::fields() lists them).
/// @param name the member's name (a string literal: the pointer is kept), also its Python key
/// @param member the member pointer
/// @return the field, checkpointed, not a flag
template <class Part, class T>
constexpr StateField<Part, T> field(const char* name, T Part::*member)
{
  return {name, member, name};
}
/// A yes/no byte of a part's state.
/// @param name the member's name (a string literal: the pointer is kept), also its Python key
/// @param member the member pointer
/// @return the field, checkpointed, a bool in Python
template <class Part>
constexpr StateField<Part, std::uint8_t> flag(const char* name, std::uint8_t Part::*member)
{
  return {name, member, name, true};
}

// The state of each part of the contact laws (dem/laws/parts/) that keeps some. Each part
// lists its fields once, in `fields()`; everything else (checkpoint, bindings) follows.

/// Hertz normal spring with Thornton's damping (Yade's MindlinPhys): F_n = kno u^1.5,
/// k_s = kso u^0.5; betan, betas: damping ratios (fractions of the critical damping 2 sqrt(m kn)).
struct HertzState
{
  double kno = 0, kso = 0, betan = 0, betas = 0;
  /// @return the part's StateFields, in the checkpoint's and Python's order
  static constexpr auto fields()
  {
    return std::tuple{field("kno", &HertzState::kno), field("kso", &HertzState::kso),
                      field("betan", &HertzState::betan), field("betas", &HertzState::betas)};
  }
};

/// Relative rotation of the two bodies (Yade's ScGeom6D): orientations when the contact (or its
/// bond) started; twist (rotation about the normal) and bending (rotation vector normal to it) of
/// body 1 relative to body 2 since then.
struct RotationState
{
  Quat initialOrientation1 = Quat::Identity(), initialOrientation2 = Quat::Identity();
  Vec3 bending = Vec3::Zero();
  double twist = 0;
  /// @return the part's StateFields, in the checkpoint's and Python's order
  static constexpr auto fields()
  {
    return std::tuple{field("twist", &RotationState::twist), field("bending", &RotationState::bending),
                      field("initialOrientation1", &RotationState::initialOrientation1),
                      field("initialOrientation2", &RotationState::initialOrientation2)};
  }
};

/// A bond (cohesion with breakage; Yade's CohFrictPhys, and KnKsPBPhys's rock joints): strengths
/// (forces), plastic normal displacement unp with its limit unpMax (negative: none), and the
/// flags: no bond any more (cohesionBroken), no tension (tensionBroken, rock joints), breaks for
/// good at its first failure (fragile), cohesion replaces friction (cohesionDisablesFriction).
struct BondState
{
  double normalAdhesion = 0, shearAdhesion = 0, unp = 0, unpMax = -1;
  std::uint8_t cohesionBroken = 1; ///< no bond (bodies interact only by contact)
  std::uint8_t tensionBroken = 1;
  std::uint8_t fragile = 1;
  std::uint8_t cohesionDisablesFriction = 0;
  /// @return the part's StateFields, in the checkpoint's and Python's order
  static constexpr auto fields()
  {
    return std::tuple{field("normalAdhesion", &BondState::normalAdhesion),
                      field("shearAdhesion", &BondState::shearAdhesion), field("unp", &BondState::unp),
                      field("unpMax", &BondState::unpMax), flag("cohesionBroken", &BondState::cohesionBroken),
                      flag("tensionBroken", &BondState::tensionBroken), flag("fragile", &BondState::fragile),
                      flag("cohesionDisablesFriction", &BondState::cohesionDisablesFriction)};
  }
};

/// Rolling and twisting moments (Yade's CohFrictPhys): stiffnesses, plastic limits (moments per
/// unit normal force, negative: no limit) and the moments on body 2 (body 1 takes the opposite),
/// kept from step to step by the incremental form. The rolling resistance part sets
/// momentBending afresh at every step.
struct MomentState
{
  double kr = 0, ktw = 0, maxRollPl = -1, maxTwistPl = -1;
  Vec3 momentBending = Vec3::Zero(), momentTwist = Vec3::Zero();
  std::uint8_t momentRotationLaw = 0;
  /// @return the part's StateFields, in the checkpoint's and Python's order
  static constexpr auto fields()
  {
    return std::tuple{field("kr", &MomentState::kr), field("ktw", &MomentState::ktw),
                      field("maxRollPl", &MomentState::maxRollPl), field("maxTwistPl", &MomentState::maxTwistPl),
                      field("momentBending", &MomentState::momentBending).yade("moment_bending"),
                      field("momentTwist", &MomentState::momentTwist).yade("moment_twist"),
                      flag("momentRotationLaw", &MomentState::momentRotationLaw)};
  }
};

/// Rolling resistance of the visco-elastic law (Yade's ViscElPhys mR, mRtype).
struct RollingResistanceState
{
  double mR = 0;
  std::uint8_t mRtype = 1;
  /// @return the part's StateFields, in the checkpoint's and Python's order
  static constexpr auto fields()
  {
    return std::tuple{field("mR", &RollingResistanceState::mR), field("mRtype", &RollingResistanceState::mRtype)};
  }
};

/// Stiffness per unit area (Yade's KnKsPBPhys): the area of the overlap region's section, set by
/// the geometry of Potential Blocks and Particles at every step; intactRock: the contact joins
/// two intact-rock faces (its bond is in BondState).
struct AreaState
{
  double contactArea = 0;
  std::uint8_t intactRock = 0;
  /// @return the part's StateFields, in the checkpoint's and Python's order
  static constexpr auto fields()
  {
    return std::tuple{field("contactArea", &AreaState::contactArea).transient(),
                      flag("intactRock", &AreaState::intactRock)};
  }
};

/// Per-contact state of the richer contact laws, kept beside the contact list (same index,
/// `Contacts::extra`) only while a law that needs it is in use: plain sphere contacts (linear,
/// visco-elastic without rolling resistance) neither store nor copy it. The state of every
/// part, each declared once above; a new part with state adds its struct to the bases and to
/// ContactStateParts.
struct ContactExtra : HertzState, RotationState, BondState, MomentState, RollingResistanceState, AreaState
{
};

/// A list of part types.
template <class... Parts>
struct PartList
{
};
/// The parts whose fields make ContactExtra, in the checkpoint's and Python's order.
using ContactStateParts
    = PartList<HertzState, RotationState, BondState, MomentState, RollingResistanceState, AreaState>;

/// A part's field as a field of ContactExtra.
/// @param f a field of one of ContactExtra's bases
/// @return the same field, its member pointer converted to ContactExtra's
template <class Part, class T>
constexpr StateField<ContactExtra, T> asContactExtraField(const StateField<Part, T>& f)
{
  return {f.name, static_cast<T ContactExtra::*>(f.member), f.python, f.flag, f.stored};
}

/// Call `f(field)` for every field the parts declare, as a StateField<ContactExtra, T>.
template <class F, class... Parts>
void forEachStateField(F&& f, PartList<Parts...> /*parts*/)
{
  (std::apply([&](const auto&... declared) { (f(asContactExtraField(declared)), ...); }, Parts::fields()), ...);
}
/// Call `f(field)` for every declared field of ContactExtra.
template <class F>
void forEachContactStateField(F&& f)
{
  forEachStateField(f, ContactStateParts{});
}
} // namespace talus::dem
