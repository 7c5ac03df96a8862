// rk-calibrate pointing: image points of landmarks and stars + turret log + camera → pointing.json (SPEC.md
// §1.1, §3.1) and the updated camera. Thin edge: CLI11 options → rk::calibrate (lib/calibrate); docs in
// docs/rk-calibrate.md.
#include <cstdint>
#include <ctime>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/pointing_observations.h"
#include "calibrate/pointing_output.h"
#include "calibrate/pointing_solve.h"
#include "calibrate_commands.h"
#include "camera/camera_model.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "track/boresight.h"
#include "formats/turret_log.h"
#include "station_option.h"

namespace rk::app {
namespace {

struct PointingCli {
  calibrate::PointingCalibrationOptions o;
  std::string observations, turret, camera, landmarks, stars, epoch_utc, station, out, camera_out, plot;
  std::string estimate = "az_offset,tilt,el_axis_tilt,mount";
  io::BadRows bad_rows = io::BadRows::kError;
  CLI::Option* dut1 = nullptr;
};

constexpr const char* kDut1Warning =
    "--dut1 not given: UT1 - UTC taken as 0 s (up to 0.9 s = 13.5\" of star azimuth at the equator)";

std::string NowUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// The refusal of outputs that would overwrite an input or each other (cli::CheckStreams).
void CheckPaths(const PointingCli& c, const Context& ctx) {
  cli::CheckStreams(ctx.common,
                    {{"--observations", c.observations}, {"--turret", c.turret}, {"--camera", c.camera},
                     {"--landmarks", c.landmarks}, {"--stars", c.stars}},
                    {{"-o", c.out}, {"--camera-out", c.camera_out}, {"--plot", c.plot}});
}

calibrate::TargetCatalogue ReadTargets(const PointingCli& c) {
  calibrate::TargetCatalogue t;
  t.station = cli::ParseStationOption(c.station);
  if (!c.landmarks.empty()) {
    t.landmarks = target::ReadLandmarks(io::CsvTable::Read(c.landmarks, {c.bad_rows, {}}), t.station);
    t.landmarks_source = c.landmarks;
  }
  if (!c.stars.empty()) {
    t.stars = target::ReadStars(io::CsvTable::Read(c.stars, {c.bad_rows, {}}));
    t.stars_source = c.stars;
    t.epoch_utc = target::ParseUtc(c.epoch_utc, "--epoch-utc");
  }
  t.dut1_s = c.o.dut1_s;
  t.atmosphere = {c.o.pressure_hpa, c.o.temperature_c, c.o.humidity, c.o.wavelength_um};
  return t;
}

// The observations rows that are not a measurement (formats::ImagePoint::measured), left out of the fit.
std::string UnmeasuredWarning(const calibrate::ImagePoints& points) {
  return std::to_string(points.unmeasured_rows) + " rows of " + points.source +
         " have no measured position (status lost, invalid or predicted, or an empty pixel) and are left out";
}

void WriteReportFile(const PointingCli& c, const Context& ctx, const calibrate::PointingSolution& sol,
                     const camera::CameraModel& cam, const calibrate::ImagePoints& points) {
  io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
  r["subcommand"] = "pointing";
  cli::AddReportInput(&r, "observations", c.observations);
  cli::AddReportInput(&r, "turret", c.turret);
  cli::AddReportInput(&r, "camera", c.camera);
  if (!c.landmarks.empty()) cli::AddReportInput(&r, "landmarks", c.landmarks);
  if (!c.stars.empty()) cli::AddReportInput(&r, "stars", c.stars);
  r["output"] = c.out;
  if (!c.camera_out.empty()) r["camera_out"] = c.camera_out;
  if (!c.plot.empty()) r["plot"] = c.plot;
  io::Json opts = c.o.ToJson();
  opts["estimate"] = c.estimate;
  opts["station"] = c.station;
  if (!c.epoch_utc.empty()) opts["epoch_utc"] = c.epoch_utc;
  r["options"] = opts;
  io::RunSummary summary = calibrate::PointingRunSummary(sol, cam, c.out);
  if (!c.stars.empty() && c.dut1->count() == 0) summary.Flag("dut1_assumed_zero", kDut1Warning);  // said at the start
  if (points.unmeasured_rows > 0) summary.Flag("rows_not_measured", UnmeasuredWarning(points));  // said at reading
  r["observations_unmeasured"] = points.unmeasured_rows;
  cli::WriteReport(ctx.common.report_path, r, summary);
}

int RunPointing(const PointingCli& c, const Context& ctx) {
  std::string why;
  if (!c.o.Check(&why)) throw UsageError(why);
  const calibrate::EstimateSet est = calibrate::ParseEstimate(c.estimate);
  if (c.landmarks.empty() && c.stars.empty()) throw UsageError("give --landmarks, --stars or both");
  if (!c.stars.empty() && c.epoch_utc.empty()) throw UsageError("--stars needs --epoch-utc (the UTC of t_s = 0)");
  cli::ParseStationOption(c.station);
  if (!c.epoch_utc.empty()) target::ParseUtc(c.epoch_utc, "--epoch-utc");
  CheckPaths(c, ctx);
  if (!c.stars.empty() && c.dut1->count() == 0) {
    cli::Warn(ctx.tool, ctx.common, kDut1Warning);
  }

  const calibrate::ImagePoints points =
      calibrate::ReadImagePoints(io::CsvTable::Read(c.observations, {c.bad_rows, calibrate::ImagePointsRowRule()}));
  if (points.unmeasured_rows > 0) cli::Warn(ctx.tool, ctx.common, UnmeasuredWarning(points));
  formats::TurretLog log = formats::ReadTurretLog(io::CsvTable::Read(c.turret, {c.bad_rows, formats::TurretLogRowRule()}));
  const camera::CameraModel cam = camera::LoadCameraModel(c.camera);
  const calibrate::TargetCatalogue targets = ReadTargets(c);
  const track::BoresightSource turret =
      track::BoresightSource::FromLog(std::move(log), track::InterpMethod::kLinear, c.o.turret_max_gap_s);
  const auto build = [&](double tau) {
    return calibrate::BuildObservations(points, targets, turret, c.o.encoder_step_rad(), c.o.pixel_sigma_px, tau);
  };
  // Solves (outlier passes, τ re-evaluations): how many is known only at the end (total 0).
  const bool progress = cli::ShowProgress(ctx.common);
  cli::ProgressMeter meter(ctx.tool, "solves", 0, progress);
  const calibrate::PointingSolution sol =
      calibrate::SolvePointing(build, cam, est, c.o, [&](std::int64_t n) { meter.Update(n); });
  meter.Finish();
  cli::WarnAll(ctx.tool, ctx.common, calibrate::PointingRunSummary(sol, cam, c.out));
  // Everything is computed before the first file is written.
  const std::string pointing_text = calibrate::PointingFileJson(sol, points, cam, NowUtc()).dump(2) + "\n";
  const std::string camera_text = camera::CameraModelToJson(sol.Camera(cam)).dump(2) + "\n";
  const std::string plot_png = c.plot.empty() ? "" : calibrate::ResidualPlotPng(sol);
  io::WriteFileAtomic(c.out, pointing_text);
  if (!c.camera_out.empty()) io::WriteFileAtomic(c.camera_out, camera_text);
  if (!c.plot.empty()) io::WriteFileAtomic(c.plot, plot_png);
  if (!ctx.common.report_path.empty()) WriteReportFile(c, ctx, sol, cam, points);
  if (progress) {
    std::cerr << ctx.tool << ": " << sol.residuals.size() << " observations: " << sol.used << " used, " << sol.rejected
              << " rejected; RMS " << sol.rms_px << " px; " << sol.iterations << " solver iterations, "
              << sol.relinearisations << " time-offset re-evaluations\n";
  }
  return 0;
}

}  // namespace

Command AddPointingCommand(CLI::App& parent) {
  CLI::App* cmd = parent.add_subcommand(
      "pointing",
      "Turret pointing model (SPEC.md 3.1), camera mount, focal length and time offset from image points of "
      "landmarks and stars");
  auto a = std::make_shared<PointingCli>();
  PointingCli& c = *a;
  cmd->add_option("--observations", c.observations,
                  "Image points CSV: frame,t_s,id,x_px,y_px[,sigma_x_px,sigma_y_px] ('-' = stdin)")
      ->required();
  cmd->add_option("--turret", c.turret, "Turret log CSV: t_s,az_deg,el_deg (logged angles)")->required();
  cmd->add_option("--camera", c.camera, "Camera model JSON (SPEC.md section 3): the starting values")->required();
  cmd->add_option("--landmarks", c.landmarks, "Landmarks CSV: id,lat_deg,lon_deg,h_m or id,e_m,n_m,u_m [,sigma_m]");
  cmd->add_option("--stars", c.stars, "Stars CSV: id,ra_deg,dec_deg[,pm_ra_mas_yr,pm_dec_mas_yr,parallax_mas,rv_kms]");
  cmd->add_option("--epoch-utc", c.epoch_utc, "UTC of t_s = 0, ISO-8601 (needed with --stars)");
  cmd->add_option("--station", c.station, "Station WGS-84 position LAT,LON,H (deg, deg, m)")->required();
  cmd->add_option("-o,--output", c.out, "pointing.json to write ('-' = stdout)")->required();
  cmd->add_option("--camera-out", c.camera_out, "Camera model JSON to write with the estimated mount, focal, time offset");
  cmd->add_option("--estimate", c.estimate,
                  "Terms to estimate: az_offset,tilt,el_axis_tilt,mount,focal,time_offset")
      ->capture_default_str();
  cmd->add_option("--plot", c.plot, "Residual plot PNG to write (residuals against target azimuth and elevation)");
  cli::AddOptions(cmd, &c.o, calibrate::PointingCalibrationOptions::Table());
  c.dut1 = cmd->get_option("--dut1");
  cli::AddBadRowsOption(cmd, &c.bad_rows);
  return {cmd, [a](const Context& ctx) { return RunPointing(*a, ctx); }};
}

}  // namespace rk::app
