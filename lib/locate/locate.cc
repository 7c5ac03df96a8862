// Locate pipeline; method, equations and assumptions in locate.h.
#include "locate/locate.h"

#include <algorithm>
#include <cmath>

#include "formats/located.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "track/boresight.h"

namespace rk::locate {

const io::OptionTable<LocateOptions>& LocateOptions::Table() {
  using track::InterpMethod;
  static const io::OptionTable<LocateOptions> table =
      io::OptionTable<LocateOptions>()
          .Choice("--turret-interp", &LocateOptions::turret_method,
                  {InterpMethod::kLinear, InterpMethod::kCubic}, track::InterpMethodName,
                  "Turret angle interpolation to frame times: linear or cubic")
          .Real("--turret-max-gap", &LocateOptions::turret_max_gap_s, "s", io::Bounds::Positive(),
                "Longest turret-log interval (s) interpolated across; frames in longer gaps are invalid")
          .Choice("--range-interp", &LocateOptions::range_method,
                  {InterpMethod::kLinear, InterpMethod::kCubic, InterpMethod::kLocalQuadratic,
                   InterpMethod::kLocalCubic},
                  track::InterpMethodName,
                  "Range interpolation to frame times: linear, cubic, local-quadratic or local-cubic")
          .Real("--range-max-gap", &LocateOptions::range_max_gap_s, "s", io::Bounds::Positive(),
                "Longest interval (s) between usable range samples interpolated across; device-error rows "
                "always break the interval")
          .Integer("--range-window", &LocateOptions::range_window, "samples per side", io::Bounds::Closed(2, 50),
                   "local-quadratic/local-cubic: range samples used on each side of the frame interval, 2..50")
          .Real("--sigma-px", &LocateOptions::sigma_px, "px", io::Bounds::AtLeast(0.0).Finite(),
                "1-sigma of x_px and y_px for tracks without sigma_x_px/sigma_y_px columns")
          .Real("--encoder-step-deg", &LocateOptions::encoder_step_deg, "deg", io::Bounds::Closed(0.0, 1.0),
                "Turret encoder step (deg): quantisation 1-sigma step/sqrt(12) per axis")
          .Real("--turret-sigma-deg", &LocateOptions::turret_sigma_deg, "deg", io::Bounds::Closed(0.0, 1.0),
                "Further turret angle 1-sigma per axis (deg): servo jitter, interpolation")
          .Real("--range-sigma-mm", &LocateOptions::range_sigma_mm, "mm", io::Bounds::AtLeast(0.0).Finite(),
                "1-sigma of the range interpolated to a frame (mm)");
  return table;
}

std::string RangeStatusName(RangeStatus status) {
  switch (status) {
    case RangeStatus::kOk:
      return "ok";
    case RangeStatus::kGap:
      return "gap";
    case RangeStatus::kDeviceError:
      return "device_error";
    case RangeStatus::kOutside:
      return "outside";
    case RangeStatus::kNoLog:
      return "none";
    case RangeStatus::kNotApplicable:
      return "";
  }
  return "?";
}

double LocateResult::RangeCoverage() const {
  if (rows_with_los == 0) return std::nan("");
  return static_cast<double>(rows_with_range) / static_cast<double>(rows_with_los);
}

io::Json LocateResult::SummaryJson() const {
  const double coverage = RangeCoverage();
  return {{"range_coverage", std::isfinite(coverage) ? io::Json(coverage) : io::Json(nullptr)},
          {"rows_with_los", rows_with_los},
          {"rows_with_range", rows_with_range}};
}

namespace {

io::Json LocateCounts(const LocateResult& r, std::size_t turret_empty_samples) {
  io::Json status = io::Json::object();
  for (int s = 0; s < 5; ++s) status[RowStatusName(static_cast<RowStatus>(s))] = r.rows_by_status[s];
  io::Json range_status = io::Json::object();
  for (int s = 0; s < 5; ++s) range_status[RangeStatusName(static_cast<RangeStatus>(s))] = r.rows_by_range_status[s];
  return {{"rows", r.rows.size()},
          {"status", status},
          {"range_status", range_status},
          {"rows_with_line_of_sight", r.rows_with_los},
          {"rows_with_range", r.rows_with_range},
          {"rows_turret_not_covered", r.rows_turret_not_covered},
          {"measured_rows_turret_not_covered", r.measured_rows_turret_not_covered},
          {"turret_duplicate_times", r.turret_duplicate_times},
          {"turret_empty_samples", turret_empty_samples},
          {"range_duplicate_times", r.range_duplicate_times},
          {"range_device_errors", r.range_device_errors}};
}

}  // namespace

io::RunSummary LocateSummary(const LocateResult& r, const LocateOptions& options, const LocateSources& sources) {
  io::RunSummary s;
  for (int k = 0; k < 5; ++k) s.CountRows(static_cast<RowStatus>(k), r.rows_by_status[k]);
  if (r.rows_turret_not_covered > 0) {
    s.Warn("turret_not_covered", std::to_string(r.rows_turret_not_covered) + " of " + std::to_string(r.rows.size()) +
                                     " frame times are not covered by " + sources.turret + " (" +
                                     std::to_string(r.measured_rows_turret_not_covered) +
                                     " measured rows written as invalid)");
  }
  if (!sources.range.empty() && r.rows_with_los > 0 && r.rows_with_range == 0) {
    s.Warn("no_range", "no frame got a range from " + sources.range + " (check its time span and status)");
  }
  const double coverage = r.RangeCoverage();
  if (std::isfinite(coverage)) {
    s.AddFigure("range coverage", coverage, "fraction", "rows with a range");
  }
  io::Json& d = s.details;
  d["options"] = options.ToJson();
  if (options.station) {
    d["station"] = {{"lat_deg", options.station->lat_deg}, {"lon_deg", options.station->lon_deg},
                    {"h_m", options.station->h_m}};
  }
  if (r.time_offset_s != 0.0) d["time_offset_s"] = r.time_offset_s;
  d["counts"] = LocateCounts(r, sources.turret_empty_samples);
  d["range_coverage"] = std::isfinite(coverage) ? io::Json(coverage) : io::Json(nullptr);
  d["summary"] = r.SummaryJson();
  return s;
}

static RangeStatus FromInterpStatus(track::InterpStatus s) {
  switch (s) {
    case track::InterpStatus::kOk:
      return RangeStatus::kOk;
    case track::InterpStatus::kOutside:
      return RangeStatus::kOutside;
    case track::InterpStatus::kGap:
      return RangeStatus::kGap;
    case track::InterpStatus::kUnusable:
      return RangeStatus::kDeviceError;
  }
  return RangeStatus::kOutside;
}

namespace {

// Central difference of an interpolated log at t (one-sided at an end, 0 where it has no value).
template <typename At>
double Rate(double t_s, const At& at) {
  constexpr double kHalfStep_s = 0.01;
  const std::optional<double> lo = at(t_s - kHalfStep_s), mid = at(t_s), hi = at(t_s + kHalfStep_s);
  if (lo && hi) return (*hi - *lo) / (2.0 * kHalfStep_s);
  if (mid && hi) return (*hi - *mid) / kHalfStep_s;
  if (lo && mid) return (*mid - *lo) / kHalfStep_s;
  return 0.0;
}

// The stages of Locate (locate.h steps 0–6), one track row at a time.
class LocateRun {
 public:
  LocateRun(const formats::Track& track, const camera::CameraModel& camera, formats::TurretLog turret, const formats::RangeLog* range,
            const LocateOptions& options)
      : camera_(camera), options_(options),
        boresight_(track::BoresightSource::FromLog(std::move(turret), options.turret_method, options.turret_max_gap_s)) {
    result_.has_frame = track.has_frame;
    result_.has_station = options.station.has_value();
    result_.time_offset_s = camera.time_offset_s;
    result_.turret_duplicate_times = boresight_.duplicate_times();
    if (options.pointing) terms_ = options.pointing->terms;
    if (options.station) enu_.emplace(*options.station);
    Sigmas();
    if (range != nullptr) Range(*range);
    result_.rows.reserve(track.rows.size());
  }

  void Row(const formats::TrackRow& in) {
    LocatedRow out;
    out.frame = in.frame;
    out.t_s = in.t_s + camera_.time_offset_s;
    out.status = in.status;
    const std::optional<geo::AzEl> b = boresight_.At(out.t_s);
    if (b) {
      out.boresight_az_rad = b->az_rad;
      out.boresight_el_rad = b->el_rad;
    } else {
      ++result_.rows_turret_not_covered;
    }
    if (in.px && !b) {
      ++result_.measured_rows_turret_not_covered;
      out.status = RowStatus::kInvalid;
    } else if (in.px) {
      LineOfSight(in, *b, &out);
    }
    ++result_.rows_by_status[static_cast<std::size_t>(out.status)];
    ++result_.rows_by_range_status[static_cast<std::size_t>(out.range_status)];
    result_.rows.push_back(out);
  }

  LocateResult Finish(const formats::Track& track) {
    if (!track.rows.empty() && result_.rows_turret_not_covered == track.rows.size()) {
      boresight_.ThrowNoFrameCovered("turret", track.source, track.rows.front().t_s + camera_.time_offset_s,
                                     track.rows.back().t_s + camera_.time_offset_s, "--turret-max-gap");
    }
    return std::move(result_);
  }

 private:
  void Sigmas() {
    sources_.pixel_px = options_.sigma_px;
    const double step = geo::DegToRad(options_.encoder_step_deg), extra = geo::DegToRad(options_.turret_sigma_deg);
    sources_.turret_rad = std::sqrt(step * step / 12.0 + extra * extra);
    sources_.range_m = options_.range_sigma_mm * 1e-3;
    CameraSigma(camera_, options_.camera_source, &sources_);
    if (options_.pointing) PointingSigma(*options_.pointing, &sources_);
  }

  void Range(const formats::RangeLog& range) {
    std::vector<double> t_r = range.t_s;
    auto r = range.range_m;
    result_.range_duplicate_times = track::MergeDuplicateTimes(&t_r, &r);
    result_.range_device_errors = range.device_errors;
    track::InterpOptions range_opt;
    range_opt.method = options_.range_method;
    range_opt.max_gap_s = options_.range_max_gap_s;
    range_opt.window = options_.range_window;
    range_interp_.emplace(t_r, r, range_opt);
  }

  std::optional<double> RangeAt(double t_s) const {
    const track::InterpValue r = range_interp_->At(t_s);
    return r.ok() ? std::optional<double>(r.value) : std::nullopt;
  }

  // Steps 2–6 for a row with a pixel and a boresight.
  void LineOfSight(const formats::TrackRow& in, const geo::AzEl& b, LocatedRow* out) {
    const Eigen::Vector3d ray_enu = camera_.RayEnu(*in.px, b.az_rad, b.el_rad, terms_).normalized();
    const geo::AzEl los = geo::AzElFromEnu(ray_enu);
    out->az_rad = los.az_rad;
    out->el_rad = los.el_rad;
    ++result_.rows_with_los;
    if (!range_interp_) {
      out->range_status = RangeStatus::kNoLog;
    } else {
      const track::InterpValue r = range_interp_->At(out->t_s);
      out->range_status = FromInterpStatus(r.status);
      if (r.ok()) {
        out->range_m = r.value;
        out->p_enu_m = r.value * ray_enu;
        ++result_.rows_with_range;
        if (enu_) out->geodetic = enu_->ToGeodetic(*out->p_enu_m);
      }
    }
    out->cov = Covariance(in, b, *out);
  }

  LocatedCovariance Covariance(const formats::TrackRow& in, const geo::AzEl& b, const LocatedRow& out) const {
    SigmaPoint p;
    p.px = *in.px;
    p.sigma_px = in.sigma_px.value_or(Eigen::Vector2d::Constant(sources_.pixel_px));
    p.az_rad = b.az_rad;
    p.el_rad = b.el_rad;
    if (sources_.time_offset_s > 0.0) {
      const double t = out.t_s;
      // Azimuth rate on the unwrapped angle: differences wrapped to (−π, π].
      p.az_rate = Rate(t, [&](double u) -> std::optional<double> {
        const auto a = boresight_.At(u);
        return a ? std::optional<double>(geo::WrapPi(a->az_rad - b.az_rad)) : std::nullopt;
      });
      p.el_rate = Rate(t, [&](double u) -> std::optional<double> {
        const auto a = boresight_.At(u);
        return a ? std::optional<double>(a->el_rad) : std::nullopt;
      });
      if (out.range_m) p.range_rate_mps = Rate(t, [&](double u) { return RangeAt(u); });
    }
    p.range_m = out.range_m.value_or(0.0);
    return LocatedCovarianceAt(camera_, terms_, p, sources_);
  }

  const camera::CameraModel& camera_;
  const LocateOptions& options_;
  const track::BoresightSource boresight_;
  std::optional<track::TimeSeriesInterpolator> range_interp_;
  geo::PointingTerms terms_;
  SigmaSources sources_;
  std::optional<geo::LocalEnu> enu_;
  LocateResult result_;
};

}  // namespace

LocateResult Locate(const formats::Track& track, const camera::CameraModel& camera, formats::TurretLog turret,
                    const formats::RangeLog* range, const LocateOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  LocateRun run(track, camera, std::move(turret), range, options);
  for (const formats::TrackRow& in : track.rows) run.Row(in);
  return run.Finish(track);
}

namespace {

// The file's record of a row: 1σ of az, el (range, e, n, u only with a range) from the covariance, and
// corr_az_el, the correlation of the azimuth and elevation errors (the pixel, turret, pointing-model and
// mount errors all move both angles), which rk-intersect weights the line of sight with (issue 28 item 6).
formats::LocatedRecord Record(const LocatedRow& row) {
  formats::LocatedRecord r;
  r.frame = row.frame;
  r.t_s = row.t_s;
  r.id = row.id;
  r.az_rad = row.az_rad;
  r.el_rad = row.el_rad;
  r.range_m = row.range_m;
  r.enu_m = row.p_enu_m;
  r.status = row.status;
  r.range_status = RangeStatusName(row.range_status);
  r.boresight_az_rad = row.boresight_az_rad;
  r.boresight_el_rad = row.boresight_el_rad;
  r.geodetic = row.geodetic;
  if (!row.cov) return r;
  const LocatedCovariance& c = *row.cov;
  auto sd = [&](int i) { return std::sqrt(std::max(c(i, i), 0.0)); };
  r.sigma_az_rad = sd(0);
  r.sigma_el_rad = sd(1);
  if (row.range_m) {
    r.sigma_range_m = sd(2);
    r.sigma_enu_m = Eigen::Vector3d(sd(3), sd(4), sd(5));
  }
  const double s = sd(0) * sd(1);
  if (s > 0.0) r.corr_az_el = std::clamp(c(0, 1) / s, -1.0, 1.0);
  return r;
}

}  // namespace

LocateResult MergeById(std::vector<std::pair<std::string, LocateResult>> by_id) {
  LocateResult out;
  if (by_id.empty()) return out;
  out = by_id.front().second;  // flags and time offset (the same camera for every id)
  out.rows.clear();
  out.has_id = true;
  out.rows_by_status = {};
  out.rows_by_range_status = {};
  out.rows_with_los = out.rows_with_range = out.rows_turret_not_covered = out.measured_rows_turret_not_covered = 0;
  for (auto& [id, r] : by_id) {
    for (LocatedRow& row : r.rows) {
      row.id = id;
      out.rows.push_back(std::move(row));
    }
    for (std::size_t k = 0; k < out.rows_by_status.size(); ++k) out.rows_by_status[k] += r.rows_by_status[k];
    for (std::size_t k = 0; k < out.rows_by_range_status.size(); ++k) {
      out.rows_by_range_status[k] += r.rows_by_range_status[k];
    }
    out.rows_with_los += r.rows_with_los;
    out.rows_with_range += r.rows_with_range;
    out.rows_turret_not_covered += r.rows_turret_not_covered;
    out.measured_rows_turret_not_covered += r.measured_rows_turret_not_covered;
  }
  std::stable_sort(out.rows.begin(), out.rows.end(),
                   [](const LocatedRow& a, const LocatedRow& b) { return a.t_s < b.t_s; });
  return out;
}

io::CsvWriter LocatedCsv(const LocateResult& result) {
  formats::LocatedLayout layout;
  layout.frame = result.has_frame;
  layout.locate_extras = layout.sigma_enu = layout.corr = true;
  layout.geodetic = result.has_station;
  layout.id = result.has_id;
  formats::LocatedWriter w(layout);
  for (const LocatedRow& row : result.rows) w.Add(Record(row));
  return w.Take();
}

}  // namespace rk::locate
