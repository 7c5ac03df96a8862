// Trial manifest trial.json (SPEC §6, docs/rk-run.md): run::ParseManifest, then what rk-run derives from
// an accepted manifest — the step graph with every command line (BuildPlan) and the list of trial files.
#include <cstdint>
#include <string>

#include "fuzz_util.h"
#include "run/manifest.h"
#include "run/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rk::fuzz::ExpectOnlyInputErrors([&] {
    const rk::run::TrialManifest m =
        rk::run::ParseManifest(std::string(rk::fuzz::AsText(data, size)), "/fuzz/t0001/trial.json");
    (void)m.AllPaths();
    for (const bool plots : {true, false}) {
      for (const rk::run::Step& s : rk::run::BuildPlan(m, rk::run::PlanOptions{plots})) {
        (void)rk::run::OverrideArgs(s.settings);
        (void)s.settings.AsJson().dump();
        (void)s.FileStem();
      }
    }
  });
  return 0;
}
