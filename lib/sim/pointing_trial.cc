#include "sim/pointing_trial.h"

#include <cmath>

#include "camera/pointing_model.h"
#include "formats/turret_log.h"
#include "geo/angles.h"
#include "geo/wgs84.h"
#include "io/csv.h"
#include "io/file_util.h"
#include "sim/sim_common.h"
#include "sim/trial_folder.h"
#include "trial/layout.h"
#include "trial/manifest.h"

namespace rk::sim {
namespace {

constexpr int kCatalogueDecimals = 10;  // degrees: 1e-10° = 0.4 µas

void WritePointingTargets(const PointingSession& s, const TrialFolder& dir) {
  io::CsvWriter lm({"id", "lat_deg", "lon_deg", "h_m", "e_m", "n_m", "u_m"});
  const geo::LocalEnu enu(s.station);
  for (const target::Landmark& l : s.landmarks) {
    const geo::Geodetic g = enu.ToGeodetic(l.p_enu);
    lm.Add(l.id).Add(g.lat_deg, kCatalogueDecimals).Add(g.lon_deg, kCatalogueDecimals);
    lm.Add(g.h_m, kMetreDecimals).Add(l.p_enu.x(), kMetreDecimals).Add(l.p_enu.y(), kMetreDecimals);
    lm.Add(l.p_enu.z(), kMetreDecimals).EndRow();
  }
  lm.Write(dir.Path("landmarks.csv"));
  io::CsvWriter st({"id", "ra_deg", "dec_deg", "pm_ra_mas_yr", "pm_dec_mas_yr", "parallax_mas", "rv_kms"});
  for (const target::Star& star : s.stars) {
    st.Add(star.id).Add(geo::RadToDeg(star.ra_rad), kCatalogueDecimals).Add(geo::RadToDeg(star.dec_rad), kCatalogueDecimals);
    st.Add(star.pm_ra_cosdec_mas_yr, 3).Add(star.pm_dec_mas_yr, 3).Add(star.parallax_mas, 3).Add(star.rv_kms, 3).EndRow();
  }
  st.Write(dir.Path("stars.csv"));
}

void WritePointingLogs(const PointingSession& s, const TrialFolder& dir) {
  io::CsvWriter turret(formats::TurretLogColumns());
  for (std::size_t k = 0; k < s.turret_t_s.size(); ++k) {
    turret.Add(s.turret_t_s[k], kTimeDecimals).Add(s.turret_az_deg[k], kAngleDecimals).Add(s.turret_el_deg[k], kAngleDecimals).EndRow();
  }
  turret.Write(dir.Path(trial::kTurretFile));
  io::CsvWriter pts({"frame", "t_s", "id", "x_px", "y_px"}), truth({"frame", "t_s", "id", "x_px", "y_px"});
  for (const PointingObservationRow& o : s.observations) {
    pts.Add(o.frame).Add(o.t_s, kTimeDecimals).Add(o.id).Add(o.px.x(), kPixelDecimals).Add(o.px.y(), kPixelDecimals).EndRow();
    truth.Add(o.frame).Add(o.t_s, kTimeDecimals).Add(o.id).Add(o.truth_px.x(), 6).Add(o.truth_px.y(), 6).EndRow();
  }
  pts.Write(dir.Path("points.csv"));
  truth.Write(dir.Path("truth/points.csv"));
}

// validation/: a tracked target for rk-locate --pointing (frames, beacon track, turret, truth).
void WriteValidation(const PointingSession& s, const TrialFolder& dir) {
  const ValidationTrack& v = s.validation;
  if (v.frame_t_s.empty()) return;
  dir.MakeSubfolder("validation");
  io::CsvWriter turret(formats::TurretLogColumns());
  for (std::size_t k = 0; k < v.turret_t_s.size(); ++k) {
    turret.Add(v.turret_t_s[k], kTimeDecimals).Add(v.turret_az_deg[k], kAngleDecimals).Add(v.turret_el_deg[k], kAngleDecimals).EndRow();
  }
  turret.Write(dir.Path("validation/turret.csv"));
  io::CsvWriter frames({"frame", "t_s"}), track({"frame", "t_s", "x_px", "y_px", "status"});
  io::CsvWriter truth({"t_s", "az_deg", "el_deg", "range_m", "e_m", "n_m", "u_m"});
  for (std::size_t k = 0; k < v.frame_t_s.size(); ++k) {
    const auto f = static_cast<std::int64_t>(k);
    frames.Add(f).Add(v.frame_t_s[k], kTimeDecimals).EndRow();
    track.Add(f).Add(v.frame_t_s[k], kTimeDecimals).Add(v.px[k].x(), kPixelDecimals).Add(v.px[k].y(), kPixelDecimals).Add("ok").EndRow();
    // Truth at the frame's true (mid-exposure) time, the camera's time offset later than its stamp, and
    // labelled with it: the time rk-locate gives the frame (SPEC.md §3.1: stamp + time_offset_s).
    const Eigen::Vector3d& p = v.p_enu[k];
    truth.Add(v.true_t_s[k], kTimeDecimals)
        .Add(geo::RadToDeg(geo::WrapTwoPi(std::atan2(p.x(), p.y()))), kAngleDecimals)
        .Add(geo::RadToDeg(std::atan2(p.z(), std::hypot(p.x(), p.y()))), kAngleDecimals)
        .Add(p.norm(), kMetreDecimals).Add(p.x(), kMetreDecimals).Add(p.y(), kMetreDecimals).Add(p.z(), kMetreDecimals)
        .EndRow();
  }
  frames.Write(dir.Path("validation/frames.csv"));
  track.Write(dir.Path("validation/track.csv"));
  truth.Write(dir.Path("validation/truth.csv"));
}

}  // namespace

io::Json PointingTrialSummary::ToJson() const {
  return {{"observations", observations}, {"frames", frames},         {"dwells", dwells},
          {"landmarks", landmarks},       {"stars", stars},           {"turret_rows", turret_rows},
          {"duration_s", duration_s}};
}

PointingTrialSummary WritePointingTrial(const PointingSimOptions& o, const PointingSession& s,
                                        const std::string& out_dir, bool force) {
  TrialFolder dir(out_dir, force);
  dir.MakeSubfolder("truth");
  WritePointingTargets(s, dir);
  WritePointingLogs(s, dir);
  WriteValidation(s, dir);
  io::WriteFileAtomic(dir.Path(trial::kCameraModelFile), camera::CameraModelToJson(s.camera_nominal).dump(2) + "\n");
  io::WriteFileAtomic(dir.Path("truth/camera.json"), camera::CameraModelToJson(s.camera_truth).dump(2) + "\n");
  camera::PointingModel truth;
  truth.terms = s.truth;
  io::WriteFileAtomic(dir.Path("truth/pointing.json"), camera::PointingModelToJson(truth).dump(2) + "\n");

  trial::Manifest m;
  m.name = dir.stem();
  m.epoch_utc = o.epoch_utc;
  m.Single().station = {{"lat_deg", o.lat_deg}, {"lon_deg", o.lon_deg}, {"h_m", o.h_m}};
  m.Single().turret = trial::kTurretFile;
  PointingTrialSummary sum;
  sum.observations = s.observations.size();
  sum.frames = s.frames;
  sum.dwells = s.dwells;
  sum.landmarks = s.landmarks.size();
  sum.stars = s.stars.size();
  sum.turret_rows = s.turret_t_s.size();
  sum.duration_s = s.duration_s;
  io::Json simj;
  simj["generator"] = "rk-sim pointing";
  simj["seed"] = o.seed;
  simj["options"] = o.ToJson();
  simj["calibration"] = {{"observations", "points.csv"}, {"landmarks", "landmarks.csv"}, {"stars", "stars.csv"},
                         {"camera", trial::kCameraModelFile}};
  simj["truth"] = {{"pointing", "truth/pointing.json"}, {"camera", "truth/camera.json"}, {"points", "truth/points.csv"}};
  if (!s.validation.frame_t_s.empty()) {
    simj["validation"] = {{"frames", "validation/frames.csv"}, {"track", "validation/track.csv"},
                          {"turret", "validation/turret.csv"}, {"truth", "validation/truth.csv"}};
  }
  simj["summary"] = sum.ToJson();
  m.extra["sim"] = simj;
  trial::WriteManifest(dir.Path(trial::kManifestFile), m);
  dir.Commit();
  return sum;
}

}  // namespace rk::sim
