#pragma once

#include "dem/core/Contacts.h"

#include <cstdint>
#include <string>

namespace talus::dem
{
/// A callback of the InteractionLoop (Yade's IntrCallback, InteractionLoop.callbacks): told
/// when a step's contacts begin, then shown every real contact once its force is computed.
class IntrCallback
{
public:
  virtual ~IntrCallback() = default;
  /// Called once per step, before the first contact.
  virtual void stepInit() = 0;
  /// Called for every real contact after the forces (serially, in list order).
  /// @param c the contact, its force of this step
  virtual void go(const Contact& c) = 0;
  /// Yade's class name, e.g. "SumIntrForcesCb".
  [[nodiscard]] virtual std::string typeName() const = 0;
};

/// Yade's SumIntrForcesCb: at the start of each step writes "(sum,count)" to standard error,
/// the sum of the magnitudes of the previous step's non-zero contact forces and their number,
/// then starts counting again.
class SumIntrForcesCb : public IntrCallback
{
public:
  void stepInit() override;
  void go(const Contact& c) override;
  [[nodiscard]] std::string typeName() const override { return "SumIntrForcesCb"; }

  double force = 0;
  std::int64_t numIntr = 0;
};
} // namespace talus::dem
