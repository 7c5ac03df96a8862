// Inputs found by the fuzz harnesses (tests/fuzz) that broke io's parsers; each input is also in the
// committed fuzz corpus (tests/fuzz/corpus/<harness>/crash-*).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "rk_test/temp_dir.h"

namespace rk::io {
namespace {

// The rk::Error message of ParseJson, or "" if it does not throw one (any other exception fails the test).
std::string JsonErrorOf(const std::string& text) {
  try {
    ParseJson(text, "cam.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData) << e.what();
    return e.what();
  }
  return "";
}

// fuzz_camera_json: a number beyond the range of a double made nlohmann::json throw out_of_range
// (error 406), which ParseJson did not turn into a DataError: the tools ended in std::terminate
// instead of "file:line:col: invalid JSON" with exit code 3.
TEST(JsonFuzzRegression, NumberOutOfRangeIsADataErrorWithItsPosition) {
  EXPECT_EQ(JsonErrorOf("{\n  \"distortion\": [\n    0.03E77777777777777777777777777777777777777777\n"),
            "cam.json:3:5: invalid JSON: number out of range '0.03E77777777777777777777777777777777777777777'");
  EXPECT_EQ(JsonErrorOf("{\"focal_length_mm\": -1e400}"), "cam.json:1:21: invalid JSON: number out of range '-1e400'");
  EXPECT_EQ(JsonErrorOf("{\"focal_length_mm\": 1e308}"), "");  // still a double
}

// fuzz_recover: `rk-capture recover` quotes a bad frames.csv cell ("0\xdc") in its problem list, and
// writing that list (the manifest's capture.recover, --report) threw nlohmann's type_error 316 (invalid
// UTF-8): the recovery ended in an internal error. WriteJson now writes invalid bytes as U+FFFD.
TEST(JsonFuzzRegression, WriteJsonReplacesInvalidUtf8) {
  const rk::test::TempDir tmp("json_utf8");
  const std::string path = tmp / "utf8.json";
  WriteJson(path, Json{{"problems", {"az/frames.csv:4:7: column 'segment': '0\xdc' is not an integer"}}});
  const Json back = ParseJson(ReadFile(path), path);
  EXPECT_EQ(back["problems"][0], "az/frames.csv:4:7: column 'segment': '0\xef\xbf\xbd' is not an integer");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rk::io
