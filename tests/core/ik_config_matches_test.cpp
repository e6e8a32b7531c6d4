// ik_config_matches: the one selection rule of the closed-form solvers (PUMA and UR) -- a
// solution's label matches a configuration when it has every letter the configuration gives.

#include <gtest/gtest.h>

#include "telear/core/ik_analytic.hpp"

namespace telear::core {
namespace {

TEST(IkConfigMatches, NeedsEveryLetterOfTheConfiguration) {
  EXPECT_TRUE(ik_config_matches("lun", ""));
  EXPECT_TRUE(ik_config_matches("lun", "l"));
  EXPECT_TRUE(ik_config_matches("lun", "nu"));
  EXPECT_TRUE(ik_config_matches("lun", "lun"));
  EXPECT_FALSE(ik_config_matches("lun", "r"));
  EXPECT_FALSE(ik_config_matches("lun", "luf"));
  EXPECT_FALSE(ik_config_matches("rdf", "ru"));
}

}  // namespace
}  // namespace telear::core
