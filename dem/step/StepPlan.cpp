#include "dem/step/StepPlan.h"

#include "dem/contact/Collider.h"
#include "dem/engines/ForceResetter.h"
#include "dem/engines/InteractionLoop.h"
#include "dem/engines/NewtonIntegrator.h"

#include <algorithm>
#include <optional>

namespace talus::dem
{
namespace
{
bool declares(const Engine& engine, StagePoint point, Grain grain) { return engine.stages().at(point) == grain; }

/// Each shared stage is run through the range functions of the engine kind that declares it.
bool usualResetter(const Engine& e)
{
  return declares(e, StagePoint::Reset, Grain::PerBody) && dynamic_cast<const ForceResetter*>(&e);
}
bool usualCollider(const Engine& e)
{
  return declares(e, StagePoint::SkinCheck, Grain::PerBody) && dynamic_cast<const Collider*>(&e);
}
bool usualLoop(const Engine& e)
{
  return declares(e, StagePoint::Gather, Grain::PerBody) && dynamic_cast<const InteractionLoop*>(&e);
}
bool usualIntegrator(const Engine& e)
{
  return declares(e, StagePoint::Integration, Grain::PerBody) && dynamic_cast<const NewtonIntegrator*>(&e);
}

/// The shared stages' engines among the live engines: a resetter, engines that declare nothing,
/// a collider and a loop right after it, then an integrator.
std::optional<StepPlan> findGroup(const std::vector<std::shared_ptr<Engine>>& engines, const std::vector<std::size_t>& live)
{
  for (std::size_t k = 0; k < live.size(); ++k)
  {
    if (!usualResetter(*engines[live[k]]))
      continue;
    std::size_t c = k + 1;
    while (c < live.size() && engines[live[c]]->stages().empty())
      ++c;
    if (c + 1 >= live.size() || !usualCollider(*engines[live[c]]) || !usualLoop(*engines[live[c + 1]]))
      return std::nullopt;
    for (std::size_t n = c + 2; n < live.size(); ++n)
      if (usualIntegrator(*engines[live[n]]))
      {
        StepPlan plan;
        plan.resetter = live[k];
        plan.collider = live[c];
        plan.loop = live[c + 1];
        plan.newton = live[n];
        plan.contactsInRegion = engines[plan.loop]->stages().at(StagePoint::Contacts) == Grain::PerContact;
        return plan;
      }
    return std::nullopt;
  }
  return std::nullopt;
}

/// The regions and barriers of a step that does not re-detect (SharedRegions' flows).
void count(StepPlan& plan, PlanConditions conditions)
{
  for (const StepPlan::Entry& e : plan.entries)
    plan.serialStages += e.item == StepPlan::Item::Serial;
  if (!plan.shared())
    return;
  const int separate = plan.separateIntegration() + plan.separateReset();
  if (plan.contactsInRegion && !conditions.distributed)
  {
    plan.regions = 1 + separate;
    plan.barriers = plan.alone ? 1 : 2; // the contacts', and the skin check's unless made ahead
  }
  else
  {
    // The reset and skin check, then (after the reduction, detection or serial contacts) the
    // contacts and the gather.
    plan.regions = 2 + separate;
    plan.barriers = plan.contactsInRegion ? 1 : 0;
  }
}
} // namespace

StepPlan planStep(const std::vector<std::shared_ptr<Engine>>& engines, std::size_t from, PlanConditions conditions)
{
  std::vector<std::size_t> live;
  for (std::size_t k = from; k < engines.size(); ++k)
    if (!engines[k]->dead)
      live.push_back(k);
  std::optional<StepPlan> group = findGroup(engines, live);
  StepPlan plan = group ? *group : StepPlan{};
  const bool resetApart = group && std::any_of(live.begin(), live.end(), [&](std::size_t k) {
                            return k > plan.resetter && k < plan.collider;
                          });
  bool middle = false;
  for (std::size_t k : live)
  {
    const bool shared = k == plan.resetter || k == plan.collider || k == plan.loop || k == plan.newton;
    if (!group || !shared)
    {
      plan.entries.push_back({StepPlan::Item::Serial, k});
      middle = middle || (group && k > plan.loop && k < plan.newton);
    }
    else if (k == plan.resetter)
      plan.entries.push_back({resetApart ? StepPlan::Item::Reset : StepPlan::Item::Forces, StepPlan::none});
    else if (k == plan.collider && resetApart)
      plan.entries.push_back({StepPlan::Item::Forces, StepPlan::none});
    else if (k == plan.newton && middle)
      plan.entries.push_back({StepPlan::Item::Integration, StepPlan::none});
  }
  plan.alone = group && plan.entries.size() == 1 && !conditions.distributed && plan.contactsInRegion;
  count(plan, conditions);
  return plan;
}

bool StepPlan::has(Item item) const
{
  return std::any_of(entries.begin(), entries.end(), [item](const Entry& e) { return e.item == item; });
}

std::string StepPlan::describe() const
{
  std::string text;
  for (const Entry& e : entries)
  {
    if (!text.empty())
      text += " | ";
    if (e.item == Item::Serial)
      text += "serial " + std::to_string(e.engine);
    else if (e.item == Item::Integration)
      text += "integration";
    else if (e.item == Item::Reset)
      text += "reset";
    else
      text += separateIntegration() ? "forces" : "forces+integration";
  }
  return text;
}
} // namespace talus::dem
