#pragma once

// The parameters a part (or a law's physics) takes from the script, declared once beside its
// members: PartsLaw lists, sets and reads them by name, so a part adds a parameter in its own
// file only. A part declares them in `static constexpr auto parameters()`, a tuple of
// `parameter(name, &Part::member)`; a yes/no is a bool member, any other a double that must be
// finite and >= 0 (stiffnesses, ratios, lengths).
#include <tuple>

namespace talus::dem::parts
{
/// One parameter: Yade's attribute name and the member holding it (bool or double).
template <class Part, class T>
struct Parameter
{
  const char* name;
  T Part::*member;
};

/// The parameter `name` held by `member`.
/// @param name Yade's attribute name (a string literal: the pointer is kept)
/// @param member the part's bool or double member
/// @return the declaration, for a part's parameters() tuple
template <class Part, class T>
constexpr Parameter<Part, T> parameter(const char* name, T Part::*member)
{
  return {name, member};
}

/// Call `f(parameter)` for each parameter `part` declares (none without `parameters()`).
template <class Part, class F>
void forEachParameter(F&& f)
{
  if constexpr (requires { Part::parameters(); })
    std::apply([&](const auto&... declared) { (f(declared), ...); }, Part::parameters());
}
} // namespace talus::dem::parts
