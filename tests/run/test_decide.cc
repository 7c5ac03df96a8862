// Unit tests of run/decide.h: which steps rk-run runs and why (docs/rk-run.md, "Skipping"), as a pure
// function of the plan, the last good report, the digests, the tool identities and the state of out/.
// The previous report is made the way rk-run writes it (id, status, key, key_parts, outputs, log), from
// a first decision, so that "nothing changed" is checked against a real fingerprint.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "run/decide.h"
#include "run/manifest.h"
#include "run/plan.h"
#include "run/previous_report.h"
#include "run/sha256.h"

namespace rk::run {
namespace {
using io::Json;

// A chain a/extract → a/locate → a/plot (a plot is warn_only), as BuildPlan makes it.
struct Chain {
  Chain() {
    Step extract;
    extract.id = "a/extract";
    extract.tool = "rk-extract";
    extract.args = {{"beacon", false}, {"--video", false}, {"a/v.mkv", false}, {"-o", false}, {"a/det.csv", true}};
    extract.inputs = {{"video", "a/v.mkv"}};
    extract.outputs = {"a/det.csv"};
    Step locate;
    locate.id = "a/locate";
    locate.tool = "rk-locate";
    locate.args = {{"--detections", false}, {"a/det.csv", true}, {"--turret", false}, {"turret.csv", false},
                   {"-o", false}, {"a/loc.csv", true}};
    locate.inputs = {{"turret", "turret.csv"}};
    locate.depends_on = {"a/extract"};
    locate.outputs = {"a/loc.csv"};
    Step plot;
    plot.id = "a/plot-loc";
    plot.tool = "rk-plot";
    plot.args = {{"a/loc.csv", true}};
    plot.depends_on = {"a/locate"};
    plot.outputs = {"a/loc.png"};
    plot.warn_only = true;
    plot.tool_report = false;
    steps = {extract, locate, plot};
    for (const auto& st : steps) {
      tools.push_back({st.tool, "/bin/" + st.tool, "1.0", "build-id:" + st.tool, 1000, 5});
    }
    sha = {{"a/v.mkv", Sha256Hex("video")}, {"turret.csv", Sha256Hex("turret")}};
  }

  std::vector<StepFacts> Facts() const {
    std::vector<StepFacts> facts(steps.size());
    for (std::size_t i = 0; i < steps.size(); ++i) {
      facts[i].tool = &tools[i];
      for (const auto& in : steps[i].inputs) facts[i].input_sha256.push_back(sha.at(in.path));
    }
    return facts;
  }

  // Decides with the current plan, facts and `report` (null: none); out/ holds what `report` names.
  RunDecision Run(const Json& report, bool force = false) {
    facts = Facts();
    DecideInput in;
    in.steps = steps;
    in.facts = facts;
    in.previous = report.is_null() ? nullptr : &report;
    in.out_files = out_files;
    in.out_dir_exists = !report.is_null();
    in.manifest_sha256 = manifest_sha;
    in.force = force;
    return Decide(in);
  }

  // The out/report.json a successful run of decision `d` writes, with every product and log present
  // in out/ as recorded (out_files).
  Json ReportOf(const RunDecision& d) {
    Json steps_json = Json::array();
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const StepDecision& s = d.steps[i];
      Json j = {{"id", steps[i].id}, {"status", s.decision == Decision::kBlocked ? "warning" : "ok"}};
      if (!s.key.empty()) {
        j["key"] = s.key;
        j["key_parts"] = s.key_parts;
        Json outs = Json::array();
        for (const auto& o : steps[i].outputs) {
          outs.push_back({{"path", o}, {"bytes", 100u + i}, {"mtime_ns", 7000 + static_cast<int>(i)}});
          out_files[o] = {true, 100u + i, 7000 + static_cast<std::int64_t>(i), true};
        }
        j["outputs"] = outs;
        const std::string log = "steps/" + std::to_string(i) + ".log";
        j["log"] = log;
        out_files[log] = {true, 10, 1, true};
      }
      steps_json.push_back(j);
    }
    return {{"tool", "rk-run"}, {"trial", {{"manifest_sha256", manifest_sha}}}, {"steps", steps_json}};
  }

  std::vector<Step> steps;
  std::vector<ToolIdentity> tools;
  std::map<std::string, std::string> sha;
  std::vector<StepFacts> facts;
  std::map<std::string, OutFileState> out_files;
  std::string manifest_sha = Sha256Hex("{\"name\": \"t\"}");
};

const StepDecision& Of(const RunDecision& d, std::size_t i) { return d.steps.at(i); }

TEST(Decide, NoPreviousReportRunsEveryStep) {
  Chain c;
  const RunDecision d = c.Run(Json(nullptr));
  ASSERT_EQ(d.steps.size(), 3u);
  for (const auto& s : d.steps) {
    EXPECT_EQ(s.decision, Decision::kRun);
    EXPECT_EQ(s.reason, "new step");
    EXPECT_EQ(s.status, "");
    EXPECT_EQ(s.key, Sha256Hex(s.key_parts.dump()));
  }
  EXPECT_TRUE(d.rebuild);
  EXPECT_EQ(d.rebuild_reason, "3 step(s) to run");
  // The fingerprint names the products under out/ and chains the upstream fingerprints.
  EXPECT_EQ(Of(d, 0).key_parts["args"].back(), "out/a/det.csv");
  EXPECT_EQ(Of(d, 1).key_parts["upstream"]["a/extract"], Of(d, 0).key);
  EXPECT_EQ(Of(d, 0).key_parts["inputs"][0]["sha256"], Sha256Hex("video"));
}

TEST(Decide, NothingChangedSkipsEveryStepAndKeepsOut) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  const RunDecision d = c.Run(report);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(Of(d, i).decision, Decision::kSkip) << i;
    EXPECT_EQ(Of(d, i).status, "skipped");
    EXPECT_EQ(Of(d, i).reason, "up to date");
    ASSERT_NE(Of(d, i).previous, nullptr);
    EXPECT_EQ(Of(d, i).previous, &report["steps"][i]);
  }
  EXPECT_FALSE(d.rebuild);
  EXPECT_EQ(d.rebuild_reason, "");
}

TEST(Decide, ForceRunsEverything) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  const RunDecision d = c.Run(report, true);
  for (const auto& s : d.steps) {
    EXPECT_EQ(s.decision, Decision::kRun);
    EXPECT_EQ(s.reason, "--force");
  }
}

TEST(Decide, InputDigestChangedRerunsTheStepAndCascadesDownstream) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  c.sha["a/v.mkv"] = Sha256Hex("another video");
  const RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 0).decision, Decision::kRun);
  EXPECT_EQ(Of(d, 0).reason, "input changed: a/v.mkv");
  EXPECT_EQ(Of(d, 1).decision, Decision::kRun);
  EXPECT_EQ(Of(d, 1).reason, "upstream changed: a/extract");
  EXPECT_EQ(Of(d, 2).reason, "upstream changed: a/locate");
  EXPECT_EQ(d.rebuild_reason, "3 step(s) to run");
}

TEST(Decide, InputOfALaterStepChangedLeavesEarlierStepsSkipped) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  c.sha["turret.csv"] = Sha256Hex("new turret log");
  const RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 0).decision, Decision::kSkip);
  EXPECT_EQ(Of(d, 1).reason, "input changed: turret.csv");
  EXPECT_EQ(Of(d, 2).reason, "upstream changed: a/locate");
  EXPECT_EQ(d.rebuild_reason, "2 step(s) to run");
}

TEST(Decide, ToolVersionOrExecutableChanged) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  c.tools[1].version = "1.1";
  RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 0).decision, Decision::kSkip);
  EXPECT_EQ(Of(d, 1).reason, "tool version changed (1.0 -> 1.1)");
  EXPECT_EQ(Of(d, 2).reason, "upstream changed: a/locate");

  c.tools[1].version = "1.0";
  c.tools[1].id = "build-id:rebuilt";
  d = c.Run(report);
  EXPECT_EQ(Of(d, 1).reason, "tool executable changed");
}

TEST(Decide, CommandLineOrOptionsChanged) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  c.steps[0].args.push_back({"--window-min", false});
  c.steps[0].args.push_back({"9", false});
  const RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 0).reason, "command line or options changed");
  EXPECT_EQ(Of(d, 1).reason, "upstream changed: a/extract");
}

// attitude-cylinder's image fit (on by default) reads the frames; switching it off in "steps" re-runs that
// step alone (the video is no longer among its inputs), and switching it on again re-runs it again.
TEST(Decide, ImageFitSwitchedOffRerunsOnlyTheCylinderStep) {
  const auto plan_with = [](const std::string& steps) {
    std::string t = R"({"cameras": {"sil": {"video": ["sil/v.mkv"], "fps": 25, "model": "sil/camera.json",
        "role": "silhouette", "target": "cyl.json"}}, "theodolite": "theo.csv", "steps": STEPS})";
    t.replace(t.find("STEPS"), 5, steps);
    return BuildPlan(ParseManifest(t, "/t/trial.json"), PlanOptions{false});
  };
  Chain c;
  c.steps = plan_with("{}");
  ASSERT_EQ(c.steps.size(), 2u);
  ASSERT_EQ(c.steps[1].kind, "attitude-cylinder");
  EXPECT_EQ(c.steps[1].method, "image-fit");
  c.tools.clear();
  for (const auto& st : c.steps) c.tools.push_back({st.tool, "/bin/" + st.tool, "1.0", "build-id:" + st.tool, 1000, 5});
  c.sha = {{"sil/v.mkv", Sha256Hex("video")}, {"theo.csv", Sha256Hex("theo")}, {"sil/camera.json", Sha256Hex("cam")},
           {"cyl.json", Sha256Hex("cyl")}};
  const Json with_fit = c.ReportOf(c.Run(Json(nullptr)));

  c.steps = plan_with(R"({"sil/attitude-cylinder": {"image-fit": false}})");
  EXPECT_EQ(c.steps[1].method, "three-point");
  RunDecision d = c.Run(with_fit);
  EXPECT_EQ(Of(d, 0).decision, Decision::kSkip);
  EXPECT_EQ(Of(d, 1).decision, Decision::kRun);
  EXPECT_EQ(Of(d, 1).reason, "input no longer read: sil/v.mkv");

  const Json without_fit = c.ReportOf(d);
  c.steps = plan_with("{}");
  d = c.Run(without_fit);
  EXPECT_EQ(Of(d, 0).decision, Decision::kSkip);
  EXPECT_EQ(Of(d, 1).reason, "input changed: sil/v.mkv");
}

TEST(Decide, MissingOrChangedProductsAndLogsRerun) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  auto saved = c.out_files;
  c.out_files.erase("a/det.csv");
  RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 0).decision, Decision::kRun);
  EXPECT_EQ(Of(d, 0).reason, "product missing or changed: out/a/det.csv");
  // Its fingerprint did not change: the steps after it stay up to date.
  EXPECT_EQ(Of(d, 1).decision, Decision::kSkip);

  c.out_files = saved;
  c.out_files["a/loc.csv"].mtime_ns += 1;
  d = c.Run(report);
  EXPECT_EQ(Of(d, 1).reason, "product missing or changed: out/a/loc.csv");

  c.out_files = saved;
  c.out_files["a/loc.csv"].bytes += 1;
  d = c.Run(report);
  EXPECT_EQ(Of(d, 1).reason, "product missing or changed: out/a/loc.csv");

  c.out_files = saved;
  c.out_files["steps/2.log"].regular = false;
  d = c.Run(report);
  EXPECT_EQ(Of(d, 2).reason, "step log missing");
}

TEST(Decide, ProductsNotRecorded) {
  Chain c;
  Json report = c.ReportOf(c.Run(Json(nullptr)));
  report["steps"][0]["outputs"] = Json::array();
  EXPECT_EQ(Of(c.Run(report), 0).reason, "products not recorded");
  // ... unless the step ended in a warning (a plot that failed has no products).
  report["steps"][0]["status"] = "warning";
  report["steps"][0]["reason"] = "rk-extract exited with code 1";
  const StepDecision s = Of(c.Run(report), 0);
  EXPECT_EQ(s.decision, Decision::kSkip);
  EXPECT_EQ(s.status, "warning");
  EXPECT_EQ(s.reason, "up to date (earlier warning: rk-extract exited with code 1)");
}

TEST(Decide, RecordWithoutFingerprintIsANewStep) {
  Chain c;
  Json report = c.ReportOf(c.Run(Json(nullptr)));
  report["steps"][1].erase("key");
  report["steps"][1]["status"] = "not-run";
  const RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 1).reason, "new step (was not-run)");
  EXPECT_EQ(Of(d, 2).decision, Decision::kSkip);  // locate's fingerprint itself is unchanged
}

TEST(Decide, DamagedPreviousReportIsNotTrustedAndEverythingRuns) {
  Chain c;
  Json report = c.ReportOf(c.Run(Json(nullptr)));
  ASSERT_TRUE(IsUsableReport(report));
  Json damaged = report;
  damaged["steps"][0]["key"] = 42;
  EXPECT_FALSE(IsUsableReport(damaged));
  damaged = report;
  damaged["steps"][1]["outputs"][0]["bytes"] = "many";
  EXPECT_FALSE(IsUsableReport(damaged));
  damaged = report;
  damaged["tool"] = "rk-smooth";
  EXPECT_FALSE(IsUsableReport(damaged));
  EXPECT_FALSE(IsUsableReport(Json("not an object")));
  // The runner passes no report then: every step is new and out/ is rebuilt.
  const RunDecision d = c.Run(Json(nullptr));
  for (const auto& s : d.steps) EXPECT_EQ(s.reason, "new step");
  EXPECT_TRUE(d.rebuild);
}

TEST(Decide, MissingPlotToolIsAWarningAndBlocksItsDownstream) {
  Chain c;
  Step after = c.steps[2];
  after.id = "a/after-plot";
  after.depends_on = {"a/plot-loc"};
  after.warn_only = false;
  c.steps.push_back(after);
  c.tools.push_back(c.tools[2]);
  DecideInput in;
  std::vector<StepFacts> facts = c.Facts();
  facts[2].tool = nullptr;
  in.steps = c.steps;
  in.facts = facts;
  const RunDecision d = Decide(in);
  EXPECT_EQ(Of(d, 2).decision, Decision::kBlocked);
  EXPECT_EQ(Of(d, 2).status, "warning");
  EXPECT_EQ(Of(d, 2).reason, "rk-plot not found (searched next to rk-run and on PATH)");
  EXPECT_EQ(Of(d, 3).decision, Decision::kBlocked);
  EXPECT_EQ(Of(d, 3).status, "not-run");
  EXPECT_EQ(Of(d, 3).reason, "needs a/plot-loc, which cannot run");
  EXPECT_TRUE(Of(d, 3).key.empty());
  EXPECT_EQ(BlockedBy(c.steps[3], {"a/plot-loc"}), "needs a/plot-loc, which cannot run");
  EXPECT_EQ(BlockedBy(c.steps[3], {"a/locate"}), "");
}

TEST(Decide, StepsOffOrNotApplicableAreInactive) {
  Chain c;
  c.steps[2].state = PlanState::kOff;
  c.steps[2].note = "switched off in steps";
  const RunDecision d = c.Run(Json(nullptr));
  EXPECT_EQ(Of(d, 2).decision, Decision::kInactive);
  EXPECT_EQ(Of(d, 2).status, "off");
  EXPECT_EQ(Of(d, 2).reason, "switched off in steps");
  EXPECT_TRUE(Of(d, 2).key.empty());
  EXPECT_EQ(d.rebuild_reason, "2 step(s) to run");
}

TEST(Decide, OutIsRebuiltWhenTheSetOfStepsOrTheManifestChanged) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  // A step switched off: nothing runs, but out/ must lose its products.
  c.steps[2].state = PlanState::kOff;
  RunDecision d = c.Run(report);
  EXPECT_EQ(Of(d, 0).decision, Decision::kSkip);
  EXPECT_TRUE(d.rebuild);
  EXPECT_EQ(d.rebuild_reason, "the set of steps changed");
  // trial.json edited without affecting any step (a comment, an unused key).
  c.steps[2].state = PlanState::kActive;
  c.manifest_sha = Sha256Hex("{\"name\": \"t\", \"operator\": \"x\"}");
  d = c.Run(report);
  EXPECT_TRUE(d.rebuild);
  EXPECT_EQ(d.rebuild_reason, "trial.json changed (no step affected)");
}

TEST(Decide, NoOutFolderMeansRebuild) {
  Chain c;
  const Json report = c.ReportOf(c.Run(Json(nullptr)));
  std::vector<StepFacts> facts = c.Facts();
  DecideInput in;
  in.steps = c.steps;
  in.facts = facts;
  in.previous = &report;
  in.out_files = c.out_files;
  in.out_dir_exists = false;
  in.manifest_sha256 = c.manifest_sha;
  const RunDecision d = Decide(in);
  EXPECT_EQ(Of(d, 0).decision, Decision::kSkip);
  EXPECT_TRUE(d.rebuild);
  EXPECT_EQ(d.rebuild_reason, "no complete out/");
}

TEST(Decide, OneFactsPerStepIsRequired) {
  Chain c;
  std::vector<StepFacts> facts = c.Facts();
  facts.pop_back();
  DecideInput in;
  in.steps = c.steps;
  in.facts = facts;
  EXPECT_THROW(Decide(in), std::invalid_argument);
}

TEST(PreviousReport, ProbeOutFilesStatsWhatTheReportNames) {
  const Json report = Json::parse(
      R"({"tool": "rk-run", "steps": [{"id": "a/x", "outputs": [{"path": "none.csv"}], "log": "steps/none.log"}]})");
  const auto files = ProbeOutFiles("/nonexistent-rk-out", report);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_FALSE(files.at("none.csv").stat_ok);
  EXPECT_FALSE(files.at("steps/none.log").regular);
  EXPECT_TRUE(ProbeOutFiles("/nonexistent-rk-out", Json(nullptr)).empty());
}

}  // namespace
}  // namespace rk::run
