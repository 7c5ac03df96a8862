// rk-locate: beacon track + turret log + camera model (+ range log) →
// azimuth, elevation, range and ENU position per frame (SPEC.md §1.1, §3).
// Thin CLI: the method lives in lib/locate (locate/locate.h).
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/wgs84.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "formats/beacon_track.h"
#include "formats/range_log.h"
#include "formats/turret_log.h"
#include "locate/locate.h"
#include "station_option.h"

namespace {

const char* const kTool = "rk-locate";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Locate the target: beacon track + turret log + camera model (+ range log) -> azimuth, elevation, "
      "range and "
      "station ENU position per frame (exact SPEC.md section 3 geometry with lens distortion).",
      kTool};
  rk::cli::CommonOptions common;
  rk::cli::AddCommonOptions(app, kTool, &common);
  std::string track_path, camera_path, turret_path, range_path, pointing_path, station_text, out_path;
  rk::locate::LocateOptions opt;
  app.add_option("--track", track_path,
                 "Beacon track CSV: frame,t_s,x_px,y_px[,status][,sigma_x_px,sigma_y_px] ('-' = stdin)")
      ->required();
  app.add_option("--camera", camera_path, "Camera model JSON (SPEC.md section 3)")->required();
  app.add_option("--turret", turret_path, "Turret log CSV: t_s,az_deg,el_deg (boresight)")->required();
  app.add_option("--range", range_path,
                 "Range log CSV: t_s,range_m[,status]; without it no range/ENU is given");
  app.add_option("--pointing", pointing_path,
                 "Turret pointing model JSON (SPEC.md section 3.1, rk-calibrate pointing); without it a perfect turret");
  app.add_option("--station", station_text,
                 "Station position LAT,LON,H (deg, deg, m WGS-84): adds lat_deg,lon_deg,h_m columns");
  app.add_option("-o,--output", out_path, "Located target CSV ('-' = stdout)")->required();
  rk::cli::AddOptions(&app, &opt, rk::locate::LocateOptions::Table());
  rk::io::BadRows bad_rows = rk::io::BadRows::kError;
  rk::cli::AddBadRowsOption(&app, &bad_rows);

  return rk::cli::Run(app, kTool, argc, argv, [&]() -> int {
    std::string why;
    if (!opt.Check(&why)) throw rk::UsageError(why);
    if (!station_text.empty()) {
      opt.station = rk::cli::ParseStationOption(station_text);
    }
    std::vector<std::string> inputs = {track_path, camera_path, turret_path};
    if (!range_path.empty()) inputs.push_back(range_path);
    if (!pointing_path.empty()) inputs.push_back(pointing_path);
    int n_stdin = 0;
    for (const auto& in : inputs) n_stdin += rk::io::IsStdStream(in) ? 1 : 0;
    if (n_stdin > 1) throw rk::UsageError("only one input can be read from stdin ('-')");
    rk::io::CheckOutputNotInput(out_path, inputs);
    if (!common.report_path.empty()) {
      rk::io::CheckOutputNotInput(common.report_path, inputs);
      if (rk::io::IsStdStream(common.report_path) && rk::io::IsStdStream(out_path)) {
        throw rk::UsageError("--report and -o cannot both be stdout");
      }
    }

    const rk::formats::Track track = rk::formats::ReadTrack(rk::io::CsvTable::Read(track_path, {bad_rows, rk::formats::TrackRowRule()}));
    const rk::camera::CameraModel camera = rk::camera::LoadCameraModel(camera_path);
    opt.camera_source = camera_path;
    if (!pointing_path.empty()) opt.pointing = rk::camera::LoadPointingModel(pointing_path);
    rk::formats::TurretLog turret = rk::formats::ReadTurretLog(rk::io::CsvTable::Read(turret_path, {bad_rows, rk::formats::TurretLogRowRule()}));
    const std::size_t turret_empty_samples = turret.empty_samples;
    std::optional<rk::formats::RangeLog> range;
    if (!range_path.empty()) range = rk::formats::ReadRangeLog(rk::io::CsvTable::Read(range_path, {bad_rows, rk::formats::RangeLogRowRule()}));

    const rk::locate::LocateResult result =
        rk::locate::Locate(track, camera, std::move(turret), range ? &*range : nullptr, opt);  // a long log: no copy
    if (result.rows_turret_not_covered > 0) {
      rk::cli::Warn(kTool, common,
                    std::to_string(result.rows_turret_not_covered) + " of " +
                        std::to_string(result.rows.size()) + " frame times are not covered by " +
                        turret_path + " (" + std::to_string(result.measured_rows_turret_not_covered) +
                        " measured rows written as invalid)");
    }
    if (range && result.rows_with_los > 0 && result.rows_with_range == 0) {
      rk::cli::Warn(kTool, common,
                    "no frame got a range from " + range_path + " (check its time span and status)");
    }
    rk::locate::LocatedCsv(result).Write(out_path);

    if (!common.report_path.empty()) {
      rk::io::Json report = rk::cli::MakeReport(kTool, argc, argv);
      rk::cli::AddReportInput(&report, "track", track_path);
      rk::cli::AddReportInput(&report, "camera", camera_path);
      rk::cli::AddReportInput(&report, "turret", turret_path);
      if (range) rk::cli::AddReportInput(&report, "range", range_path);
      if (opt.pointing) rk::cli::AddReportInput(&report, "pointing", pointing_path);
      report["output"] = out_path;
      report["options"] = opt.ToJson();
      if (opt.station) {
        report["station"] = {{"lat_deg", opt.station->lat_deg}, {"lon_deg", opt.station->lon_deg},
                             {"h_m", opt.station->h_m}};
      }
      if (camera.time_offset_s != 0.0) report["time_offset_s"] = camera.time_offset_s;
      rk::io::Json status = rk::io::Json::object();
      for (int s = 0; s < 5; ++s) {
        status[rk::RowStatusName(static_cast<rk::RowStatus>(s))] =
            result.rows_by_status[s];
      }
      rk::io::Json range_status = rk::io::Json::object();
      for (int s = 0; s < 5; ++s) {
        range_status[rk::locate::RangeStatusName(static_cast<rk::locate::RangeStatus>(s))] =
            result.rows_by_range_status[s];
      }
      const double coverage = result.RangeCoverage();
      report["counts"] = {{"rows", result.rows.size()},
                          {"status", status},
                          {"range_status", range_status},
                          {"rows_with_line_of_sight", result.rows_with_los},
                          {"rows_with_range", result.rows_with_range},
                          {"rows_turret_not_covered", result.rows_turret_not_covered},
                          {"measured_rows_turret_not_covered", result.measured_rows_turret_not_covered},
                          {"turret_duplicate_times", result.turret_duplicate_times},
                          {"turret_empty_samples", turret_empty_samples},
                          {"range_duplicate_times", result.range_duplicate_times},
                          {"range_device_errors", result.range_device_errors}};
      report["range_coverage"] = std::isfinite(coverage) ? rk::io::Json(coverage) : rk::io::Json(nullptr);
      report["summary"] = result.SummaryJson();
      rk::cli::WriteReport(common.report_path, report);
    }
    return 0;
  });
}
