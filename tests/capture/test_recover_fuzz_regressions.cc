// Inputs found by the fuzz harness of `rk-capture recover` (tests/fuzz/fuzz_recover.cc); each is also
// in the committed corpus tests/fuzz/corpus/fuzz_recover/crash-*.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "capture/recover.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "rk_test/temp_dir.h"

namespace rk::capture {
namespace recover_fuzz_regression {

// A frames.csv cell with a byte that is not UTF-8 ("0\xdc") is quoted in recover's problem list; writing
// the repaired manifest (capture.recover.problems) and the --report threw nlohmann's type_error 316, so
// recover ended in an internal error and repaired nothing. The problem is now reported and written.
TEST(RecoverFuzzRegression, ProblemQuotingNonUtf8BytesIsWritten) {
  const rk::test::TempDir trial_tmp("capture_recover_utf8");
  const std::string trial = trial_tmp.path();
  std::filesystem::create_directories(trial + "/az");
  std::ofstream(trial + "/trial.json") << R"({"cameras": {"az": {}}, "capture": {"state": "recording"}})";
  {
    std::ofstream y4m(trial + "/az/seg_000.y4m", std::ios::binary);
    y4m << "YUV4MPEG2 W2 H2 F2997:100 Ip A1:1 Cmono16\n";
    for (int f = 0; f < 3; ++f) y4m << "FRAME\n" << std::string(8, '\0');
  }
  std::ofstream(trial + "/az/frames.csv", std::ios::binary) << "# az\nframe,t_s,segment\n0,1.0,0\n1,1.1,0\xdc\n2,1.2,0\n";
  RecoverSummary s;
  ASSERT_NO_THROW(s = RecoverTrial(trial, {}));
  ASSERT_EQ(s.problems.size(), 1u);
  EXPECT_NE(s.problems[0].find("az/frames.csv:4:"), std::string::npos) << s.problems[0];
  const io::Json m = io::LoadJson(trial + "/trial.json");
  EXPECT_EQ(m["capture"]["state"], "recovered");
  EXPECT_NE(m["capture"]["recover"]["problems"][0].get<std::string>().find("\xef\xbf\xbd"), std::string::npos);
  ASSERT_NO_THROW(io::WriteJson(trial + "/report.json", s.ToJson()));
  std::filesystem::remove_all(trial);
}

}  // namespace recover_fuzz_regression
}  // namespace rk::capture
