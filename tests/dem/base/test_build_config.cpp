// The library reports the version and the component table decided at configure time.
#include "dem/base/build_config.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

TEST(BuildConfig, VersionMatchesProject) { EXPECT_EQ(talus::version(), TALUS_EXPECTED_VERSION); }

TEST(BuildConfig, ListsEveryComponentOnceWithANote)
{
  std::set<std::string> components;
  for (const talus::BuildEntry& e : talus::build_config())
  {
    EXPECT_FALSE(std::string(e.note).empty()) << e.name << " has no note";
    if (std::string(e.kind) == "component")
    {
      EXPECT_TRUE(components.insert(e.name).second) << e.name << " listed twice";
    }
  }
  EXPECT_EQ(components, (std::set<std::string>{"dem", "flow", "coupling", "foam-solvers", "fem"}));
}

TEST(BuildConfig, DemIsAlwaysOn)
{
  bool found = false;
  for (const talus::BuildEntry& e : talus::build_config())
  {
    if (std::string(e.name) == "dem")
    {
      found = true;
      EXPECT_TRUE(e.enabled);
    }
  }
  EXPECT_TRUE(found);
}
