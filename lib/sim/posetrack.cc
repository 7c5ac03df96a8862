#include "sim/posetrack.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "sim/trial_folder.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace fs = std::filesystem;
namespace {

constexpr int kValueDecimals = 9;  // m and deg: 1 nm / 1e-9° — far below any noise, so truth interpolates exactly

// Head profile (see the header): number of sines per component and their ranges.
constexpr int kHeadSines = 3;
constexpr double kHeadMinHz = 0.1, kHeadMaxHz = 2.0;
constexpr double kHeadMinPosAmpM = 0.1, kHeadMaxPosAmpM = 0.3;
constexpr double kHeadMinAngAmpDeg = 10.0, kHeadMaxAngAmpDeg = 40.0;
constexpr double kHeadCentreZ_m = 0.8;

// Turntable: the fixed part of the pose.
constexpr double kTurntableX_m = 0.05, kTurntableY_m = -0.02, kTurntableZ_m = 0.80;
constexpr double kTurntablePitchDeg = 10.0, kTurntableRollDeg = -5.0;

// Sample grid tolerance: 0–9 s at 20 fps must give 181 samples although 9·20 is computed in floating point.
constexpr double kGridEps = 1e-9;


double FileValue(int c, double v) {
  if (!PoseIsAngle(c)) return v;
  const double deg = geo::RadToDeg(v);
  if (c == kPoseYaw) return geo::WrapDeg360(deg);
  if (c == kPoseYaw + 2) return geo::WrapDeg180(deg);  // roll
  return deg;                                           // pitch: within [−90, 90] by construction
}
double FileRate(int c, double v) { return PoseIsAngle(c) ? geo::RadToDeg(v) : v; }

}  // namespace

bool ParsePoseScenario(const std::string& name, PoseScenario* scenario) {
  if (name == "turntable") {
    *scenario = PoseScenario::kTurntable;
  } else if (name == "head") {
    *scenario = PoseScenario::kHead;
  } else {
    return false;
  }
  return true;
}

std::string PoseScenarioName(PoseScenario scenario) {
  return scenario == PoseScenario::kTurntable ? "turntable" : "head";
}

const std::array<std::string, kPoseDof>& PoseColumns() {
  static const std::array<std::string, kPoseDof> c{"x_m", "y_m", "z_m", "yaw_deg", "pitch_deg", "roll_deg"};
  return c;
}
const std::array<std::string, kPoseDof>& PoseRateColumns() {
  static const std::array<std::string, kPoseDof> c{"x_rate_m_s",     "y_rate_m_s",       "z_rate_m_s",
                                                   "yaw_rate_deg_s", "pitch_rate_deg_s", "roll_rate_deg_s"};
  return c;
}
const std::array<std::string, kPoseDof>& PoseAccelColumns() {
  static const std::array<std::string, kPoseDof> c{"x_accel_m_s2",     "y_accel_m_s2",       "z_accel_m_s2",
                                                   "yaw_accel_deg_s2", "pitch_accel_deg_s2", "roll_accel_deg_s2"};
  return c;
}
bool PoseIsAngle(int component) { return component >= kPoseYaw; }

const io::OptionTable<PoseTrackOptions>& PoseTrackOptions::Table() {
  using O = PoseTrackOptions;
  using io::Bounds;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--scenario", &O::scenario, {PoseScenario::kTurntable, PoseScenario::kHead}, PoseScenarioName,
                  "turntable (seed 000: yaw at 10 deg/s, 20 fps, 0-9 s) or head (maneuvering 6-DOF head motion)")
          .Real("--fps", &O::fps, "Hz", Bounds::LeftOpen(0, 1000), "Sample rate (Hz)")
          .Real("--t0", &O::t0_s, "s", Bounds::AtLeast(0), "Time of sample 0 since the epoch (s)")
          .Count("--seed", &O::seed, "", Bounds::Any(), "Random seed (same seed, same files)")
          .Real("--noise-deg", &O::noise_deg, "deg", Bounds::Closed(0, 10),
                "Measurement noise std of the three angles (deg)")
          .Real("--noise-m", &O::noise_position_m, "m", Bounds::Closed(0, 1), "Measurement noise std of x, y, z (m)")
          .Real("--dropout", &O::dropout, "", Bounds::RightOpen(0, 1),
                "Probability that a measurement row is missing (all values empty)")
          .Real("--dropout-value", &O::dropout_value, "", Bounds::RightOpen(0, 1),
                "Probability that a single measured value is missing");
  return table;
}

bool PoseTrackOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!Table().Check(*this, why)) return false;
  if (!std::isfinite(t0_s)) return fail("--t0 must be finite");
  if (!(duration_s > 0 && duration_s <= 3600)) return fail("duration must be in (0, 3600] s");
  if (std::floor(duration_s * fps + kGridEps) < 2) return fail("duration x fps gives fewer than 3 samples");
  if (!(std::abs(rate_rad_s) <= geo::DegToRad(1000.0))) return fail("turntable rate must be in [-1000, 1000] deg/s");
  if (!(yaw0_rad >= 0 && yaw0_rad < geo::kTwoPi)) return fail("turntable initial yaw must be in [0, 360) deg");
  return true;
}

io::Json PoseTrackOptions::ToJson() const {
  const io::Json sim = PoseTrackOptionsToJson(*this);
  io::Json j = Table().ToJson(*this);
  for (const char* key : {"duration_s", "rate_deg_s", "yaw0_deg"}) {
    if (sim.contains(key)) j[key] = sim[key];
  }
  return j;
}

const io::OptionTable<PoseTrackWriteOptions>& PoseTrackWriteOptions::Table() {
  static const io::OptionTable<PoseTrackWriteOptions> table = io::OptionTable<PoseTrackWriteOptions>().Flag(
      "--force", &PoseTrackWriteOptions::force, "Replace an existing non-empty --out folder");
  return table;
}

PoseTrackOptions DefaultPoseTrackOptions(PoseScenario scenario) {
  PoseTrackOptions o;
  o.scenario = scenario;
  o.duration_s = scenario == PoseScenario::kTurntable ? 9.0 : 20.0;
  return o;
}

io::Json PoseTrackOptionsToJson(const PoseTrackOptions& opt) {
  io::Json j;
  j["scenario"] = PoseScenarioName(opt.scenario);
  j["duration_s"] = opt.duration_s;
  j["fps"] = opt.fps;
  j["t0_s"] = opt.t0_s;
  j["noise_deg"] = geo::RadToDeg(opt.noise_angle_rad());
  j["noise_m"] = opt.noise_position_m;
  if (opt.scenario == PoseScenario::kTurntable) {
    j["rate_deg_s"] = geo::RadToDeg(opt.rate_rad_s);
    j["yaw0_deg"] = geo::RadToDeg(opt.yaw0_rad);
  }
  j["dropout"] = opt.dropout;
  j["dropout_value"] = opt.dropout_value;
  j["seed"] = opt.seed;
  return j;
}

PoseTrackSimulator::PoseTrackSimulator(PoseTrackOptions opt) : opt_(std::move(opt)) {
  std::string why;
  if (!opt_.Check(&why)) throw UsageError(why);

  const auto k_last = static_cast<std::size_t>(std::floor(opt_.duration_s * opt_.fps + kGridEps));
  sample_t_s_.resize(k_last + 1);
  mid_t_s_.resize(k_last);
  for (std::size_t k = 0; k <= k_last; ++k) sample_t_s_[k] = opt_.t0_s + static_cast<double>(k) / opt_.fps;
  for (std::size_t k = 0; k < k_last; ++k) mid_t_s_[k] = opt_.t0_s + (static_cast<double>(k) + 0.5) / opt_.fps;

  if (opt_.scenario == PoseScenario::kTurntable) {
    const double fixed[kPoseDof] = {kTurntableX_m, kTurntableY_m, kTurntableZ_m, opt_.yaw0_rad,
                                    geo::DegToRad(kTurntablePitchDeg), geo::DegToRad(kTurntableRollDeg)};
    for (int c = 0; c < kPoseDof; ++c) motion_[c].centre = fixed[c];
    motion_[kPoseYaw].slope = opt_.rate_rad_s;
  } else {
    std::mt19937_64 rng = SplitSeedStream(opt_.seed, 1);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (int c = 0; c < kPoseDof; ++c) {
      const double amp = PoseIsAngle(c)
                             ? geo::DegToRad(kHeadMinAngAmpDeg + (kHeadMaxAngAmpDeg - kHeadMinAngAmpDeg) * u01(rng))
                             : kHeadMinPosAmpM + (kHeadMaxPosAmpM - kHeadMinPosAmpM) * u01(rng);
      double wsum = 0;
      std::vector<double> w(kHeadSines);
      motion_[c].sines.resize(kHeadSines);
      for (int i = 0; i < kHeadSines; ++i) {
        PoseSine& s = motion_[c].sines[i];
        s.freq_hz = kHeadMinHz + (kHeadMaxHz - kHeadMinHz) * u01(rng);
        s.phase_rad = geo::kTwoPi * u01(rng);
        w[i] = (0.5 + 0.5 * u01(rng)) / s.freq_hz;
        wsum += w[i];
      }
      for (int i = 0; i < kHeadSines; ++i) motion_[c].sines[i].amplitude = amp * w[i] / wsum;
    }
    motion_[2].centre = kHeadCentreZ_m;
    // Yaw centre: the oscillating part's range over the sample and mid-times is centred on
    // north, so the yaw takes both signs there and crosses 0/360 at least once.
    double lo = INFINITY, hi = -INFINITY;
    for (const auto* times : {&sample_t_s_, &mid_t_s_}) {
      for (double t : *times) {
        const double v = TruthAt(t).value[kPoseYaw];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    motion_[kPoseYaw].centre = -0.5 * (lo + hi);
  }

  // Measurements: noise (stream 2) and dropout (stream 3) are drawn for every sample and
  // component whatever the options, so one option does not change the other's draws.
  std::mt19937_64 noise_rng = SplitSeedStream(opt_.seed, 2), drop_rng = SplitSeedStream(opt_.seed, 3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  meas_.resize(sample_t_s_.size());
  for (std::size_t k = 0; k < sample_t_s_.size(); ++k) {
    PoseMeasurement& m = meas_[k];
    m.t_s = sample_t_s_[k];
    m.value = TruthAt(m.t_s).value;
    for (int c = 0; c < kPoseDof; ++c) {
      m.value[c] += (PoseIsAngle(c) ? opt_.noise_angle_rad() : opt_.noise_position_m) * gauss(noise_rng);
    }
    m.row_missing = u01(drop_rng) < opt_.dropout;
    for (int c = 0; c < kPoseDof; ++c) {
      const bool drop_value = u01(drop_rng) < opt_.dropout_value;
      if (m.row_missing || drop_value) m.value[c] = NAN;
    }
  }
}

PoseTruth PoseTrackSimulator::TruthAt(double t_s) const {
  PoseTruth p;
  p.t_s = t_s;
  const double dt = t_s - opt_.t0_s;
  for (int c = 0; c < kPoseDof; ++c) {
    const PoseComponentMotion& m = motion_[c];
    double v = m.centre + m.slope * dt, r = m.slope, a = 0;
    for (const PoseSine& s : m.sines) {
      const double w = geo::kTwoPi * s.freq_hz;
      const double arg = w * dt + s.phase_rad;
      v += s.amplitude * std::sin(arg);
      r += s.amplitude * w * std::cos(arg);
      a -= s.amplitude * w * w * std::sin(arg);
    }
    p.value[c] = v;
    p.rate[c] = r;
    p.accel[c] = a;
  }
  return p;
}

bool PoseTrackWriteOptions::Check(std::string* why) const {
  if (out_dir.empty() || out_dir == "-") {
    if (why) *why = "--out must name a folder";
    return false;
  }
  return true;
}

io::Json PoseTrackSummary::ToJson() const {
  io::Json j;
  j["samples"] = samples;
  j["mid_times"] = mid_times;
  j["missing_rows"] = missing_rows;
  j["missing_values"] = missing_values;
  j["yaw_wraps"] = yaw_wraps;
  j["max_abs_rate_deg_s"] = max_abs_rate_deg_s;
  j["max_abs_accel_deg_s2"] = max_abs_accel_deg_s2;
  j["max_abs_speed_mps"] = max_abs_speed_mps;
  return j;
}

namespace {

// measurements.csv; the sample and missing counts of `sum`.
io::CsvWriter MeasurementsCsv(const PoseTrackSimulator& sim, PoseTrackSummary* out) {
  PoseTrackSummary& sum = *out;
  std::vector<std::string> meas_cols{"t_s"};
  for (const auto& c : PoseColumns()) meas_cols.push_back(c);
  io::CsvWriter meas_csv(meas_cols);
  for (const PoseMeasurement& m : sim.measurements()) {
    meas_csv.Add(m.t_s, kTimeDecimals);
    for (int c = 0; c < kPoseDof; ++c) {
      if (std::isnan(m.value[c])) {
        meas_csv.AddEmpty();
        if (!m.row_missing) ++sum.missing_values;
      } else {
        meas_csv.Add(FileValue(c, m.value[c]), kValueDecimals);
      }
    }
    meas_csv.EndRow();
    if (m.row_missing) ++sum.missing_rows;
  }
  sum.samples = static_cast<std::int64_t>(sim.sample_count());
  sum.mid_times = static_cast<std::int64_t>(sim.mid_times().size());
  return meas_csv;
}

// truth.csv (sample and mid rows), truth_sample.csv, truth_mid.csv; the yaw wraps and largest rates of `sum`.
void WriteTruth(const PoseTrackSimulator& sim, const fs::path& root, PoseTrackSummary* out) {
  PoseTrackSummary& sum = *out;
  // Truth: merged (kind sample/mid, time order), and split by kind.
  std::vector<std::string> value_cols;
  for (int c = 0; c < kPoseDof; ++c) value_cols.push_back(PoseColumns()[c]);
  for (int c = 0; c < kPoseDof; ++c) value_cols.push_back(PoseRateColumns()[c]);
  for (int c = 0; c < kPoseDof; ++c) value_cols.push_back(PoseAccelColumns()[c]);
  std::vector<std::string> all_cols{"t_s", "kind"}, split_cols{"t_s"};
  all_cols.insert(all_cols.end(), value_cols.begin(), value_cols.end());
  split_cols.insert(split_cols.end(), value_cols.begin(), value_cols.end());
  io::CsvWriter truth_csv(all_cols), sample_csv(split_cols), mid_csv(split_cols);
  auto add_values = [](io::CsvWriter& w, const PoseTruth& p) {
    for (int c = 0; c < kPoseDof; ++c) w.Add(FileValue(c, p.value[c]), kValueDecimals);
    for (int c = 0; c < kPoseDof; ++c) w.Add(FileRate(c, p.rate[c]), kValueDecimals);
    for (int c = 0; c < kPoseDof; ++c) w.Add(FileRate(c, p.accel[c]), kValueDecimals);
  };
  double prev_turns = NAN;
  auto account = [&](const PoseTruth& p) {
    const double turns = std::floor(p.value[kPoseYaw] / geo::kTwoPi);
    if (!std::isnan(prev_turns) && turns != prev_turns) sum.yaw_wraps += static_cast<std::int64_t>(std::abs(turns - prev_turns));
    prev_turns = turns;
    for (int c = 0; c < kPoseDof; ++c) {
      if (PoseIsAngle(c)) {
        sum.max_abs_rate_deg_s = std::max(sum.max_abs_rate_deg_s, std::abs(geo::RadToDeg(p.rate[c])));
        sum.max_abs_accel_deg_s2 = std::max(sum.max_abs_accel_deg_s2, std::abs(geo::RadToDeg(p.accel[c])));
      } else {
        sum.max_abs_speed_mps = std::max(sum.max_abs_speed_mps, std::abs(p.rate[c]));
      }
    }
  };
  const auto& ts = sim.sample_times();
  const auto& tm = sim.mid_times();
  for (std::size_t k = 0; k < ts.size(); ++k) {
    const PoseTruth p = sim.TruthAt(ts[k]);
    account(p);
    truth_csv.Add(p.t_s, kTimeDecimals).Add("sample");
    add_values(truth_csv, p);
    truth_csv.EndRow();
    sample_csv.Add(p.t_s, kTimeDecimals);
    add_values(sample_csv, p);
    sample_csv.EndRow();
    if (k < tm.size()) {
      const PoseTruth q = sim.TruthAt(tm[k]);
      account(q);
      truth_csv.Add(q.t_s, kTimeDecimals).Add("mid");
      add_values(truth_csv, q);
      truth_csv.EndRow();
      mid_csv.Add(q.t_s, kTimeDecimals);
      add_values(mid_csv, q);
      mid_csv.EndRow();
    }
  }
  truth_csv.Write((root / "truth.csv").string());
  sample_csv.Write((root / "truth_sample.csv").string());
  mid_csv.Write((root / "truth_mid.csv").string());
}

// scenario.json: everything needed to reproduce and to interpret the files.
io::Json PoseScenarioJson(const PoseTrackSimulator& sim, const PoseTrackSummary& sum) {
  const PoseTrackOptions& so = sim.options();
  io::Json j;
  j["generator"] = "rk-sim posetrack";
  j["scenario"] = PoseScenarioName(so.scenario);
  j["seed"] = so.seed;
  j["options"] = PoseTrackOptionsToJson(so);
  io::Json motion = io::Json::object();
  for (int c = 0; c < kPoseDof; ++c) {
    const PoseComponentMotion& m = sim.motion()[c];
    io::Json mj;
    mj["centre"] = FileRate(c, m.centre);  // unwrapped, file units (m or deg)
    mj["slope_per_s"] = FileRate(c, m.slope);
    mj["sines"] = io::Json::array();
    for (const PoseSine& s : m.sines) {
      mj["sines"].push_back(
          {{"amplitude", FileRate(c, s.amplitude)}, {"freq_hz", s.freq_hz}, {"phase_rad", s.phase_rad}});
    }
    motion[PoseColumns()[c]] = mj;
  }
  j["motion"] = motion;
  j["motion_model"] = "value(t) = centre + slope_per_s*(t - t0) + sum amplitude*sin(2*pi*freq_hz*(t - t0) + phase_rad)";
  j["noise_std"] = {{"x_m", so.noise_position_m},
                    {"y_m", so.noise_position_m},
                    {"z_m", so.noise_position_m},
                    {"yaw_deg", geo::RadToDeg(so.noise_angle_rad())},
                    {"pitch_deg", geo::RadToDeg(so.noise_angle_rad())},
                    {"roll_deg", geo::RadToDeg(so.noise_angle_rad())}};
  j["files"] = {{"measurements", "measurements.csv"},
                {"truth", "truth.csv"},
                {"truth_sample", "truth_sample.csv"},
                {"truth_mid", "truth_mid.csv"}};
  j["summary"] = sum.ToJson();
  return j;
}

}  // namespace

PoseTrackSummary WritePoseTrack(const PoseTrackSimulator& sim, const PoseTrackWriteOptions& opt) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  TrialFolder folder(opt.out_dir, opt.force);
  const fs::path root(folder.Path(""));
  PoseTrackSummary sum;
  const io::CsvWriter meas_csv = MeasurementsCsv(sim, &sum);
  meas_csv.Write((root / "measurements.csv").string());
  WriteTruth(sim, root, &sum);
  io::WriteJson((root / "scenario.json").string(), PoseScenarioJson(sim, sum));
  folder.Commit();
  return sum;
}

}  // namespace rk::sim
