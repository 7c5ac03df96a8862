// Unit tests of run/plan: the step graph (SPEC.md §1.1 command lines) built from a manifest.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "manifest_examples.h"
#include "run/manifest.h"
#include "run/plan.h"

namespace rk::run {
namespace {
using testing::ManifestError;
using testing::WithSteps;

std::vector<std::string> Argv(const Step& s) {
  std::vector<std::string> a = {s.tool};
  for (const auto& x : s.args) a.push_back(x.out_path ? "out/" + x.text : x.text);
  return a;
}
const Step& Find(const std::vector<Step>& plan, const std::string& id) {
  for (const auto& s : plan) {
    if (s.id == id) return s;
  }
  throw std::runtime_error("no step " + id);
}

// "steps": {"bad-rows": ...} gives --bad-rows to every step that reads CSV (not the plots); a step's
// own "bad-rows" wins; values other than error/skip are errors at their position in trial.json.
TEST(Manifest, BadRowsSettingReachesEveryCsvStep) {
  const TrialManifest m =
      ParseManifest(WithSteps(R"({"bad-rows": "skip", "az/smooth": {"bad-rows": "error"}})"), "/t/trial.json");
  for (const char* kind : {"extract-beacon", "locate", "resample-range"}) {
    const StepSettings s = m.Settings("az", kind);
    ASSERT_EQ(s.options.size(), 1u) << kind;
    EXPECT_EQ(s.options[0].first, "bad-rows");
    EXPECT_EQ(s.options[0].second, "skip");
  }
  const StepSettings smooth = m.Settings("az", "smooth");
  ASSERT_EQ(smooth.options.size(), 1u);
  EXPECT_EQ(smooth.options[0].second, "error");
  EXPECT_TRUE(m.Settings("az", "plot").options.empty());
  const std::vector<Step> plan = BuildPlan(m, PlanOptions{});
  bool seen = false;
  for (const Step& st : plan) {
    if (st.kind != "locate") continue;
    const std::vector<std::string> argv = Argv(st);
    seen = std::find(argv.begin(), argv.end(), "--bad-rows") != argv.end();
  }
  EXPECT_TRUE(seen);
  EXPECT_NE(ManifestError(WithSteps(R"({"bad-rows": "ignore"})")).find("must be \"error\" or \"skip\""),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"bad-rows": true})")).find("steps.bad-rows"), std::string::npos);
}

TEST(Plan, BeaconChainFollowsSpecCommandLines) {
  const TrialManifest m = ParseManifest(WithSteps(R"({"locate": {"range-interp": "linear"}})"), "/t/trial.json");
  const std::vector<Step> plan = BuildPlan(m, PlanOptions{});
  std::vector<std::string> ids;
  for (const auto& s : plan) ids.push_back(s.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"az/extract-beacon", "az/locate", "az/plot-located", "az/smooth",
                                           "az/plot-rates", "az/resample-range"}));
  EXPECT_EQ(Argv(Find(plan, "az/extract-beacon")),
            (std::vector<std::string>{"rk-extract", "beacon", "--video", "az/seg_000.mkv", "--video", "az/seg_001.mkv",
                                      "--frames", "az/frames.csv", "-o", "out/az/track.csv"}));
  EXPECT_EQ(Argv(Find(plan, "az/locate")),
            (std::vector<std::string>{"rk-locate", "--track", "out/az/track.csv", "--camera", "az/camera.json",
                                      "--turret", "turret.csv", "--range", "range.csv", "--station", "10,20,5", "-o",
                                      "out/az/located.csv", "--range-interp", "linear"}));
  EXPECT_EQ(Argv(Find(plan, "az/smooth")),
            (std::vector<std::string>{"rk-smooth", "singer", "-i", "out/az/located.csv", "--columns",
                                      "az_deg,el_deg,range_m,e_m,n_m,u_m", "-o", "out/az/smoothed.csv"}));
  EXPECT_EQ(Argv(Find(plan, "az/resample-range")),
            (std::vector<std::string>{"rk-smooth", "resample", "-i", "range.csv", "--columns", "range_m", "--at",
                                      "az/frames.csv", "-o", "out/az/range_at_frames.csv"}));
  EXPECT_EQ(Find(plan, "az/smooth").depends_on, (std::vector<std::string>{"az/locate"}));
  EXPECT_TRUE(Find(plan, "az/plot-located").warn_only);
  EXPECT_EQ(BuildPlan(m, PlanOptions{false}).size(), 4u);  // --no-plots
}

TEST(Plan, OffAndNotApplicablePropagate) {
  std::string text = WithSteps(R"({"az/extract-beacon": false})");
  const std::string logs = "\"turret\": \"turret.csv\", \"range\": \"range.csv\"";
  text.replace(text.find(logs), logs.size(), "\"turret\": null");
  const std::vector<Step> plan = BuildPlan(ParseManifest(text, "/t/trial.json"), PlanOptions{});
  EXPECT_EQ(Find(plan, "az/extract-beacon").state, PlanState::kOff);
  EXPECT_EQ(Find(plan, "az/locate").state, PlanState::kNotApplicable);
  EXPECT_EQ(Find(plan, "az/smooth").state, PlanState::kNotApplicable);
  EXPECT_NE(Find(plan, "az/resample-range").note.find("no range log"), std::string::npos);
}

TEST(Plan, FeaturesSilhouetteRadar) {
  const std::string text = R"({"cameras": {
      "att": {"video": "att/%06d.png", "frames": "att/frames.csv", "model": "att/camera.json",
              "role": "features", "target": "target.json"},
      "sil": {"video": ["sil/v.mkv"], "fps": 25, "t0_s": 1.5, "model": "sil/camera.json",
              "role": "silhouette", "target": "cyl.json"}},
    "turret": "turret.csv", "theodolite": "theo.csv",
    "radar": {"plots": "radar/plots.csv", "nav": "radar/nav.csv"}})";
  const std::vector<Step> plan = BuildPlan(ParseManifest(text, "/t/trial.json"), PlanOptions{false});
  EXPECT_EQ(Argv(Find(plan, "att/extract-features")),
            (std::vector<std::string>{"rk-extract", "features", "--video", "att/%06d.png", "--frames", "att/frames.csv",
                                      "--target", "target.json", "-o", "out/att/points.csv"}));
  EXPECT_EQ(Argv(Find(plan, "att/attitude-oi")),
            (std::vector<std::string>{"rk-attitude", "oi", "--points", "out/att/points.csv", "--camera",
                                      "att/camera.json", "--target", "target.json", "--turret", "turret.csv", "-o",
                                      "out/att/pose.csv"}));
  EXPECT_EQ(Argv(Find(plan, "sil/extract-silhouette")),
            (std::vector<std::string>{"rk-extract", "silhouette", "--video", "sil/v.mkv", "--fps", "25", "--t0", "1.5",
                                      "-o", "out/sil/points.csv"}));
  EXPECT_EQ(Argv(Find(plan, "sil/attitude-cylinder")),
            (std::vector<std::string>{"rk-attitude", "cylinder", "--points", "out/sil/points.csv", "--theodolite",
                                      "theo.csv", "--camera", "sil/camera.json", "--target", "cyl.json", "-o",
                                      "out/sil/axis.csv"}));
  EXPECT_EQ(Argv(Find(plan, "radar/register")),
            (std::vector<std::string>{"rk-register", "bernoulli", "--plots", "radar/plots.csv", "--nav",
                                      "radar/nav.csv", "-o", "out/radar/biases.csv"}));
  EXPECT_EQ(Argv(Find(plan, "radar/register-batch"))[1], "batch");
}

// SPEC.md §3.1: the manifest's station.pointing reaches rk-locate and both rk-attitude steps as --pointing (an
// input: its digest decides re-runs), the station's position reaches rk-locate as --station; both are reserved.
TEST(Plan, StationPointingAndPositionArePassedOn) {
  const std::string text = R"({
    "station": {"lat_deg": -33.5, "lon_deg": 18.25, "h_m": 12, "pointing": "cal/pointing.json"},
    "cameras": {
      "az": {"video": ["az/v.mkv"], "frames": "az/frames.csv", "model": "az/camera.json", "role": "beacon"},
      "att": {"video": "att/%06d.png", "frames": "att/frames.csv", "model": "att/camera.json",
              "role": "features", "target": "target.json"},
      "sil": {"video": ["sil/v.mkv"], "frames": "sil/frames.csv", "model": "sil/camera.json",
              "role": "silhouette", "target": "cyl.json"}},
    "turret": "turret.csv"})";
  const TrialManifest m = ParseManifest(text, "/t/trial.json");
  EXPECT_EQ(m.pointing, "cal/pointing.json");
  const std::vector<std::string> paths = m.AllPaths();
  EXPECT_NE(std::find(paths.begin(), paths.end(), "cal/pointing.json"), paths.end());
  const std::vector<Step> plan = BuildPlan(m, PlanOptions{false});
  EXPECT_EQ(Argv(Find(plan, "az/locate")),
            (std::vector<std::string>{"rk-locate", "--track", "out/az/track.csv", "--camera", "az/camera.json",
                                      "--turret", "turret.csv", "--pointing", "cal/pointing.json", "--station",
                                      "-33.5,18.25,12", "-o", "out/az/located.csv"}));
  EXPECT_EQ(Argv(Find(plan, "att/attitude-oi")),
            (std::vector<std::string>{"rk-attitude", "oi", "--points", "out/att/points.csv", "--camera",
                                      "att/camera.json", "--target", "target.json", "--turret", "turret.csv",
                                      "--pointing", "cal/pointing.json", "-o", "out/att/pose.csv"}));
  EXPECT_EQ(Argv(Find(plan, "sil/attitude-cylinder")),
            (std::vector<std::string>{"rk-attitude", "cylinder", "--points", "out/sil/points.csv", "--theodolite",
                                      "turret.csv", "--camera", "sil/camera.json", "--target", "cyl.json",
                                      "--pointing", "cal/pointing.json", "-o", "out/sil/axis.csv"}));
  for (const char* kind : {"locate", "attitude-oi", "attitude-cylinder"}) {
    EXPECT_TRUE(IsReservedOption(kind, "pointing"));
  }
  EXPECT_TRUE(IsReservedOption("locate", "station"));
  const std::string bad = ManifestError(R"({"station": {"lat_deg": 0, "lon_deg": 0, "h_m": 0, "pointing": 3}})");
  EXPECT_NE(bad.find("station.pointing"), std::string::npos) << bad;
}

// The reserved options come from the plan's bindings: every option the plan gives a step from the
// manifest (an argument before the overrides, other than the defaults --columns/--title a manifest may
// replace) is reserved for its kind, and a manifest that sets one fails with the one message.
TEST(Plan, EveryBoundOptionIsReserved) {
  const std::string text = R"({"cameras": {
      "az": {"video": "az/v.mkv", "frames": "az/frames.csv", "model": "az/camera.json", "role": "beacon"},
      "att": {"video": "att/v.mkv", "fps": 25, "t0_s": 1.5, "model": "att/camera.json", "role": "features",
              "target": "target.json", "boresight_deg": [10, 20]},
      "sil": {"video": ["sil/v.mkv"], "fps": 25, "t0_s": 1.5, "model": "sil/camera.json",
              "role": "silhouette", "target": "cyl.json"}},
    "theodolite": "theo.csv", "range": "range.csv",
    "radar": {"plots": "radar/plots.csv", "nav": "radar/nav.csv"}})";
  const std::vector<Step> plan = BuildPlan(ParseManifest(text, "/t/trial.json"), PlanOptions{});
  std::size_t bound = 0;
  for (const Step& st : plan) {
    for (std::size_t i = st.subcommand.empty() ? 0 : 1; i + 1 < st.args.size(); i += 2) {
      std::string name = st.args[i].text;
      ASSERT_EQ(name[0], '-') << st.id << " argument " << i;
      while (name[0] == '-') name.erase(0, 1);
      if (name == "columns" || name == "title") continue;
      EXPECT_TRUE(IsReservedOption(st.kind, name)) << st.id << " --" << name;
      ++bound;
    }
  }
  EXPECT_GE(bound, 30u);
  EXPECT_NE(ManifestError(WithSteps(R"({"smooth": {"input": "x.csv"}})"))
                .find("option '--input' is set by rk-run from the manifest and cannot be overridden"),
            std::string::npos);
}

// A binding added to a kind's table is reserved at once; the common options are reserved for every kind.
TEST(Plan, BindingAddedToTheTableIsReserved) {
  StepKindInfo kind = *FindStepKind("locate");
  EXPECT_FALSE(IsReservedOption(kind, "pointing-model"));
  kind.bindings.push_back("pointing-model");
  EXPECT_TRUE(IsReservedOption(kind, "pointing-model"));
  EXPECT_FALSE(IsReservedOption("locate", "range-interp"));
  EXPECT_TRUE(IsReservedOption("resample-range", "rate"));  // contradicts --at
  EXPECT_TRUE(IsReservedOption("extract-beacon", "decode-only"));
  for (const char* common : {"help", "h", "version", "report", "quiet", "q", "o", "output"}) {
    EXPECT_TRUE(IsReservedOption("plot", common)) << common;
    EXPECT_TRUE(IsReservedOption("no-such-kind", common)) << common;
  }
  EXPECT_FALSE(IsReservedOption("no-such-kind", "input"));
}

}  // namespace
}  // namespace rk::run
