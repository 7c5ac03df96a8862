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
                                           "az/plot-rates", "az/resample-range", "trajectory/export-kml",
                                           "trajectory/export-czml"}));
  EXPECT_EQ(Argv(Find(plan, "az/extract-beacon")),
            (std::vector<std::string>{"rk-extract", "beacon", "--video", "az/seg_000.mkv", "--video", "az/seg_001.mkv",
                                      "--frames", "az/frames.csv", "-o", "out/az/track.csv"}));
  EXPECT_EQ(Argv(Find(plan, "az/locate")),
            (std::vector<std::string>{"rk-locate", "--track", "out/az/track.csv", "--camera", "az/camera.json",
                                      "--turret", "turret.csv", "--range", "range.csv", "--station", "10,20,5",
                                      "--range-interp", "linear", "-o", "out/az/located.csv"}));
  EXPECT_EQ(Argv(Find(plan, "az/smooth")),
            (std::vector<std::string>{"rk-smooth", "singer", "-i", "out/az/located.csv", "--columns",
                                      "az_deg,el_deg,range_m,e_m,n_m,u_m", "-o", "out/az/smoothed.csv"}));
  EXPECT_EQ(Argv(Find(plan, "az/resample-range")),
            (std::vector<std::string>{"rk-smooth", "resample", "-i", "range.csv", "--columns", "range_m", "--at",
                                      "az/frames.csv", "-o", "out/az/range_at_frames.csv"}));
  EXPECT_EQ(Find(plan, "az/smooth").depends_on, (std::vector<std::string>{"az/locate"}));
  EXPECT_TRUE(Find(plan, "az/plot-located").warn_only);
  // A station position and a range log: the located target is exported for earth viewers (issue 34).
  EXPECT_EQ(Argv(Find(plan, "trajectory/export-kml")),
            (std::vector<std::string>{"rk-export", "kml", "--located", "out/az/located.csv", "--epoch-utc",
                                      "2026-11-21T08:00:00Z", "--name", "t0001", "-o", "out/trajectory.kml"}));
  EXPECT_EQ(Find(plan, "trajectory/export-czml").depends_on, (std::vector<std::string>{"az/locate"}));
  EXPECT_EQ(BuildPlan(m, PlanOptions{false}).size(), 6u);  // --no-plots
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
                                      "theo.csv", "--camera", "sil/camera.json", "--target", "cyl.json", "--video",
                                      "sil/v.mkv", "-o", "out/sil/axis.csv"}));
  EXPECT_EQ(Find(plan, "sil/attitude-cylinder").method, "image-fit");
  EXPECT_EQ(Argv(Find(plan, "radar/register")),
            (std::vector<std::string>{"rk-register", "bernoulli", "--plots", "radar/plots.csv", "--nav",
                                      "radar/nav.csv", "-o", "out/radar/biases.csv"}));
  EXPECT_EQ(Argv(Find(plan, "radar/register-batch"))[1], "batch");
}

// SPEC.md §6 role points: rk-extract points with the camera's seeds, then rk-locate of the points track (one
// located series per id); a points camera needs "seeds" (at its position in trial.json), not a target.
TEST(Plan, PointsCameraExtractsAndLocatesEachPoint) {
  const std::string text = R"({"cameras": {
      "pt": {"video": ["pt/v.mkv"], "frames": "pt/frames.csv", "model": "pt/camera.json", "role": "points",
             "seeds": "pt/seeds.csv"}},
    "turret": "turret.csv"})";
  const std::vector<Step> plan = BuildPlan(ParseManifest(text, "/t/trial.json"), PlanOptions{false});
  EXPECT_EQ(Argv(Find(plan, "pt/extract-points")),
            (std::vector<std::string>{"rk-extract", "points", "--video", "pt/v.mkv", "--frames", "pt/frames.csv",
                                      "--seeds", "pt/seeds.csv", "-o", "out/pt/points.csv"}));
  EXPECT_EQ(Argv(Find(plan, "pt/locate-points")),
            (std::vector<std::string>{"rk-locate", "--track", "out/pt/points.csv", "--camera", "pt/camera.json",
                                      "--turret", "turret.csv", "-o", "out/pt/located.csv"}));
  const std::string no_seeds = R"({"cameras": {
      "pt": {"video": ["pt/v.mkv"], "fps": 10, "model": "pt/camera.json", "role": "points"}}})";
  EXPECT_NE(ManifestError(no_seeds).find("seeds"), std::string::npos) << ManifestError(no_seeds);
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
  EXPECT_EQ(m.Single().pointing, "cal/pointing.json");
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
                                      "--pointing", "cal/pointing.json", "--video", "sil/v.mkv", "-o",
                                      "out/sil/axis.csv"}));  // the image fit by default (issue 20)
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

const char* const kSilhouetteTrial = R"({"cameras": {
      "sil": {"video": ["sil/a.mkv", "sil/b.mkv"], "frames": "sil/frames.csv", "model": "sil/camera.json",
              "role": "silhouette", "target": "cyl.json"}},
    "theodolite": "theo.csv", "steps": STEPS})";
std::string Silhouette(const std::string& steps) {
  std::string t = kSilhouetteTrial;
  return t.replace(t.find("STEPS"), 5, steps);
}
std::string Replaced(std::string t, const std::string& from, const std::string& to) {
  const auto at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? t : t.replace(at, from.size(), to);
}
std::string RequestError(const TrialManifest& m, const std::vector<Step>& plan) {
  try {
    CheckRequestedProducts(m, plan);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    return e.what();
  }
  return "";
}

// attitude-cylinder fits the image (every segment of the camera's video) unless "steps" says
// "image-fit": false; the key is rk-run's (not passed on), takes only true/false, and the time cap is the
// tool's --fit-time-limit, passed through.
TEST(Plan, CylinderImageFitByDefaultAndItsSwitch) {
  std::vector<Step> plan = BuildPlan(ParseManifest(Silhouette("{}"), "/t/trial.json"), PlanOptions{false});
  std::vector<std::string> argv = Argv(Find(plan, "sil/attitude-cylinder"));
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--video"), 2);
  EXPECT_EQ(Find(plan, "sil/attitude-cylinder").inputs.back().path, "sil/b.mkv");
  EXPECT_EQ(Find(plan, "sil/attitude-cylinder").method, "image-fit");

  const TrialManifest off = ParseManifest(
      Silhouette(R"({"attitude-cylinder": {"fit-time-limit": 30}, "sil/attitude-cylinder": {"image-fit": false}})"),
      "/t/trial.json");
  plan = BuildPlan(off, PlanOptions{false});
  const Step& at = Find(plan, "sil/attitude-cylinder");
  argv = Argv(at);
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--video"), 0);
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--image-fit"), 0);
  EXPECT_EQ(argv[argv.size() - 3], "30");  // the manifest's options come before rk-run's output
  EXPECT_EQ(argv[argv.size() - 2], "-o");
  EXPECT_EQ(at.method, "three-point");
  EXPECT_EQ(at.settings.AsJson(), (io::Json{{"fit-time-limit", 30}, {"image-fit", false}}));
  EXPECT_EQ(PlanByUnit(off, plan)[0].Line(), "sil (silhouette camera): planned extract-silhouette, "
                                             "attitude-cylinder (three-point)");

  EXPECT_NE(ManifestError(Silhouette(R"({"attitude-cylinder": {"image-fit": "yes"}})"))
                .find("steps.attitude-cylinder.image-fit: must be true or false"),
            std::string::npos);
  EXPECT_NE(ManifestError(Silhouette(R"({"attitude-cylinder": {"video": "x.mkv"}})"))
                .find("option '--video' is set by rk-run"),
            std::string::npos);
  // Only attitude-cylinder has the key: elsewhere it is an option name like any other (passed on).
  EXPECT_EQ(ManifestError(WithSteps(R"({"locate": {"image-fit": true}})")), "");
}

// One line per unit: the steps planned and those skipped with the reason; logs no step reads; an empty plan.
TEST(Plan, PlanByUnitSaysWhatIsPlannedAndSkipped) {
  const std::string text = Replaced(WithSteps(R"({"resample-range": false})"), "\"theodolite\": null",
                                    "\"theodolite\": \"theo.csv\"");
  const TrialManifest m = ParseManifest(text, "/t/trial.json");
  const std::vector<UnitPlan> units = PlanByUnit(m, BuildPlan(m, PlanOptions{}));
  ASSERT_EQ(units.size(), 3u);
  EXPECT_EQ(units[0].Line(),
            "az (beacon camera): planned extract-beacon, locate, plot-located, smooth, plot-rates; skipped "
            "resample-range (off: switched off in trial.json \"steps\")");
  EXPECT_EQ(units[1].Line(), "trajectory (export of the located target): planned export-kml, export-czml");
  EXPECT_EQ(units[2].unit, "theodolite");
  EXPECT_EQ(units[2].Line(),
            "theodolite (log theo.csv): not used: no silhouette camera, and the beacon cameras use the turret log");
  const io::Json j = units[0].ToJson();
  EXPECT_EQ(j["skipped"][0]["step"], "resample-range");
  EXPECT_EQ(j["planned"].size(), 5u);

  // A single station's camera named "trajectory" (allowed): one unit for it and the exports, not two.
  const TrialManifest named = ParseManifest(Replaced(WithSteps("{}"), "\"az\":", "\"trajectory\":"), "/t/trial.json");
  const std::vector<UnitPlan> n_units = PlanByUnit(named, BuildPlan(named, PlanOptions{}));
  ASSERT_EQ(n_units.size(), 1u);
  EXPECT_EQ(n_units[0].Line(),
            "trajectory (beacon camera, and export of the located target): planned extract-beacon, locate, "
            "plot-located, smooth, plot-rates, resample-range, export-kml, export-czml");
  // ... and without a range log nothing is exported: the camera's unit is said to be the camera's only.
  const TrialManifest named_no_range =
      ParseManifest(Replaced(Replaced(WithSteps("{}"), "\"az\":", "\"trajectory\":"), "\"range\": \"range.csv\",", ""),
                    "/t/trial.json");
  const std::vector<UnitPlan> r_units = PlanByUnit(named_no_range, BuildPlan(named_no_range, PlanOptions{}));
  ASSERT_EQ(r_units.size(), 1u);
  EXPECT_EQ(r_units[0].what, "beacon camera");

  // A theodolite trial whose manifest lists no images (rk-sim theodolite --images none): no camera.
  const TrialManifest theo = ParseManifest(R"({"theodolite": "theodolite.csv"})", "/t/trial.json");
  const std::vector<UnitPlan> t_units = PlanByUnit(theo, BuildPlan(theo, PlanOptions{}));
  ASSERT_EQ(t_units.size(), 2u);
  EXPECT_NE(t_units[0].Line().find("theodolite (log theodolite.csv): not used: \"cameras\" lists no camera"),
            std::string::npos);
  EXPECT_EQ(t_units[1].Line(), "trial (manifest): nothing to run: the manifest lists no camera and no radar");
  EXPECT_EQ(t_units[1].ToJson()["planned"], io::Json::array());
  EXPECT_EQ(RequestError(theo, BuildPlan(theo, PlanOptions{})), "");  // nothing asked for: not an error
}

// A product the manifest asks for that cannot be made: a "steps" key (not false) whose step is not
// applicable, a radar key without radar, or a camera role whose last product is not applicable; errors at
// the request's place in trial.json.
TEST(Plan, RequestedProductThatCannotBeMadeIsAnError) {
  // The role asks for it: a silhouette camera without a theodolite or turret log.
  std::string text = Replaced(Silhouette("{}"), "\"theodolite\": \"theo.csv\", ", "");
  TrialManifest m = ParseManifest(text, "/t/trial.json");
  std::string e = RequestError(m, BuildPlan(m, PlanOptions{}));
  EXPECT_NE(e.find("/t/trial.json:3:23: cameras.sil.role: a silhouette camera asks for sil/attitude-cylinder, "
                   "which cannot run: the manifest has no theodolite or turret log"),
            std::string::npos)
      << e;
  // ... unless "steps" switches that step off.
  text = Replaced(text, "\"steps\": {}", R"("steps": {"attitude-cylinder": false})");
  m = ParseManifest(text, "/t/trial.json");
  EXPECT_EQ(RequestError(m, BuildPlan(m, PlanOptions{})), "");

  // "steps" asks for it: resample-range options without a range log (the key's line:col).
  const std::string beacon =
      Replaced(WithSteps("{\n  \"az/resample-range\": {\"method\": \"cubic\"}}"), ", \"range\": \"range.csv\"", "");
  m = ParseManifest(beacon, "/t/trial.json");
  e = RequestError(m, BuildPlan(m, PlanOptions{}));
  EXPECT_NE(e.find(":8:3: steps.az/resample-range: asks for az/resample-range, which cannot run: the manifest "
                   "has no range log"),
            std::string::npos)
      << e;
  // A radar step without a radar block.
  m = ParseManifest(WithSteps(R"({"radar/register": {"pd": 0.9}})"), "/t/trial.json");
  EXPECT_NE(RequestError(m, BuildPlan(m, PlanOptions{})).find("steps.radar/register: asks for register of the radar, but "
                                                         "the manifest has no \"radar\" block"),
            std::string::npos);
  // A chain switched off by "steps" asks for nothing after it; a plot and "bad-rows" ask for nothing.
  m = ParseManifest(WithSteps(R"({"az/extract-beacon": false, "locate": {"range-interp": "linear"},
                                  "plot": {"dpi": 50}, "bad-rows": "skip"})"),
                    "/t/trial.json");
  EXPECT_EQ(RequestError(m, BuildPlan(m, PlanOptions{})), "");
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


// Several stations (docs/rk-run.md "Several stations"): each camera's chain with its own station's logs,
// pointing model and position, into out/S/C/; then rk-intersect after every locate step, through the
// stations.json the plan writes (positions, origin, located paths relative to it).
constexpr const char* kTwoStations = R"({"name": "ms", "origin": {"lat_deg": 47, "lon_deg": 8, "h_m": 400},
 "stations": {
  "s2": {"station": {"lat_deg": 47.01, "lon_deg": 8.05, "h_m": 750},
         "cameras": {"az": {"video": "s2/az/video.mkv", "frames": "s2/az/frames.csv",
                            "model": "s2/az/camera.json", "role": "beacon"}},
         "turret": "s2/turret.csv"},
  "s1": {"station": {"lat_deg": 47, "lon_deg": 8, "h_m": 400, "pointing": "s1/pointing.json"},
         "cameras": {"az": {"video": "s1/az/video.mkv", "frames": "s1/az/frames.csv",
                            "model": "s1/az/camera.json", "role": "beacon"}},
         "turret": "s1/turret.csv", "range": "s1/range.csv"}},
 "steps": {"intersect": {"smooth": true}, "s2/az/locate": {"turret-max-gap": 0.2}}})";

TEST(Plan, SeveralStationsRunEachChainThenTheIntersection) {
  const TrialManifest m = ParseManifest(kTwoStations, "/t/trial.json");
  const std::vector<Step> plan = BuildPlan(m, PlanOptions{.plots = false});
  const Step& lo1 = Find(plan, "s1/az/locate");
  EXPECT_EQ(Argv(lo1), (std::vector<std::string>{"rk-locate", "--track", "out/s1/az/track.csv", "--camera",
                                                 "s1/az/camera.json", "--turret", "s1/turret.csv", "--range",
                                                 "s1/range.csv", "--pointing", "s1/pointing.json", "--station",
                                                 "47,8,400", "-o", "out/s1/az/located.csv"}));
  const Step& lo2 = Find(plan, "s2/az/locate");
  EXPECT_EQ(Argv(lo2), (std::vector<std::string>{"rk-locate", "--track", "out/s2/az/track.csv", "--camera",
                                                 "s2/az/camera.json", "--turret", "s2/turret.csv", "--station",
                                                 "47.01,8.05,750", "--turret-max-gap", "0.2", "-o",
                                                 "out/s2/az/located.csv"}));
  EXPECT_EQ(Find(plan, "s2/az/resample-range").state, PlanState::kNotApplicable);  // s2 has no range log
  const Step& in = Find(plan, "trajectory/intersect");
  EXPECT_EQ(in.state, PlanState::kActive);
  EXPECT_EQ(Argv(in), (std::vector<std::string>{"rk-intersect", "--smooth", "--stations", "out/trajectory/stations.json",
                                                "-o", "out/trajectory/trajectory.csv"}));
  EXPECT_EQ(in.depends_on, (std::vector<std::string>{"s1/az/locate", "s2/az/locate"}));
  // The trajectory for earth viewers (issue 34): no epoch_utc in this manifest, so no --epoch-utc.
  EXPECT_EQ(Argv(Find(plan, "trajectory/export-czml")),
            (std::vector<std::string>{"rk-export", "czml", "--trajectory", "out/trajectory/trajectory.csv", "--name",
                                      "ms", "-o", "out/trajectory.czml"}));
  EXPECT_EQ(Find(plan, "trajectory/export-kml").depends_on, (std::vector<std::string>{"trajectory/intersect"}));
  // The intersection comes after every locate step it reads.
  const auto pos = [&](const std::string& id) {
    return std::find_if(plan.begin(), plan.end(), [&](const Step& s) { return s.id == id; }) - plan.begin();
  };
  EXPECT_GT(pos("trajectory/intersect"), pos("s2/az/locate"));
  ASSERT_EQ(in.generated.size(), 1u);
  EXPECT_EQ(in.generated[0].first, "trajectory/stations.json");
  const io::Json st = io::Json::parse(in.generated[0].second);
  EXPECT_EQ(st["origin"]["h_m"], 400);
  ASSERT_EQ(st["stations"].size(), 2u);
  EXPECT_EQ(st["stations"][0]["name"], "s1.az"  /* rk-intersect names: no slash */);
  EXPECT_EQ(st["stations"][0]["located"], "../s1/az/located.csv");
  EXPECT_EQ(st["stations"][1]["lat_deg"], 47.01);
  EXPECT_EQ(st["stations"][1]["h_m"], 750);
  // Units: one per camera, and the trajectory.
  std::vector<std::string> units;
  for (const UnitPlan& u : PlanByUnit(m, plan)) units.push_back(u.unit);
  EXPECT_EQ(units, (std::vector<std::string>{"s1/az", "s2/az", "trajectory"}));
  EXPECT_NO_THROW(CheckRequestedProducts(m, plan));
}

TEST(Plan, SeveralStationsErrorsAtTheirPlace) {
  std::string two = kTwoStations;
  // The intersection asks for two located targets: one station without a turret log cannot give one.
  std::string no_turret = two;
  const std::string s2_turret = "\"turret\": \"s2/turret.csv\"";
  no_turret.replace(no_turret.find(s2_turret), s2_turret.size(), "\"turret\": null");
  const TrialManifest m = ParseManifest(no_turret, "/t/trial.json");
  const std::vector<Step> plan = BuildPlan(m, PlanOptions{});
  EXPECT_EQ(Find(plan, "trajectory/intersect").state, PlanState::kNotApplicable);
  try {
    CheckRequestedProducts(m, plan);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    // The "s2/az/locate" key asks for it first (the camera's role would too).
    EXPECT_NE(std::string(e.what()).find("steps.s2/az/locate: asks for s2/az/locate, which cannot run"),
              std::string::npos)
        << e.what();
  }
  // Step keys: an unknown station/camera, and the intersection in a single-station manifest.
  std::string unit = two;
  unit.replace(unit.find("\"s2/az/locate\""), std::string("\"s2/az/locate\"").size(), "\"s9/az/locate\"");
  EXPECT_NE(ManifestError(unit).find("steps.s9/az/locate: no camera 'STATION/CAMERA' named 's9/az'"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"intersect": {}})")).find("step 'intersect' needs several stations"),
            std::string::npos);
  // A unit key reaches its camera only.
  const TrialManifest ok = ParseManifest(two, "/t/trial.json");
  EXPECT_TRUE(ok.Settings("s1/az", "locate").options.empty());
  EXPECT_EQ(ok.Settings("s2/az", "locate").options.size(), 1u);
}

// A single-station manifest plans as before: no intersection, camera units by their names; only the exports of its
// located target are in the unit trajectory.
TEST(Plan, SingleStationManifestHasNoIntersection) {
  const TrialManifest m = ParseManifest(testing::kBeaconManifest, "/t/trial.json");
  for (const Step& s : BuildPlan(m, PlanOptions{})) {
    EXPECT_NE(s.kind, "intersect");
    EXPECT_TRUE(s.generated.empty());
    if (s.unit == "trajectory") {
      EXPECT_EQ(s.kind.rfind("export-", 0), 0u) << s.id;
    } else {
      EXPECT_EQ(s.id.rfind("az/", 0), 0u) << s.id;
    }
  }
}

// The exports (issue 34): only where something has a WGS-84 position (several stations, or one station with its
// position and a range log); switched off, given options, asked for where nothing can be exported (an error at the
// key); their inputs, epoch and name are rk-run's.
TEST(Plan, ExportsOnlyWhatHasAPlaceOnTheEarth) {
  const auto kinds = [](const std::vector<Step>& plan) {
    std::vector<std::string> k;
    for (const Step& s : plan) {
      if (s.unit == "trajectory") k.push_back(s.kind + ":" + PlanStateName(s.state));
    }
    return k;
  };
  const std::string no_range = Replaced(testing::kBeaconManifest, "\"range\": \"range.csv\"", "\"range\": null");
  const TrialManifest nr = ParseManifest(no_range, "/t/trial.json");
  EXPECT_TRUE(kinds(BuildPlan(nr, PlanOptions{})).empty());
  const std::string no_station =
      Replaced(testing::kBeaconManifest, "\"station\": {\"lat_deg\": 10, \"lon_deg\": 20, \"h_m\": 5},", "");
  const TrialManifest ns = ParseManifest(no_station, "/t/trial.json");
  EXPECT_TRUE(kinds(BuildPlan(ns, PlanOptions{})).empty());
  const TrialManifest asked = ParseManifest(Replaced(no_range, "\"steps\": {}", "\"steps\": {\"export-kml\": true}"),
                                            "/t/trial.json");
  EXPECT_NE(RequestError(asked, BuildPlan(asked, PlanOptions{})).find(
                "steps.export-kml: asks for export-kml, but the trial has nothing in WGS-84 to export"),
            std::string::npos);
  const TrialManifest off = ParseManifest(
      WithSteps(R"({"export-kml": false, "trajectory/export-czml": {"path-width": 3}})"), "/t/trial.json");
  const std::vector<Step> plan = BuildPlan(off, PlanOptions{});
  EXPECT_EQ(kinds(plan), (std::vector<std::string>{"export-kml:off", "export-czml:active"}));
  const std::vector<std::string> argv = Argv(Find(plan, "trajectory/export-czml"));
  EXPECT_EQ(std::vector<std::string>(argv.end() - 4, argv.end()),
            (std::vector<std::string>{"--path-width", "3", "-o", "out/trajectory.czml"}));
  EXPECT_NO_THROW(CheckRequestedProducts(off, plan));
  for (const char* option : {"trajectory", "located", "epoch-utc", "name"}) {
    EXPECT_TRUE(IsReservedOption("export-kml", option)) << option;
  }
  // The locate step switched off: nothing to export, and nothing asked for.
  const TrialManifest no_locate = ParseManifest(WithSteps(R"({"locate": false})"), "/t/trial.json");
  EXPECT_TRUE(kinds(BuildPlan(no_locate, PlanOptions{})).empty());
}

}  // namespace
}  // namespace rk::run
