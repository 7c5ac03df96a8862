// Unit tests of io/json_positions.h: where each value and key of a JSON text sits.
#include <gtest/gtest.h>

#include <string>

#include "io/json_positions.h"

namespace rk::io {
namespace {

TEST(JsonPositions, NestedValuesKeysAndComments) {
  const std::string text =
      "{\n"
      "  // comment with \"quotes\" and { braces\n"
      "  \"a\": {\"b\": [1, {\"c\": \"x\"}]},\n"
      "  /* block\n comment */ \"d/e\": true\n"
      "}\n";
  JsonPositions p(text);
  EXPECT_EQ(p.At("/a").line, 3u);
  EXPECT_EQ(p.At("/a").column, 8u);
  EXPECT_EQ(p.At("/a/b/1/c").line, 3u);
  EXPECT_EQ(p.At("/a/b/1/c").column, 24u);
  EXPECT_EQ(p.KeyAt("/d~1e").line, 5u);
  EXPECT_EQ(p.KeyAt("/d~1e").column, 13u);
  // Unknown pointers fall back to the nearest ancestor.
  EXPECT_EQ(p.At("/a/zzz").line, 3u);
}

}  // namespace
}  // namespace rk::io
