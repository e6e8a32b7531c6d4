// The YAML readers' one error path (core/yaml_reader.hpp): a reader throws YamlFieldError (or
// lets a yaml-cpp conversion throw) deep inside and catch_yaml_errors turns either into a Result
// whose message starts with the file; the throwing helpers carry yaml_number's messages.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "telear/core/yaml_reader.hpp"

namespace telear::core {
namespace {

const std::string kWhere = "file 'f.yaml': ";

TEST(CatchYamlErrors, ReturnsWhatTheParserReturns) {
  const auto value = catch_yaml_errors<int>(kWhere, [] { return 7; });
  ASSERT_TRUE(value);
  EXPECT_EQ(*value, 7);
  // A parser that answers with a Result itself: its error passes unchanged (no prefix added).
  const auto refused =
      catch_yaml_errors<int>(kWhere, []() -> Result<int> { return Error{"own message"}; });
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message, "own message");
}

TEST(CatchYamlErrors, PrefixesAFieldErrorWithTheFile) {
  const auto value = catch_yaml_errors<int>(
      kWhere, []() -> int { throw YamlFieldError{"joints[2].d_m must be a number"}; });
  ASSERT_FALSE(value);
  EXPECT_EQ(value.error().message, "file 'f.yaml': joints[2].d_m must be a number");
}

TEST(CatchYamlErrors, WordsAYamlCppExceptionAsDescribeYamlErrorDoes) {
  const YAML::Node root = YAML::Load("a: [1, 2]\n");
  const auto value = catch_yaml_errors<int>(kWhere, [&] { return root["a"].as<int>(); });
  ASSERT_FALSE(value);
  EXPECT_EQ(value.error().message.rfind("file 'f.yaml': not valid YAML", 0), 0u)
      << value.error().message;
}

TEST(NumberOrThrow, ThrowsYamlNumbersMessage) {
  const YAML::Node root = YAML::Load("a: 1.5\nb: x\nq: [1, y]\n");
  EXPECT_EQ(number_or_throw(root["a"], "a"), 1.5);
  const auto b = catch_yaml_errors<double>(kWhere, [&] { return number_or_throw(root["b"], "b"); });
  ASSERT_FALSE(b);
  EXPECT_EQ(b.error().message, "file 'f.yaml': b: must be a number, got 'x'");
  const auto d = catch_yaml_errors<double>(
      kWhere, [&] { return number_or_throw(root["b"], "joint 1 d_m", " "); });
  EXPECT_EQ(d.error().message, "file 'f.yaml': joint 1 d_m must be a number, got 'x'");
  const auto q = catch_yaml_errors<std::vector<double>>(
      kWhere, [&] { return numbers_or_throw(root["q"], "q"); });
  ASSERT_FALSE(q);
  EXPECT_EQ(q.error().message, "file 'f.yaml': q[1]: must be a number, got 'y'");
}

TEST(ValueOrThrow, PassesAValueAndThrowsAnError) {
  EXPECT_EQ(value_or_throw(Result<int>(3)), 3);
  const auto thrown =
      catch_yaml_errors<int>(kWhere, [] { return value_or_throw(Result<int>(Error{"bad"})); });
  EXPECT_EQ(thrown.error().message, "file 'f.yaml': bad");
  const auto status = catch_yaml_errors<int>(kWhere, [] {
    ok_or_throw(Status(Error{"refused"}));
    return 0;
  });
  EXPECT_EQ(status.error().message, "file 'f.yaml': refused");
}

TEST(CheckYamlKeys, NamesTheUnknownKeyAndTheExpectedOnes) {
  const YAML::Node root = YAML::Load("name: a\nshape: box\nsize: 1\n");
  EXPECT_TRUE(check_yaml_keys(root, {"name", "shape", "size"}, "object 'a'"));
  EXPECT_EQ(check_yaml_keys(root, {"shape", "name"}, "object 'a'").error().message,
            "object 'a': unknown key 'size' (expected name, shape)");
  EXPECT_EQ(check_yaml_keys(root, {"shape", "name"}, "").error().message,
            "unknown key 'size' (expected name, shape)");
}

}  // namespace
}  // namespace telear::core
