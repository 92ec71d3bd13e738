#include "dem/laws/ContactLaw.h"

#include <map>
#include <stdexcept>

namespace talus::dem
{
namespace
{
std::map<std::string, std::function<std::unique_ptr<ContactLaw>()>>& registry()
{
  static std::map<std::string, std::function<std::unique_ptr<ContactLaw>()>> laws;
  return laws;
}
} // namespace

bool registerContactLaw(const std::vector<std::string>& names, std::function<std::unique_ptr<ContactLaw>()> factory)
{
  for (const std::string& name : names)
    registry()[name] = factory;
  return true;
}

std::unique_ptr<ContactLaw> makeContactLaw(const std::string& name)
{
  auto it = registry().find(name);
  if (it == registry().end())
  {
    std::string known;
    for (const auto& [n, _] : registry())
      known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown contact law '" + name + "'; known: " + known);
  }
  return it->second();
}

void ContactLaw::unknownParameter(const std::string& name) const
{
  std::string known;
  for (const std::string& n : parameterNames())
    known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument(typeName() + " has no parameter '" + name + "'"
                              + (known.empty() ? std::string(" (it has none)") : "; known: " + known));
}

void ContactLaw::setParameter(const std::string& name, double /*value*/) { unknownParameter(name); }

double ContactLaw::parameter(const std::string& name) const { unknownParameter(name); }

void ContactLaw::setPairParameter(const std::string& name, const PairParameter& /*value*/) { unknownParameter(name); }

void alignContactExtra(Contacts& contacts)
{
  if (contacts.extra.empty())
    contacts.extra.resize(contacts.list.size());
  static_cast<void>(contacts.extraState()); // throws if misaligned
}

std::vector<std::string> contactLawNames()
{
  std::vector<std::string> names;
  for (const auto& [n, _] : registry())
    names.push_back(n);
  return names;
}
} // namespace talus::dem
