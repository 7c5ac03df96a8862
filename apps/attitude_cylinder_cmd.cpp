// rk-attitude cylinder: single-station axis attitude of a cylindrical target from three silhouette points
// (seed 004, SPEC.md §1.1, §3). Thin CLI: the method lives in lib/attitude (attitude/cylinder_run.h), user
// page docs/rk-attitude-cylinder.md.
#include <memory>
#include <string>
#include <vector>

#include "attitude/cylinder_run.h"
#include "attitude_commands.h"
#include "camera/camera_model.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "locate/inputs.h"
#include "video/frame_source.h"

namespace rk::app {
namespace {

struct CylinderArgs {
  std::string points_path, theodolite_path, camera_path, target_path, out_path;
  std::vector<std::string> videos;
  std::string method = "p3p", theodolite_interp = "cubic";
  double max_edge_tilt_deg = 60.0;
  attitude::CylinderRunOptions opt;
  io::BadRows bad_rows = io::BadRows::kError;
};

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
  c->add_option("--target", a->target_path, "Target model JSON {\"length_m\", \"diameter_m\"} (length = nose to tail plane)")
      ->required();
  c->add_option("-o,--output", a->out_path, "Axis attitude CSV ('-' = stdout)")->required();
  c->add_option("--method", a->method, "Solver: p3p (closed form, Ferrari quartic) or search (the paper's R1 search)")
      ->check(CLI::IsMember({"p3p", "search"}))
      ->capture_default_str();
  c->add_option("--theodolite-interp", a->theodolite_interp, "Theodolite interpolation: linear or cubic")
      ->check(CLI::IsMember({"linear", "cubic"}))
      ->capture_default_str();
  c->add_option("--theodolite-max-gap", a->opt.theodolite_max_gap_s,
                "Longest theodolite-log interval (s) interpolated across; frames in longer gaps are invalid")
      ->capture_default_str();
  c->add_option("--continuity-gap", a->opt.continuity_gap_s,
                "History older than this (s) is not used to choose between the two solutions")
      ->capture_default_str();
  c->add_option("--ambiguity-deg", a->opt.ambiguity_deg,
                "Solutions (or their distances to the predicted axis) closer than this are not told apart (deg)")
      ->capture_default_str();
  c->add_option("--max-asymmetry-px", a->opt.max_asymmetry_px,
                "Largest difference of the nose's distances to tail1 and tail2 (px; at least a quarter of the tail diameter's image) before a frame is inconsistent")
      ->capture_default_str();
  c->add_option("--max-miss-px", a->opt.max_miss_px,
                "Where noise removes the exact solutions, accept the closest approach if it misses by at most this (px); 0 = never")
      ->capture_default_str();
  c->add_option("--max-edge-tilt-deg", a->max_edge_tilt_deg,
                "Solutions tilting the tail diameter further out of the image plane are not admissible (deg)")
      ->capture_default_str();
  c->add_option("--video", a->videos,
                "The frames the points came from (file or image-sequence pattern; repeat for segments): each "
                "solution is then refined by fitting the projected target to its frame (image fit; needs the "
                "points file's frame column)");
  c->add_option("--fit-psf-sigma", a->opt.image_fit.initial_psf_sigma_px,
                "Image fit: starting value of the optics blur sigma (px; fitted)")
      ->capture_default_str();
  c->add_option("--fit-max-iterations", a->opt.image_fit.max_iterations, "Image fit: Levenberg-Marquardt iteration limit")
      ->capture_default_str();
  c->add_option("--pixel-sigma", a->opt.pixel_sigma_px, "Point error assumed for the sigma columns (px, each coordinate)")
      ->capture_default_str();
  c->add_option("--angle-sigma-arcsec", a->opt.angle_sigma_arcsec,
                "Theodolite angle error assumed for the sigma columns (arcsec, each axis)")
      ->capture_default_str();

  return {c, [a](const Context& ctx) -> int {
            attitude::CylinderRunOptions opt = a->opt;
            if (!attitude::ParseCylinderMethod(a->method, &opt.solve.method)) throw UsageError("unknown --method " + a->method);
            if (!track::ParseInterpMethod(a->theodolite_interp, &opt.theodolite_method))
              throw UsageError("unknown --theodolite-interp " + a->theodolite_interp);
            opt.solve.max_edge_tilt_rad = geo::DegToRad(a->max_edge_tilt_deg);
            std::string why;
            if (!opt.Check(&why)) throw UsageError(why);
            std::vector<std::string> inputs = {a->points_path, a->theodolite_path, a->camera_path, a->target_path};
            inputs.insert(inputs.end(), a->videos.begin(), a->videos.end());
            int stdin_inputs = 0;
            for (const std::string& p : inputs) stdin_inputs += io::IsStdStream(p) ? 1 : 0;
            if (stdin_inputs > 1) throw UsageError("only one input can be read from stdin ('-')");
            io::CheckOutputNotInput(a->out_path, inputs);
            if (!ctx.common.report_path.empty()) io::CheckOutputNotInput(ctx.common.report_path, inputs);
            if (!ctx.common.report_path.empty() && ctx.common.report_path == a->out_path && !io::IsStdStream(a->out_path))
              throw UsageError("--report and -o name the same file " + a->out_path);

            const camera::CameraModel cam = camera::LoadCameraModel(a->camera_path);
            const target::CylinderShape target = target::LoadCylinderShape(a->target_path);
            const attitude::CylinderPointsFile points = attitude::ReadCylinderPoints(
                io::CsvTable::Read(a->points_path, {a->bad_rows, attitude::CylinderPointsRowRule()}));
            const locate::TurretLog theo = locate::ReadTurretLog(io::CsvTable::Read(a->theodolite_path, {a->bad_rows, locate::TurretLogRowRule()}));
            // Frames for the image fit, read forward in decode order (rows come in frame order).
            std::unique_ptr<video::FrameSource> source;
            cv::Mat image;
            std::int64_t next_frame = 0;
            const std::string video_name = a->videos.empty() ? "" : a->videos.front();
            const attitude::CylinderFrameReader reader = [&](std::int64_t frame) -> const cv::Mat& {
              if (frame < next_frame - 1 || frame < 0)
                throw DataError(a->points_path, 0, 0,
                                "frame " + std::to_string(frame) + " comes after a later frame; the image fit reads " +
                                    video_name + " forward only");
              while (next_frame <= frame) {
                if (!source->Read(&image))
                  throw DataError(video_name, 0, 0,
                                "the video ends after " + std::to_string(next_frame) + " frames but " + a->points_path +
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
            if (!a->videos.empty()) source = std::make_unique<video::FrameSource>(a->videos);
            const attitude::CylinderRunResult res =
                attitude::RunCylinder(points, theo, cam, target, opt, a->videos.empty() ? nullptr : &reader);
            attitude::CylinderCsv(res).Write(a->out_path);

            using S = attitude::CylinderSolutionStatus;
            const auto n = [&](S s) { return res.rows_by_solution[static_cast<std::size_t>(s)]; };
            if (n(S::kAmbiguous) > 0) {
              cli::Warn(
                  ctx.tool, ctx.common,
                  std::to_string(n(S::kAmbiguous)) +
                      " frame(s) ambiguous: two solutions that no history separates; primary = nose-nearer "
                      "(SPEC.md 3), the other in alt_yaw_deg/alt_pitch_deg");
            }
            const std::size_t invalid = res.rows_by_status[static_cast<std::size_t>(RowStatus::kInvalid)];
            if (invalid > 0) {
              cli::Warn(ctx.tool, ctx.common,
                        std::to_string(invalid) + " frame(s) invalid (no_theodolite " +
                            std::to_string(n(S::kNoTheodolite)) + ", outside_image " +
                            std::to_string(n(S::kOutsideImage)) + ", inconsistent " +
                            std::to_string(n(S::kInconsistent)) + ", degenerate " +
                            std::to_string(n(S::kDegenerate)) + ", no_solution " +
                            std::to_string(n(S::kNoSolution)) + ")");
            }
            if (!ctx.common.report_path.empty()) {
              io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
              cli::AddReportInput(&rep, "points", a->points_path);
              cli::AddReportInput(&rep, "theodolite", a->theodolite_path);
              cli::AddReportInput(&rep, "camera", a->camera_path);
              cli::AddReportInput(&rep, "target", a->target_path);
              rep["subcommand"] = "cylinder";
              rep["output"] = a->out_path;
              rep["target"] = {{"length_m", target.length_m}, {"diameter_m", target.diameter_m}};
              rep["options"] = {{"method", a->method},
                                {"theodolite_interp", a->theodolite_interp},
                                {"theodolite_max_gap_s", opt.theodolite_max_gap_s},
                                {"continuity_gap_s", opt.continuity_gap_s},
                                {"ambiguity_deg", opt.ambiguity_deg},
                                {"max_asymmetry_px", opt.max_asymmetry_px},
                                {"max_miss_px", opt.max_miss_px},
                                {"max_edge_tilt_deg", a->max_edge_tilt_deg},
                                {"pixel_sigma_px", opt.pixel_sigma_px},
                                {"angle_sigma_arcsec", opt.angle_sigma_arcsec},
                                {"fit_psf_sigma_px", opt.image_fit.initial_psf_sigma_px},
                                {"fit_max_iterations", opt.image_fit.max_iterations}};
              for (std::size_t i = 0; i < a->videos.size(); ++i)
                cli::AddReportInput(&rep, "video_" + std::to_string(i), a->videos[i]);
              rep["summary"] = res.SummaryJson();
              cli::WriteReport(ctx.common.report_path, rep);
            }
            return 0;
          }};
}

}  // namespace rk::app
