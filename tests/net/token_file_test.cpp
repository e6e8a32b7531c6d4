// net/token_file.hpp: the one reader of a bearer token file -- the first line, trimmed -- and
// its two messages (a file that cannot be read, a first line without a token).

#include "telear/net/token_file.hpp"

#include <gtest/gtest.h>

#include <string>

#include "test_util/temp_dir.hpp"

namespace telear::net {
namespace {

TEST(TokenFile, ReadsTheFirstLineTrimmed) {
  test_files::TempDir dir("token_file");
  const auto plain = load_token_file(dir.write("plain", "abc123\n"));
  ASSERT_TRUE(plain) << plain.error().message;
  EXPECT_EQ(*plain, "abc123");
  const auto padded = load_token_file(dir.write("padded", "  \tabc123 \r\nsecond line\n"));
  ASSERT_TRUE(padded) << padded.error().message;
  EXPECT_EQ(*padded, "abc123");
  const auto unterminated = load_token_file(dir.write("unterminated", "xyz"));
  ASSERT_TRUE(unterminated) << unterminated.error().message;
  EXPECT_EQ(*unterminated, "xyz");
}

TEST(TokenFile, SaysWhenTheFileCannotBeRead) {
  const auto token = load_token_file("/nonexistent/token");
  ASSERT_FALSE(token);
  EXPECT_EQ(token.error().message, "cannot read the token file '/nonexistent/token'");
}

TEST(TokenFile, SaysWhenTheFirstLineHoldsNoToken) {
  test_files::TempDir dir("token_file");
  for (const std::string text : {"", "\n", "   \r\n", "\nabc123\n"}) {
    const std::string path = dir.write("empty", text);
    const auto token = load_token_file(path);
    ASSERT_FALSE(token) << "'" << text << "'";
    EXPECT_EQ(token.error().message, "the token file '" + path + "' holds no token (first line)");
  }
}

}  // namespace
}  // namespace telear::net
