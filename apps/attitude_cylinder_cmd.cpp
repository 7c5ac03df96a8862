// rk-attitude cylinder: single-station axis attitude of a cylindrical target from three silhouette points
// (seed 004, SPEC.md §1.1, §3). Thin CLI: the method lives in lib/attitude (attitude/cylinder_run.h), user
// page docs/rk-attitude-cylinder.md.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "attitude/cylinder_run.h"
#include "attitude_commands.h"
#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "formats/turret_log.h"
#include "video/frame_source.h"
#include "video/stdin_video.h"

namespace rk::app {
namespace {

struct CylinderArgs {
  std::string points_path, theodolite_path, camera_path, target_path, pointing_path, out_path;
  std::vector<std::string> videos;
  attitude::CylinderRunOptions opt;
  io::BadRows bad_rows = io::BadRows::kError;
};

int RunCylinderCmd(const CylinderArgs& a, const Context& ctx) {
  attitude::CylinderRunOptions opt = a.opt;
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  video::RefuseStdinVideo(a.videos);
  std::vector<cli::NamedPath> inputs = {{"--points", a.points_path}, {"--theodolite", a.theodolite_path},
                                         {"--camera", a.camera_path}, {"--target", a.target_path},
                                         {"--pointing", a.pointing_path}};
  for (const std::string& v : a.videos) inputs.push_back({"--video", v});
  cli::CheckStreams(ctx.common, inputs, {{"-o", a.out_path}});

  const camera::CameraModel cam = camera::LoadCameraModel(a.camera_path);
  if (!a.pointing_path.empty()) opt.pointing = camera::LoadPointingModel(a.pointing_path).terms;
  const target::CylinderShape target = target::LoadCylinderShape(a.target_path);
  const attitude::CylinderPointsFile points = attitude::ReadCylinderPoints(
      io::CsvTable::Read(a.points_path, {a.bad_rows, attitude::CylinderPointsRowRule()}));
  formats::TurretLog theo = formats::ReadTurretLog(io::CsvTable::Read(a.theodolite_path, {a.bad_rows, formats::TurretLogRowRule()}));
  // Frames for the image fit, read forward in decode order (rows come in frame order).
  std::unique_ptr<video::FrameSource> source;
  cv::Mat image;
  std::int64_t next_frame = 0;
  const std::string video_name = a.videos.empty() ? "" : a.videos.front();
  // The image fit's progress on a terminal: one frame read per row fitted.
  cli::ProgressMeter meter(ctx.tool, "frames fitted", static_cast<std::int64_t>(points.frames.size()),
                           cli::ShowProgress(ctx.common));
  std::int64_t frames_asked = 0;
  const attitude::CylinderFrameReader reader = [&](std::int64_t frame) -> const cv::Mat& {
    meter.Update(++frames_asked);
    if (frame < next_frame - 1 || frame < 0)
      throw DataError(a.points_path, 0, 0,
                      "frame " + std::to_string(frame) + " comes after a later frame; the image fit reads " +
                          video_name + " forward only");
    while (next_frame <= frame) {
      if (!source->Read(&image))
        throw DataError(video_name, 0, 0,
                      "the video ends after " + std::to_string(next_frame) + " frames but " + a.points_path +
                          " refers to frame " + std::to_string(frame));
      ++next_frame;
    }
    if (image.cols != cam.width_px || image.rows != cam.height_px)
      throw DataError(video_name, 0, 0,
                      "frames are " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                          " px but the camera model is " + std::to_string(cam.width_px) + "x" +
                          std::to_string(cam.height_px));
    return image;
  };
  if (!a.videos.empty()) source = std::make_unique<video::FrameSource>(a.videos);
  const attitude::CylinderRunResult res =
      attitude::RunCylinder(points, std::move(theo), cam, target, opt, a.videos.empty() ? nullptr : &reader);
  meter.Finish();
  attitude::CylinderCsv(res).Write(a.out_path);

  const io::RunSummary summary = res.Summary();
  cli::WarnAll(ctx.tool, ctx.common, summary);
  if (!ctx.common.report_path.empty()) {
    io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&rep, "points", a.points_path);
    cli::AddReportInput(&rep, "theodolite", a.theodolite_path);
    cli::AddReportInput(&rep, "camera", a.camera_path);
    cli::AddReportInput(&rep, "target", a.target_path);
    if (!a.pointing_path.empty()) cli::AddReportInput(&rep, "pointing", a.pointing_path);
    rep["subcommand"] = "cylinder";
    rep["output"] = a.out_path;
    rep["target"] = {{"length_m", target.length_m}, {"diameter_m", target.diameter_m}};
    rep["options"] = opt.ToJson();
    for (std::size_t i = 0; i < a.videos.size(); ++i)
      cli::AddReportInput(&rep, "video_" + std::to_string(i), a.videos[i]);
    cli::WriteReport(ctx.common.report_path, rep, summary);
  }
  if (cli::ShowProgress(ctx.common)) {
    std::cerr << ctx.tool << ": " << points.frames.size() << " frames: "
              << res.rows_by_status[static_cast<std::size_t>(RowStatus::kOk)] << " ok, "
              << res.rows_by_status[static_cast<std::size_t>(RowStatus::kInvalid)] << " invalid, "
              << res.rows_by_solution[static_cast<std::size_t>(attitude::CylinderSolutionStatus::kAmbiguous)]
              << " ambiguous\n";
  }
  return 0;
}

}  // namespace

Command AddCylinderCommand(CLI::App& parent) {
  auto a = std::make_shared<CylinderArgs>();
  CLI::App* c = parent.add_subcommand(
      "cylinder",
      "Axis attitude (yaw, pitch) of a cylindrical target from its nose and tail-rim silhouette points, one "
      "theodolite (seed 004): isosceles P3P by closed form or the paper's R1 search, SPEC.md 3 lines of "
      "sight, both solutions reported, the primary continuous with the previous rows. Writes t_s,yaw_deg,"
      "pitch_deg,status,alt_yaw_deg,alt_pitch_deg,solution,ranges,sigma and quality columns, one row per frame.");
  c->add_option("--points", a->points_path, "Image points CSV frame,t_s,id,x_px,y_px with ids nose, tail1, tail2 ('-' = stdin)")
      ->required();
  c->add_option("--theodolite", a->theodolite_path, "Theodolite log CSV t_s,az_deg,el_deg (boresight)")->required();
  cli::AddBadRowsOption(c, &a->bad_rows);
  c->add_option("--camera", a->camera_path, "Camera model JSON (SPEC.md 3)")->required();
  c->add_option("--pointing", a->pointing_path,
                "Theodolite/turret pointing model JSON (SPEC.md 3.1, rk-calibrate pointing); without it a perfect "
                "instrument");
  c->add_option("--target", a->target_path, "Target model JSON {\"length_m\", \"diameter_m\"} (length = nose to tail plane)")
      ->required();
  c->add_option("-o,--output", a->out_path, "Axis attitude CSV ('-' = stdout)")->required();
  c->add_option("--video", a->videos,
                "The frames the points came from (file or image-sequence pattern; repeat for segments): each "
                "solution is then refined by fitting the projected target to its frame (image fit; needs the "
                "points file's frame column). Not '-': a video is not read from stdin");
  cli::AddOptions(c, &a->opt, attitude::CylinderRunOptions::Table());

  return {c, [a](const Context& ctx) { return RunCylinderCmd(*a, ctx); }};
}

}  // namespace rk::app
