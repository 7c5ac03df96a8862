// Locate pipeline; method, equations and assumptions in locate.h.
#include "locate/locate.h"

#include <cmath>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"
#include "locate/boresight.h"

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
                   "local-quadratic/local-cubic: range samples used on each side of the frame interval, 2..50");
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

LocateResult Locate(const Track& track, const camera::CameraModel& camera, const TurretLog& turret,
                    const RangeLog* range, const LocateOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  LocateResult result;
  result.has_frame = track.has_frame;

  // Turret: merge repeated time stamps, interpolate az on the unwrapped sequence (boresight.h).
  const BoresightSource boresight = BoresightSource::FromLog(turret, options.turret_method, options.turret_max_gap_s);
  result.turret_duplicate_times = boresight.duplicate_times();

  std::optional<track::TimeSeriesInterpolator> range_interp;
  if (range != nullptr) {
    std::vector<double> t_r = range->t_s;
    auto r = range->range_m;
    result.range_duplicate_times = track::MergeDuplicateTimes(&t_r, &r);
    result.range_device_errors = range->device_errors;
    track::InterpOptions range_opt;
    range_opt.method = options.range_method;
    range_opt.max_gap_s = options.range_max_gap_s;
    range_opt.window = options.range_window;
    range_interp.emplace(t_r, r, range_opt);
  }

  result.rows.reserve(track.rows.size());
  for (const TrackRow& in : track.rows) {
    LocatedRow out;
    out.frame = in.frame;
    out.t_s = in.t_s;
    out.status = in.status;
    const std::optional<geo::AzEl> b = boresight.At(in.t_s);
    const bool turret_ok = b.has_value();
    if (turret_ok) {
      out.boresight_az_rad = b->az_rad;
      out.boresight_el_rad = b->el_rad;
    } else {
      ++result.rows_turret_not_covered;
    }
    if (in.px && !turret_ok) {
      ++result.measured_rows_turret_not_covered;
      out.status = TrackStatus::kInvalid;
    } else if (in.px) {
      const Eigen::Vector3d ray_enu = camera.RayEnu(*in.px, b->az_rad, b->el_rad).normalized();
      const geo::AzEl los = geo::AzElFromEnu(ray_enu);
      out.az_rad = los.az_rad;
      out.el_rad = los.el_rad;
      ++result.rows_with_los;
      if (!range_interp) {
        out.range_status = RangeStatus::kNoLog;
      } else {
        const track::InterpValue r = range_interp->At(in.t_s);
        out.range_status = FromInterpStatus(r.status);
        if (r.ok()) {
          out.range_m = r.value;
          out.p_enu_m = r.value * ray_enu;
          ++result.rows_with_range;
        }
      }
    }
    ++result.rows_by_status[static_cast<std::size_t>(out.status)];
    ++result.rows_by_range_status[static_cast<std::size_t>(out.range_status)];
    result.rows.push_back(out);
  }

  if (!track.rows.empty() && result.rows_turret_not_covered == track.rows.size()) {
    boresight.ThrowNoFrameCovered("turret", track.source, track.rows.front().t_s, track.rows.back().t_s,
                                  "--turret-max-gap");
  }
  return result;
}

io::CsvWriter LocatedCsv(const LocateResult& result) {
  std::vector<std::string> cols;
  if (result.has_frame) cols.push_back("frame");
  for (const char* c : {"t_s", "az_deg", "el_deg", "range_m", "e_m", "n_m", "u_m", "status", "range_status",
                        "boresight_az_deg", "boresight_el_deg"}) {
    cols.push_back(c);
  }
  io::CsvWriter w(cols);
  constexpr int kAngleDecimals = 9;   // 1e-9° = 3.6e-6″
  constexpr int kLengthDecimals = 6;  // µm
  auto deg = [](const std::optional<double>& rad) {
    return rad ? std::optional<double>(geo::RadToDeg(*rad)) : std::nullopt;
  };
  for (const LocatedRow& row : result.rows) {
    if (result.has_frame) {
      if (row.frame) {
        w.Add(*row.frame);
      } else {
        w.AddEmpty();
      }
    }
    w.Add(row.t_s, 9);
    w.Add(deg(row.az_rad), kAngleDecimals);
    w.Add(deg(row.el_rad), kAngleDecimals);
    w.Add(row.range_m, kLengthDecimals);
    for (int i = 0; i < 3; ++i) {
      w.Add(row.p_enu_m ? std::optional<double>((*row.p_enu_m)(i)) : std::nullopt, kLengthDecimals);
    }
    w.Add(TrackStatusName(row.status));
    w.Add(RangeStatusName(row.range_status));
    w.Add(deg(row.boresight_az_rad), kAngleDecimals);
    w.Add(deg(row.boresight_el_rad), kAngleDecimals);
    w.EndRow();
  }
  return w;
}

}  // namespace rk::locate
