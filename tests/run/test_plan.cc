// Unit tests of rangekit::run: SHA-256 against FIPS 180-4 test vectors, JSON positions, the manifest's
// checks (errors at trial.json:LINE:COL), the step graph (SPEC.md §1.1 command lines), the size+mtime
// digest shortcut, the trial lock, and the out/ swap with its recovery.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/error.h"
#include "io/file_util.h"
#include "run/digest.h"
#include "run/elf_build_id.h"
#include "run/process.h"
#include "run/json_positions.h"
#include "run/manifest.h"
#include "run/plan.h"
#include "run/sha256.h"
#include "run/trial_dir.h"

namespace rk::run {
namespace {
namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "rk_run_test.XXXXXX").string();
    path_ = ::mkdtemp(templ.data());
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string operator/(const std::string& rel) const { return (fs::path(path_) / rel).string(); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void Write(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

std::string Read(const std::string& path) { return io::ReadFile(path); }

// ---------------------------------------------------------------------------------------------- SHA-256
TEST(Sha256, Fips180Vectors) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, MillionAStreamedInOddChunks) {
  // One million 'a' fed in chunks of 1, 63, 64, 65, 1000 bytes: block buffering must not matter.
  Sha256 h;
  const std::string chunk(1000, 'a');
  std::size_t done = 0;
  const std::size_t sizes[] = {1, 63, 64, 65, 1000};
  for (int k = 0; done < 1000000; ++k) {
    const std::size_t n = std::min(sizes[k % 5], 1000000 - done);
    h.Update(chunk.data(), n);
    done += n;
  }
  EXPECT_EQ(h.HexDigest(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, FileMatchesString) {
  TempDir d;
  Write(d / "f.bin", "abc");
  EXPECT_EQ(Sha256File(d / "f.bin"), Sha256Hex("abc"));
  EXPECT_THROW(Sha256File(d / "missing"), Error);
}

// ------------------------------------------------------------------------------------------ positions
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

// ------------------------------------------------------------------------------------------- manifest
const char* const kBeaconManifest = R"({"name": "t0001", "epoch_utc": "2026-11-21T08:00:00Z",
 "station": {"lat_deg": 10, "lon_deg": 20, "h_m": 5},
 "cameras": {"az":  {"video": ["az/seg_000.mkv", "az/seg_001.mkv"], "frames": "az/frames.csv",
                     "model": "az/camera.json", "role": "beacon"}},
 "turret": "turret.csv", "range": "range.csv",
 "theodolite": null, "radar": null,
 "steps": {}, "operator": "kept"})";

std::string WithSteps(const std::string& steps) {
  std::string m = kBeaconManifest;
  const std::string from = "\"steps\": {}";
  m.replace(m.find(from), from.size(), "\"steps\": " + steps);
  return m;
}

// The error of ParseManifest, or "" if it accepts the text.
std::string ManifestError(const std::string& text) {
  try {
    ParseManifest(text, "/trials/t1/trial.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    return e.what();
  }
  return "";
}

TEST(Manifest, ReadsTheSpecExample) {
  const TrialManifest m = ParseManifest(kBeaconManifest, "/trials/t1/trial.json");
  EXPECT_EQ(m.dir, "/trials/t1");
  EXPECT_EQ(m.name, "t0001");
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].video.size(), 2u);
  EXPECT_EQ(m.cameras[0].role, CameraRole::kBeacon);
  EXPECT_EQ(m.turret, "turret.csv");
  EXPECT_TRUE(m.theodolite.empty());
  EXPECT_FALSE(m.radar.has_value());
  EXPECT_EQ(m.json["operator"], "kept");  // extra keys are kept
}

TEST(Manifest, ErrorsNameLineAndColumn) {
  std::string bad = kBeaconManifest;
  bad.replace(bad.find("\"beacon\""), 8, "\"beakon\"");
  EXPECT_EQ(ManifestError(bad).rfind("/trials/t1/trial.json:4:57: cameras.az.role: 'beakon' is not one of", 0), 0u)
      << ManifestError(bad);
  EXPECT_NE(ManifestError(WithSteps(R"({"locat": {}})")).find("trial.json:7:12: steps.locat: unknown step"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"locate": {"range": "r2.csv"}})")).find("cannot be overridden"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"az/attitude-oi": {}})")).find("does not apply to 'az'"), std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"cam9/locate": {}})")).find("no camera named 'cam9'"), std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"locate": {"x": {"y": 1}}})")).find("option values must be"),
            std::string::npos);
  EXPECT_NE(ManifestError(WithSteps(R"({"locate": 3})")).find("true or false"), std::string::npos);
  std::string no_target = kBeaconManifest;
  no_target.replace(no_target.find("\"beacon\""), 8, "\"features\"");
  EXPECT_NE(ManifestError(no_target).find("needs 'target'"), std::string::npos);
  std::string epoch = kBeaconManifest;
  epoch.replace(epoch.find("2026-11-21T08:00:00Z"), 20, "21/11/2026 08:00");
  EXPECT_NE(ManifestError(epoch).find("is not ISO-8601"), std::string::npos);
  EXPECT_NE(ManifestError("{\"cameras\": [}").find("invalid JSON"), std::string::npos);
  EXPECT_EQ(ManifestError(WithSteps(R"({"locate": {"range-interp": "linear"}, "az/plot": false})")), "");
}

TEST(Manifest, SettingsMergeUnitOverKind) {
  const TrialManifest m = ParseManifest(
      WithSteps(R"({"locate": {"range-interp": "linear", "turret-max-gap": 0.5},
                    "az/locate": {"range-interp": "cubic"}, "resample-range": false})"),
      "/t/trial.json");
  const StepSettings s = m.Settings("az", "locate");
  EXPECT_TRUE(s.enabled);
  ASSERT_EQ(s.options.size(), 2u);
  EXPECT_EQ(s.options[0].second, "cubic");
  EXPECT_FALSE(m.Settings("az", "resample-range").enabled);
  EXPECT_TRUE(m.Settings("az", "smooth").enabled);
}

TEST(Manifest, OverrideArgs) {
  StepSettings s;
  s.options = {{"range-interp", "linear"}, {"lead", 0.5}, {"window", 4}, {"smooth", true}, {"bg-plane", false},
               {"accel-sigma", io::Json::array({1.5, 2})}};
  EXPECT_EQ(OverrideArgs(s), (std::vector<std::string>{"--range-interp", "linear", "--lead", "0.5", "--window", "4",
                                                       "--smooth", "--accel-sigma", "1.5,2"}));
}

// ---------------------------------------------------------------------------------------------- plan
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
                                      "--turret", "turret.csv", "--range", "range.csv", "-o", "out/az/located.csv",
                                      "--range-interp", "linear"}));
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

// -------------------------------------------------------------------------------------------- digests
TEST(Digest, SizeMtimeShortcutAndContentHash) {
  TempDir d;
  Write(d / "a.csv", "t_s,x\n0,1\n");
  DigestCache first(d.path(), io::Json(), true);
  const FileDigest a = first.Digest("a.csv");
  EXPECT_TRUE(a.hashed);
  EXPECT_EQ(a.sha256, Sha256Hex("t_s,x\n0,1\n"));
  EXPECT_THROW(first.Digest("missing.csv"), Error);

  // Same size and mtime: the recorded hash is trusted (even a deliberately wrong one, which shows that
  // the file was not read); --rehash reads it.
  io::Json prev = first.ToJson();
  prev["a.csv"]["sha256"] = "recorded";
  DigestCache second(d.path(), prev, true);
  EXPECT_EQ(second.Digest("a.csv").sha256, "recorded");
  EXPECT_FALSE(second.Digest("a.csv").hashed);
  DigestCache rehash(d.path(), prev, false);
  EXPECT_EQ(rehash.Digest("a.csv").sha256, a.sha256);

  // A touch changes mtime only: hashed again, same content hash.
  struct timespec ts[2] = {{0, UTIME_NOW}, {1, 0}};
  ASSERT_EQ(::utimensat(AT_FDCWD, (d / "a.csv").c_str(), ts, 0), 0);
  DigestCache third(d.path(), first.ToJson(), true);
  EXPECT_TRUE(third.Digest("a.csv").hashed);
  EXPECT_EQ(third.Digest("a.csv").sha256, a.sha256);
  // New content: new hash.
  Write(d / "a.csv", "t_s,x\n0,2\n");
  DigestCache fourth(d.path(), first.ToJson(), true);
  EXPECT_NE(fourth.Digest("a.csv").sha256, a.sha256);
}

TEST(Digest, ImageSequencePattern) {
  TempDir d;
  for (int i : {0, 1, 2, 10}) {
    char name[32];
    std::snprintf(name, sizeof name, "seq/%06d.png", i);
    Write(d / name, "frame" + std::to_string(i));
  }
  Write(d / "seq/notes.txt", "x");
  EXPECT_TRUE(IsSequencePattern("seq/%06d.png"));
  EXPECT_FALSE(IsSequencePattern("seq/video.mkv"));
  const auto files = ExpandSequence(d / "seq/%06d.png");
  ASSERT_EQ(files.size(), 4u);
  EXPECT_EQ(fs::path(files.back()).filename(), "000010.png");
  DigestCache c(d.path(), io::Json(), true);
  const FileDigest s = c.Digest("seq/%06d.png");
  EXPECT_EQ(s.files, 4u);
  Write(d / "seq/000002.png", "changed");
  DigestCache c2(d.path(), io::Json(), true);
  EXPECT_NE(c2.Digest("seq/%06d.png").sha256, s.sha256);
  EXPECT_THROW(c2.Digest("seq/%04d.jpg"), Error);
}

// ------------------------------------------------------------------------------------------- build ID
TEST(ElfBuildId, MatchesReadelf) {
  const std::string self = SelfDir() + "/test_run";
  const std::string id = ElfBuildId(self);
  ASSERT_FALSE(id.empty()) << "Debian's toolchain links a GNU build ID into every executable";
  EXPECT_EQ(id.size() % 2, 0u);
  std::string out;
  if (::access("/usr/bin/readelf", X_OK) == 0) {
    ASSERT_EQ(RunAndCapture({"/usr/bin/readelf", "-n", self}, &out), 0);
    EXPECT_NE(out.find("Build ID: " + id), std::string::npos) << out;
  }
  TempDir d;
  Write(d / "script", "#!/bin/sh\necho hi\n");
  EXPECT_EQ(ElfBuildId(d / "script"), "");
  EXPECT_EQ(ElfBuildId(d / "missing"), "");
}

// ------------------------------------------------------------------------------------ lock and out/
TEST(TrialDir, LockIsExclusiveAndReleased) {
  TempDir d;
  std::string holder;
  auto first = TrialLock::Acquire(d.path(), 0.0, &holder);
  ASSERT_TRUE(first);
  // flock locks belong to the open file description: a second open in this process conflicts too.
  EXPECT_FALSE(TrialLock::Acquire(d.path(), 0.2, &holder));
  EXPECT_NE(holder.find("pid " + std::to_string(::getpid())), std::string::npos) << holder;
  first.reset();
  EXPECT_TRUE(TrialLock::Acquire(d.path(), 0.0, &holder));
}

TEST(TrialDir, CommitExchangesAndRemovesTheOldOut) {
  TempDir d;
  Write(d / "out/report.json", "old");
  Write(d / "out/a.csv", "old");
  const std::string work = MakeWorkDir(d.path());
  Write(work + "/report.json", "new");
  Write(work + "/a.csv", "new");
  const std::string how = CommitOut(d.path(), work);
  EXPECT_TRUE(how == "exchange" || how == "two-renames") << how;
  EXPECT_EQ(Read(d / "out/a.csv"), "new");
  EXPECT_FALSE(fs::exists(work));
  EXPECT_TRUE(RecoverAndClean(d.path()).empty());
  // First out/: a plain rename.
  TempDir e;
  const std::string w2 = MakeWorkDir(e.path());
  Write(w2 + "/report.json", "r");
  EXPECT_EQ(CommitOut(e.path(), w2), "rename");
  EXPECT_TRUE(fs::exists(e / "out/report.json"));
}

TEST(TrialDir, RecoveryAfterAKilledSwap) {
  TempDir d;
  // Killed between the two renames of the fallback swap: no out/, a complete new folder and the old one.
  Write(d / "out.old.AAAAAA/report.json", "old");
  Write(d / "out.tmp.BBBBBB/report.json", "new");
  Write(d / "out.tmp.CCCCCC/a.csv", "partial (no report.json)");
  const auto notes = RecoverAndClean(d.path());
  EXPECT_EQ(Read(d / "out/report.json"), "new");
  EXPECT_FALSE(fs::exists(d / "out.old.AAAAAA"));
  EXPECT_FALSE(fs::exists(d / "out.tmp.CCCCCC"));
  EXPECT_EQ(notes.size(), 3u);
  // Only the old one complete: it comes back.
  TempDir e;
  Write(e / "out.old.AAAAAA/report.json", "old");
  Write(e / "out.tmp.BBBBBB/a.csv", "partial");
  RecoverAndClean(e.path());
  EXPECT_EQ(Read(e / "out/report.json"), "old");
  // With an out/ present every temporary goes, complete or not.
  TempDir f;
  Write(f / "out/report.json", "current");
  Write(f / "out.tmp.BBBBBB/report.json", "stale");
  RecoverAndClean(f.path());
  EXPECT_EQ(Read(f / "out/report.json"), "current");
  EXPECT_FALSE(fs::exists(f / "out.tmp.BBBBBB"));
}

}  // namespace
}  // namespace rk::run
