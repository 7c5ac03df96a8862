// JSON reading (io/json_util.h): syntax errors with line and column, missing fields named.
#include <gtest/gtest.h>

#include "io/error.h"
#include "io/json_util.h"
#include "test_expect_error.h"

namespace rk::io {
namespace {

TEST(Json, SyntaxErrorsGiveLineAndColumnAndMissingFieldsAreNamed) {
  ExpectError([] { ParseJson("{\n  \"a\": 1,\n  \"b\": ]\n}", "cam.json"); }, ExitCode::kInvalidData,
              "cam.json:3:");
  Json j = ParseJson("{\"a\": 1, \"v\": [1, 2]}", "x.json");
  EXPECT_EQ(RequireNumber(j, "a", "x.json"), 1.0);
  ExpectError([&] { RequireNumber(j, "b", "x.json"); }, ExitCode::kInvalidData, "missing field 'b'");
  ExpectError([&] { RequireNumbers(j, "v", 3, 3, "x.json"); }, ExitCode::kInvalidData, "array of 3");
}

}  // namespace
}  // namespace rk::io
