// rk-attitude oi: target position and attitude in the station frame from image points of known
// features (seed 001 §2.3, orthogonal iteration). Method: lib/pose/station_pose.h; user page
// docs/rk-attitude-oi.md.
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "attitude_commands.h"
#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/angles.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "track/boresight.h"
#include "formats/turret_log.h"
#include "pose/image_points.h"
#include "pose/station_pose.h"

namespace rk::app {
namespace {

struct OiArgs {
  std::string points, camera, target, turret, boresight, pointing, output;
  pose::AttitudeOiOptions opt;
  io::BadRows bad_rows = io::BadRows::kError;
};

geo::AzEl ParseBoresight(const std::string& text) {
  const std::vector<std::string> parts = io::SplitList(text);
  auto fail = [&]() -> geo::AzEl {
    throw UsageError("--boresight must be AZ,EL in degrees (e.g. 30,5), not '" + text + "'");
  };
  if (parts.size() != 2) return fail();
  double v[2];
  for (int k = 0; k < 2; ++k) {
    try {
      std::size_t used = 0;
      v[k] = std::stod(parts[static_cast<std::size_t>(k)], &used);
      if (used != parts[static_cast<std::size_t>(k)].size() || !std::isfinite(v[k])) return fail();
    } catch (const std::exception&) {
      return fail();
    }
  }
  if (v[1] < -90.0 || v[1] > 90.0) throw UsageError("--boresight elevation must be in [-90, 90] degrees");
  geo::AzEl b;
  b.az_rad = geo::WrapTwoPi(geo::DegToRad(v[0]));
  b.el_rad = geo::DegToRad(v[1]);
  return b;
}

int RunOi(const OiArgs& a, const Context& ctx) {
  pose::AttitudeOiOptions opt = a.opt;
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);

  cli::CheckStreams(ctx.common,
                    {{"--points", a.points}, {"--camera", a.camera}, {"--target", a.target},
                     {"--turret", a.turret}, {"--pointing", a.pointing}},
                    {{"-o", a.output}});
  std::optional<geo::AzEl> fixed;
  if (!a.boresight.empty()) fixed = ParseBoresight(a.boresight);

  const target::FeatureModel model = target::LoadFeatureModel(a.target);
  const camera::CameraModel camera = camera::LoadCameraModel(a.camera);
  if (!a.pointing.empty()) opt.pointing = camera::LoadPointingModel(a.pointing).terms;
  const pose::ImagePoints points =
      pose::ReadImagePoints(io::CsvTable::Read(a.points, {a.bad_rows, pose::ImagePointsRowRule()}), model);
  if (points.frames.empty()) throw DataError(points.source, 0, 0, "no image points (header only)");
  std::optional<formats::TurretLog> turret_log;
  if (!a.turret.empty()) turret_log = formats::ReadTurretLog(io::CsvTable::Read(a.turret, {a.bad_rows, formats::TurretLogRowRule()}));
  const track::BoresightSource boresight =
      fixed ? track::BoresightSource::Fixed(fixed->az_rad, fixed->el_rad)
            : track::BoresightSource::FromLog(std::move(*turret_log), opt.turret_method, opt.turret_max_gap_s);

  const pose::AttitudeOiResult res = pose::RunAttitudeOi(points, model, camera, boresight, opt);
  io::RunSummary summary = res.Summary(a.turret, fixed.has_value(), points.unusable_rows);
  if (points.ignored_rows > 0) {
    std::string ids;
    for (const std::string& id : points.ignored_ids) ids += (ids.empty() ? "" : ", ") + id;
    summary.Warn("ids_not_in_model", std::to_string(points.ignored_rows) + " rows of points the target model does not "
                                     "have (" + ids + ") are not used");
  }
  cli::WarnAll(ctx.tool, ctx.common, summary);
  pose::PoseCsv(res).Write(a.output);

  if (!ctx.common.report_path.empty()) {
    io::Json r = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    r["subcommand"] = "oi";
    cli::AddReportInput(&r, "points", a.points);
    cli::AddReportInput(&r, "camera", a.camera);
    cli::AddReportInput(&r, "target", a.target);
    if (!a.turret.empty()) cli::AddReportInput(&r, "turret", a.turret);
    if (!a.pointing.empty()) cli::AddReportInput(&r, "pointing", a.pointing);
    r["output"] = a.output;
    r["target"] = {{"points", model.size()}, {"planarity", model.Planarity()}};
    r["options"] = opt.ToJson();
    r["options"]["boresight"] =
        fixed ? io::Json{geo::RadToDeg(fixed->az_rad), geo::RadToDeg(fixed->el_rad)} : io::Json(nullptr);
    cli::WriteReport(ctx.common.report_path, r, summary);
  }
  return 0;
}

}  // namespace

Command AddOiCommand(CLI::App& parent) {
  auto a = std::make_shared<OiArgs>();
  CLI::App* s = parent.add_subcommand(
      "oi",
      "Target position and attitude (yaw, pitch, roll) in the station frame from image points of known "
      "features: orthogonal iteration (Lu, Hager & Mjolsness 2000) + reprojection polish, camera on the turret. "
      "Writes t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,status,reproj_rms_px,... (one row per frame).");
  s->add_option("--points", a->points, "Image points CSV: frame,t_s,id,x_px,y_px[,status][,sigma_px] ('-' = stdin)")
      ->required();
  s->add_option("--camera", a->camera, "Attitude camera model JSON (SPEC.md section 3, with mount_deg)")->required();
  s->add_option("--target", a->target, "Target model JSON {\"points\": {\"<id>\": [x, y, z], ...}} (body metres)")
      ->required();
  auto* o_turret = s->add_option("--turret", a->turret, "Turret log CSV t_s,az_deg,el_deg (the camera rides on the turret)");
  auto* o_bore = s->add_option("--boresight", a->boresight, "Fixed boresight AZ,EL (degrees) instead of a turret log");
  o_turret->excludes(o_bore);
  s->add_option("--pointing", a->pointing,
                "Turret pointing model JSON (SPEC.md section 3.1, rk-calibrate pointing); without it a perfect turret");
  cli::AddBadRowsOption(s, &a->bad_rows);
  s->add_option("-o,--output", a->output, "Pose CSV ('-' = stdout)")->required();
  cli::AddOptions(s, &a->opt, pose::AttitudeOiOptions::Table());
  return {s, [a, s](const Context& ctx) {
            if (a->turret.empty() && a->boresight.empty()) {
              throw UsageError("give the camera's pointing: --turret turret.csv or --boresight AZ,EL");
            }
            (void)s;
            return RunOi(*a, ctx);
          }};
}

}  // namespace rk::app
