// Prints the version and components of the Talus it was linked against.
#include <dem/base/build_config.h>

#include <iostream>

int main()
{
  std::cout << "talus " << talus::version() << "\n";
  for (const talus::BuildEntry& e : talus::build_config())
    std::cout << e.kind << " " << e.name << " " << (e.enabled ? "ON" : "OFF") << "\n";
}
