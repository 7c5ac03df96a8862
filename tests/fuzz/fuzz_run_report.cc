// rk-run's reader of the last run's report, TRIAL/out/report.json (docs/rk-run.md, "Skipping"): the
// input becomes the previous report of a small beacon trial and rk-run plans it (--dry-run), which
// reads every part of the report it trusts (input digests, tool identities, step fingerprints,
// products). The trial, its files and stand-in tools (shell scripts that answer --version) are made
// once; the tool identities are shared through a --tool-cache file, so no tool runs per input.
// rk-run turns any exception into a failed trial; one that is not an rk::Error is reported as
// "internal: ..." and is a finding here.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../run/stand_in_trial.h"
#include "fuzz_util.h"
#include "run/runner.h"

namespace {

const rk::run::RunOptions& Options() {
  static const rk::run::RunOptions o = rk::run::testing::MakeStandInTrial(rk::fuzz::ScratchDir());
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Identify the stand-in tools once (fills the tool cache).
  const rk::run::RunSummary s = rk::run::RunTrial(Options());
  if (s.result != rk::run::TrialResult::kPlanned) {
    std::fprintf(stderr, "fuzz_run_report: set-up trial not planned: %s\n", s.error.c_str());
    std::abort();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rk::fuzz::WriteScratch("t0001/out/report.json", rk::fuzz::AsText(data, size));
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::run::RunSummary s = rk::run::RunTrial(Options());
    if (s.error.find("internal:") != std::string::npos) {
      std::fprintf(stderr, "fuzz_run_report: %s\n", s.error.c_str());
      std::abort();
    }
  });
  return 0;
}
