// apps/command_failure.hpp: how every command reports a failure -- one line "telear SUB: what"
// and the exit status (2 for refused input by default, 1 when asked).

#include "apps/command_failure.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace telear::cli {
namespace {

TEST(CommandFailure, PrintsOneLineNamingTheCommandAndReturnsTheStatus) {
  std::ostringstream err;
  const CommandFailure fail{err, "telear register"};
  EXPECT_EQ(fail("--rig: give the stereo camera file to register"), kExitBadInput);
  EXPECT_EQ(fail("cannot write 'x'", kExitFailure), kExitFailure);
  EXPECT_EQ(err.str(),
            "telear register: --rig: give the stereo camera file to register\n"
            "telear register: cannot write 'x'\n");
  EXPECT_EQ(kExitBadInput, 2);
  EXPECT_EQ(kExitFailure, 1);
}

}  // namespace
}  // namespace telear::cli
