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
#include "formats/image_points.h"
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
                 "Beacon track CSV: frame,t_s,x_px,y_px[,status][,sigma_x_px,sigma_y_px], or a points track "
                 "(rk-extract points: with an id column; one located series per id) ('-' = stdin)")
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
    rk::cli::CheckStreams(common,
                          {{"--track", track_path}, {"--camera", camera_path}, {"--turret", turret_path},
                           {"--range", range_path}, {"--pointing", pointing_path}},
                          {{"-o", out_path}});

    // A beacon track, or a points track (an id column): one located series per id.
    const rk::io::CsvTable track_table = rk::io::CsvTable::Read(track_path, {bad_rows, rk::formats::TrackRowRule()});
    std::vector<std::pair<std::string, rk::formats::Track>> tracks;
    if (track_table.HasColumn("id")) {
      tracks = rk::formats::TracksById(rk::formats::ReadImagePoints(track_table));
      if (tracks.empty()) throw rk::DataError(track_path, 0, 0, "the points track has no rows");
    } else {
      tracks.emplace_back("", rk::formats::ReadTrack(track_table));
    }
    const rk::camera::CameraModel camera = rk::camera::LoadCameraModel(camera_path);
    opt.camera_source = camera_path;
    if (!pointing_path.empty()) opt.pointing = rk::camera::LoadPointingModel(pointing_path);
    rk::formats::TurretLog turret = rk::formats::ReadTurretLog(rk::io::CsvTable::Read(turret_path, {bad_rows, rk::formats::TurretLogRowRule()}));
    const std::size_t turret_empty_samples = turret.empty_samples;
    std::optional<rk::formats::RangeLog> range;
    if (!range_path.empty()) range = rk::formats::ReadRangeLog(rk::io::CsvTable::Read(range_path, {bad_rows, rk::formats::RangeLogRowRule()}));

    rk::locate::LocateResult result;
    if (tracks.size() == 1 && tracks.front().first.empty()) {
      result = rk::locate::Locate(tracks.front().second, camera, std::move(turret), range ? &*range : nullptr,
                                  opt);  // a long log: no copy
    } else {
      std::vector<std::pair<std::string, rk::locate::LocateResult>> by_id;
      for (std::size_t i = 0; i < tracks.size(); ++i) {
        // The turret log is taken over by Locate: a copy for every id but the last.
        rk::formats::TurretLog log = i + 1 < tracks.size() ? turret : std::move(turret);
        by_id.emplace_back(tracks[i].first,
                           rk::locate::Locate(tracks[i].second, camera, std::move(log), range ? &*range : nullptr, opt));
      }
      result = rk::locate::MergeById(std::move(by_id));
    }
    const rk::io::RunSummary summary = rk::locate::LocateSummary(
        result, opt, {turret_path, range ? range_path : std::string(), turret_empty_samples});
    rk::cli::WarnAll(kTool, common, summary);
    rk::locate::LocatedCsv(result).Write(out_path);

    if (!common.report_path.empty()) {
      rk::io::Json report = rk::cli::MakeReport(kTool, argc, argv);
      rk::cli::AddReportInput(&report, "track", track_path);
      rk::cli::AddReportInput(&report, "camera", camera_path);
      rk::cli::AddReportInput(&report, "turret", turret_path);
      if (range) rk::cli::AddReportInput(&report, "range", range_path);
      if (opt.pointing) rk::cli::AddReportInput(&report, "pointing", pointing_path);
      report["output"] = out_path;
      rk::cli::WriteReport(common.report_path, report, summary);
    }
    return 0;
  });
}
