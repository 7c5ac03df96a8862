// Theodolite trial writer; file layout in theodolite_trial.h.
#include "sim/theodolite_trial.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "camera/camera_model.h"
#include "formats/turret_log.h"
#include "geo/angles.h"
#include "io/utc_time.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "sim/trial_folder.h"
#include "trial/layout.h"
#include "trial/manifest.h"
#include "video/frame_sink.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace {

constexpr int kSilhouettePixelDecimals = 6;
constexpr const char* kTheodoliteCamera = "theo";  // the camera's name in the manifest and its folder

std::mt19937_64 FrameStream(std::uint64_t seed, std::int64_t k) {
  std::seed_seq seq{seed, static_cast<std::uint64_t>(1000), static_cast<std::uint64_t>(k)};
  return std::mt19937_64(seq);
}

}  // namespace

const io::OptionTable<TheodoliteWriteOptions>& TheodoliteWriteOptions::Table() {
  static const io::OptionTable<TheodoliteWriteOptions> table =
      io::OptionTable<TheodoliteWriteOptions>()
          .Flag("--force", &TheodoliteWriteOptions::force, "Replace an existing non-empty --out folder")
          .Choice("--images", &TheodoliteWriteOptions::images, {{"none", "none"}, {"png", "png"}, {"mkv", "mkv"}},
                  "Rendered frames: none, png (theo/%06d.png) or mkv (theo/video.mkv, FFV1)");
  return table;
}

bool TheodoliteWriteOptions::Check(std::string* why) const {
  if (out_dir.empty() || out_dir == "-") {
    *why = "--out must name a folder";
    return false;
  }
  if (images != "none" && images != "png" && images != "mkv") {
    *why = "--images must be none, png or mkv";
    return false;
  }
  io::UtcTime utc_epoch;
  if (!io::ParseUtcIso(epoch_utc, &utc_epoch, nullptr)) {
    *why = "epoch must be ISO-8601 UTC, e.g. 2026-01-01T00:00:00Z";
    return false;
  }
  return render.Check(why);
}

io::Json TheodoliteTrialSummary::ToJson() const {
  return {{"frames", frames},
          {"theodolite_rows", theodolite_rows},
          {"view_angle_deg", {min_view_angle_deg, max_view_angle_deg}},
          {"image_length_px", {min_image_length_px, max_image_length_px}},
          {"angle_bias_arcsec", {{"az", bias_az_arcsec}, {"el", bias_el_arcsec}}}};
}

TheodoliteTrialSummary WriteTheodoliteTrial(const TheodoliteSimulator& sim, const TheodoliteWriteOptions& opt) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  const TheodoliteSimOptions& so = sim.options();
  TrialFolder dir(opt.out_dir, opt.force);
  io::MakeDirectories(dir.Path(kTheodoliteCamera));
  io::MakeDirectories(dir.Path("truth"));
  using geo::RadToDeg;

  TheodoliteTrialSummary sum;
  sum.min_view_angle_deg = sum.min_image_length_px = std::numeric_limits<double>::infinity();
  sum.max_view_angle_deg = sum.max_image_length_px = -std::numeric_limits<double>::infinity();
  sum.bias_az_arcsec = sim.bias_az_rad() * geo::kArcsecPerRad;
  sum.bias_el_arcsec = sim.bias_el_rad() * geo::kArcsecPerRad;

  io::WriteJson(dir.Path(trial::CameraFile(kTheodoliteCamera, trial::kCameraModelFile)),
                camera::CameraModelToJson(so.camera));
  io::WriteJson(dir.Path(trial::kTargetModelFile), {{"length_m", so.shape.length_m},
                                                    {"diameter_m", so.shape.diameter_m},
                                                    {"nose_length_m", so.shape.nose_length_m}});
  io::CsvWriter frames_csv({"frame", "t_s"});
  io::CsvWriter points_csv({"frame", "t_s", "id", "x_px", "y_px"});
  io::CsvWriter truth_points({"frame", "t_s", "id", "x_px", "y_px"});
  io::CsvWriter axis_csv({"frame", "t_s", "yaw_deg", "pitch_deg", "alt_yaw_deg", "alt_pitch_deg", "range_nose_m",
                          "range_tail1_m", "range_tail2_m", "e_m", "n_m", "u_m", "view_angle_deg", "image_length_px",
                          "boresight_az_deg", "boresight_el_deg"});
  const char* ids[3] = {"nose", "tail1", "tail2"};
  for (const TheodoliteFrameTruth& f : sim.frames()) {
    frames_csv.Add(f.frame).Add(f.t_s, kTimeDecimals).EndRow();
    const Eigen::Vector2d* exact[3] = {&f.nose_px, &f.tail1_px, &f.tail2_px};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d& m = f.measured_px[static_cast<std::size_t>(i)];
      points_csv.Add(f.frame).Add(f.t_s, kTimeDecimals).Add(ids[i]);
      points_csv.Add(m.x(), so.quantise ? 0 : kSilhouettePixelDecimals).Add(m.y(), so.quantise ? 0 : kSilhouettePixelDecimals).EndRow();
      truth_points.Add(f.frame).Add(f.t_s, kTimeDecimals).Add(ids[i]);
      truth_points.Add(exact[i]->x(), kSilhouettePixelDecimals).Add(exact[i]->y(), kSilhouettePixelDecimals).EndRow();
    }
    axis_csv.Add(f.frame).Add(f.t_s, kTimeDecimals);
    axis_csv.Add(RadToDeg(f.pose.yaw_rad), kAngleDecimals).Add(RadToDeg(f.pose.pitch_rad), kAngleDecimals);
    axis_csv.Add(f.alt_yaw_rad ? std::optional<double>(RadToDeg(*f.alt_yaw_rad)) : std::nullopt, kAngleDecimals);
    axis_csv.Add(f.alt_pitch_rad ? std::optional<double>(RadToDeg(*f.alt_pitch_rad)) : std::nullopt, kAngleDecimals);
    axis_csv.Add(f.points.nose.norm(), kMetreDecimals)
        .Add(f.points.tail1.norm(), kMetreDecimals)
        .Add(f.points.tail2.norm(), kMetreDecimals);
    for (int i = 0; i < 3; ++i) axis_csv.Add(f.points.tail_centre(i), kMetreDecimals);
    axis_csv.Add(RadToDeg(f.view_angle_rad), 6).Add(f.image_length_px, 4);
    axis_csv.Add(RadToDeg(f.boresight_az_rad), kAngleDecimals).Add(RadToDeg(f.boresight_el_rad), kAngleDecimals);
    axis_csv.EndRow();
    ++sum.frames;
    sum.min_view_angle_deg = std::min(sum.min_view_angle_deg, RadToDeg(f.view_angle_rad));
    sum.max_view_angle_deg = std::max(sum.max_view_angle_deg, RadToDeg(f.view_angle_rad));
    sum.min_image_length_px = std::min(sum.min_image_length_px, f.image_length_px);
    sum.max_image_length_px = std::max(sum.max_image_length_px, f.image_length_px);
  }
  frames_csv.Write(dir.Path(trial::CameraFile(kTheodoliteCamera, trial::kFramesFile)));
  points_csv.Write(dir.Path("points.csv"));
  truth_points.Write(dir.Path("truth/points.csv"));
  axis_csv.Write(dir.Path("truth/axis.csv"));

  io::CsvWriter theo_csv(formats::TurretLogColumns()), theo_truth(formats::TurretLogColumns());
  for (const TheodoliteSample& s : sim.TheodoliteLog()) {
    theo_csv.Add(s.t_s, kTimeDecimals).Add(RadToDeg(s.az_rad), kAngleDecimals).Add(RadToDeg(s.el_rad), kAngleDecimals).EndRow();
    theo_truth.Add(s.t_s, kTimeDecimals)
        .Add(RadToDeg(s.true_az_rad), kAngleDecimals)
        .Add(RadToDeg(s.true_el_rad), kAngleDecimals)
        .EndRow();
    ++sum.theodolite_rows;
  }
  theo_csv.Write(dir.Path(trial::kTheodoliteFile));
  theo_truth.Write(dir.Path("truth/theodolite.csv"));

  trial::Manifest m;
  m.name = opt.name.empty() ? dir.stem() : opt.name;
  m.epoch_utc = opt.epoch_utc;
  m.Single().station = {{"lat_deg", 0.0}, {"lon_deg", 0.0}, {"h_m", 0.0}};
  // Without images there is nothing for rk-extract to read: the camera is left out of the manifest
  // (SPEC.md §6 wants a non-empty video list); rk-attitude cylinder can still run on points.csv.
  if (opt.images != "none") {
    const std::string video_rel = trial::CameraFile(kTheodoliteCamera, opt.images == "mkv" ? "video.mkv" : "%06d.png");
    trial::CameraEntry theo = trial::CameraInItsFolder(kTheodoliteCamera, trial::CameraRole::kSilhouette, {video_rel});
    theo.target = trial::kTargetModelFile;
    m.Single().cameras = {theo};
    video::FrameSink sink(dir.Path(video_rel), so.camera.width_px, so.camera.height_px, opt.render.sensor.bit_depth,
                          so.fps);
    for (std::size_t k = 0; k < sim.frames().size(); ++k) {
      std::mt19937_64 rng = FrameStream(so.seed, static_cast<std::int64_t>(k));
      sink.Write(RenderSilhouetteFrame(so.camera, sim.frames()[k], so.shape, opt.render, rng));
      if (opt.progress) opt.progress(k + 1, sim.frames().size());
    }
    sink.Close();
  }

  m.Single().theodolite = trial::kTheodoliteFile;
  io::Json simj;
  simj["generator"] = "rk-sim theodolite";
  simj["seed"] = so.seed;
  simj["images"] = opt.images;
  simj["options"] = TheodoliteSimOptionsToJson(so);
  simj["render"] = {{"sky_dn", opt.render.sky_dn},
                    {"sky_gradient_dn", opt.render.sky_gradient_dn},
                    {"body_dn", opt.render.body_dn},
                    {"shading_dn", opt.render.shading_dn},
                    {"psf_sigma_px", opt.render.psf_sigma_px},
                    {"read_noise_dn", opt.render.sensor.read_noise_dn},
                    {"gain_e_per_dn", opt.render.sensor.gain_e_per_dn},
                    {"bit_depth", opt.render.sensor.bit_depth}};
  simj["points"] = "points.csv";
  simj["truth"] = {{"axis", "truth/axis.csv"}, {"points", "truth/points.csv"}, {"theodolite", "truth/theodolite.csv"}};
  simj["summary"] = sum.ToJson();
  m.extra["sim"] = simj;
  trial::WriteManifest(dir.Path(trial::kManifestFile), m);
  dir.Commit();
  return sum;
}

}  // namespace rk::sim
