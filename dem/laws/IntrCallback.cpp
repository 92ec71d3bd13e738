#include "dem/laws/IntrCallback.h"

#include <iostream>

namespace talus::dem
{
void SumIntrForcesCb::stepInit()
{
  std::cerr << "(" << force << "," << numIntr << ")";
  force = 0;
  numIntr = 0;
}

void SumIntrForcesCb::go(const Contact& c)
{
  if (c.force == Vec3::Zero())
    return;
  ++numIntr;
  force += c.force.norm();
}
} // namespace talus::dem
