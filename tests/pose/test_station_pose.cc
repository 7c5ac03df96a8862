// rk-attitude oi pipeline: station-frame chain checked by hand, angle wraps, turret
// interpolation, per-row statuses, bad input, and the honesty of the sigma columns.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "geo/angles.h"
#include "geo/body_attitude.h"
#include "io/csv.h"
#include "io/error.h"
#include "track/boresight.h"
#include "pose/image_points.h"
#include "pose/station_pose.h"
#include "target/feature_model.h"

namespace rk::pose {
namespace {

using geo::DegToRad;
using geo::RadToDeg;

constexpr double kHand = 1e-9;  // hand-computed trigonometry, double precision

camera::CameraModel AttitudeCamera() {
  camera::CameraModel c;
  c.focal_length_mm = 100.0;  // seed 001's attitude camera
  return c;
}

// A non-planar 8-marker target about 0.7 m across (the rk-sim attitude layout's scale).
target::FeatureModel Model() {
  io::Json j = {{"points",
                 {{"nose", {0.40, 0.0, 0.02}},
                  {"tail", {-0.35, 0.0, -0.05}},
                  {"fin", {-0.30, 0.02, -0.25}},
                  {"lwing", {-0.02, -0.36, 0.0}},
                  {"rwing", {-0.08, 0.30, 0.01}},
                  {"belly", {0.12, 0.03, 0.12}},
                  {"ltail", {-0.30, -0.15, 0.0}},
                  {"canopy", {0.22, -0.02, -0.08}}}}};
  return target::FeatureModelFromJson(j, "target.json");
}

struct Truth {
  double t_s;
  Eigen::Vector3d p_enu;
  geo::EulerZyx att;
  geo::AzEl boresight;
};

// Pixels of every model point for a station-frame truth (exact camera model incl. mount and
// distortion), as an image-points CSV text.
std::string PointsCsv(const std::vector<Truth>& truth, const camera::CameraModel& cam,
                      const target::FeatureModel& model, double noise_px, std::uint64_t seed,
                      const std::vector<std::pair<int, std::string>>& drop = {}) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, noise_px);
  std::string s = "frame,t_s,id,x_px,y_px,status\n";
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Truth& tr = truth[k];
    const Eigen::Matrix3d R_enu_body = geo::RotationEnuFromBody(tr.att);
    for (std::size_t i = 0; i < model.size(); ++i) {
      bool dropped = false;
      for (const auto& d : drop) dropped |= d.first == static_cast<int>(k) && d.second == model.ids[i];
      s += std::to_string(k) + "," + std::to_string(tr.t_s) + "," + model.ids[i] + ",";
      if (dropped) {
        s += ",,lost\n";
        continue;
      }
      const Eigen::Vector3d p = tr.p_enu + R_enu_body * model.p_body[i];
      const auto uv = cam.ProjectEnu(p, tr.boresight.az_rad, tr.boresight.el_rad);
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.6f,%.6f,ok\n", uv->x() + g(rng), uv->y() + g(rng));
      s += buf;
    }
  }
  return s;
}

TEST(StationPose, HandCheckedChainBoresightEastLevel) {
  // Boresight east (A = 90°), level: r = (0, −1, 0) south, d = (0, 0, −1) down, b = (1, 0, 0).
  // Body on the axis 20 m out, nose away from the station (east), right wing = south = image
  // right, body down = image down: R_cam_body columns = body axes in the camera frame:
  // x_body → cam z, y_body → cam x, z_body → cam y. Expected yaw 90°, pitch 0, roll 0.
  camera::CameraModel cam = AttitudeCamera();
  Eigen::Matrix3d R_cam_body;
  R_cam_body << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  Eigen::Vector3d p_enu;
  Eigen::Matrix3d R_enu_body;
  StationPose(cam, {DegToRad(90.0), 0.0}, R_cam_body, Eigen::Vector3d(0, 0, 20), &p_enu, &R_enu_body);
  EXPECT_LT((p_enu - Eigen::Vector3d(20, 0, 0)).norm(), kHand);
  const geo::EulerZyx e = geo::EulerFromRotationEnuBody(R_enu_body);
  EXPECT_NEAR(RadToDeg(e.yaw_rad), 90.0, kHand);
  EXPECT_NEAR(RadToDeg(e.pitch_rad), 0.0, kHand);
  EXPECT_NEAR(RadToDeg(e.roll_rad), 0.0, kHand);
}

TEST(StationPose, HandCheckedChainBoresightNorthUp30) {
  // Boresight north at 30° elevation: b = (0, cos30, sin30), r = (1, 0, 0) east,
  // d = (0, sin30, −cos30). Same R_cam_body (nose along the boresight, right wing to image
  // right): the body points north, nose up 30°, wings level → yaw 0, pitch 30, roll 0; the
  // body origin at 20 m is (0, 17.3205…, 10). Check in NED too: nose = (cos30, 0, −sin30).
  camera::CameraModel cam = AttitudeCamera();
  Eigen::Matrix3d R_cam_body;
  R_cam_body << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  Eigen::Vector3d p_enu;
  Eigen::Matrix3d R_enu_body;
  StationPose(cam, {0.0, DegToRad(30.0)}, R_cam_body, Eigen::Vector3d(0, 0, 20), &p_enu, &R_enu_body);
  EXPECT_LT((p_enu - Eigen::Vector3d(0, 20 * std::sqrt(3.0) / 2, 10)).norm(), kHand);
  const Eigen::Vector3d nose_ned = geo::RotationNedFromEnu() * R_enu_body.col(0);
  EXPECT_LT((nose_ned - Eigen::Vector3d(std::sqrt(3.0) / 2, 0, -0.5)).norm(), kHand);
  const geo::EulerZyx e = geo::EulerFromRotationEnuBody(R_enu_body);
  EXPECT_NEAR(RadToDeg(e.yaw_rad), 0.0, kHand);
  EXPECT_NEAR(RadToDeg(e.pitch_rad), 30.0, kHand);
  EXPECT_NEAR(RadToDeg(e.roll_rad), 0.0, kHand);
  // Roll the camera's view: rotate the body by +20° about its own x (right wing down). The
  // right wing (body y) then points east and 20° down: ENU (cos20, −sin20·sin30, −sin20·cos30)
  // … computed: y_enu = cos20·east + sin20·(body z at roll 0) = cos20 (1,0,0) + sin20 (0, 0.5, −0.866).
  const Eigen::Matrix3d R_roll =
      R_cam_body * Eigen::AngleAxisd(DegToRad(20.0), Eigen::Vector3d::UnitX()).toRotationMatrix();
  StationPose(cam, {0.0, DegToRad(30.0)}, R_roll, Eigen::Vector3d(0, 0, 20), &p_enu, &R_enu_body);
  const double s20 = std::sin(DegToRad(20.0)), c20 = std::cos(DegToRad(20.0));
  EXPECT_LT((R_enu_body.col(1) - Eigen::Vector3d(c20, 0.5 * s20, -std::sqrt(3.0) / 2 * s20)).norm(), kHand);
  const geo::EulerZyx er = geo::EulerFromRotationEnuBody(R_enu_body);
  EXPECT_NEAR(RadToDeg(er.yaw_rad), 0.0, kHand);
  EXPECT_NEAR(RadToDeg(er.pitch_rad), 30.0, kHand);
  EXPECT_NEAR(RadToDeg(er.roll_rad), 20.0, kHand);
}

TEST(BodyAttitude, EulerRoundTripAcrossWraps) {
  for (double yaw : {0.0, 0.001, 359.999, 180.0, 90.0, 271.5}) {
    for (double pitch : {-89.0, -30.0, 0.0, 45.0, 89.0}) {
      for (double roll : {-179.999, -90.0, 0.0, 179.999, 180.0, 33.0}) {
        const geo::EulerZyx e =
            geo::EulerFromRotationNedBody(geo::RotationNedFromBody(DegToRad(yaw), DegToRad(pitch), DegToRad(roll)));
        EXPECT_NEAR(geo::AngleDiff(e.yaw_rad, DegToRad(yaw)), 0.0, 1e-9);
        EXPECT_NEAR(e.pitch_rad, DegToRad(pitch), 1e-9);
        EXPECT_NEAR(geo::AngleDiff(e.roll_rad, DegToRad(roll)), 0.0, 1e-9);
        EXPECT_GE(e.yaw_rad, 0.0);
        EXPECT_LT(e.yaw_rad, geo::kTwoPi);
        EXPECT_GT(e.roll_rad, -geo::kPi);
        EXPECT_LE(e.roll_rad, geo::kPi);
      }
    }
  }
  // Yaw 90° turns the nose east: NED (0, 1, 0), ENU (1, 0, 0).
  const Eigen::Matrix3d R = geo::RotationEnuFromBody({DegToRad(90.0), 0.0, 0.0});
  EXPECT_LT((R.col(0) - Eigen::Vector3d(1, 0, 0)).norm(), kHand);
  EXPECT_LT((R.col(2) - Eigen::Vector3d(0, 0, -1)).norm(), kHand);  // body z down
}

// A moving, rotating target seen by a tracking turret whose log is sampled at 50 Hz; yaw crosses
// 0/360 and roll crosses ±180 during the run.
struct Scene {
  camera::CameraModel cam;
  target::FeatureModel model = Model();
  std::vector<Truth> truth;
  std::string turret_csv;
};

Scene MakeScene(int frames, double yaw0_deg, double roll0_deg) {
  Scene s;
  s.cam = AttitudeCamera();
  s.cam.distortion = {-0.05, 0.02, 1e-4, -2e-4, 0.0};
  s.cam.mount_yaw_rad = DegToRad(0.05);
  s.cam.mount_pitch_rad = DegToRad(-0.03);
  s.cam.mount_roll_rad = DegToRad(0.2);
  auto pos = [](double t) { return Eigen::Vector3d(11.0 + 0.3 * t, 18.0 - 0.4 * t, 2.0 + 0.05 * t); };
  auto bore = [&](double t) {
    // The turret lags the target by 30 ms.
    const geo::AzEl d = geo::AzElFromEnu(pos(t - 0.03));
    return d;
  };
  s.turret_csv = "t_s,az_deg,el_deg\n";
  for (int i = -10; i < frames * 3 + 10; ++i) {
    const double t = 0.0037 + i * 0.02;
    const geo::AzEl d = bore(t);
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.6f,%.9f,%.9f\n", t, RadToDeg(d.az_rad), RadToDeg(d.el_rad));
    s.turret_csv += buf;
  }
  for (int k = 0; k < frames; ++k) {
    const double t = 0.05 * k;
    Truth tr;
    tr.t_s = t;
    tr.p_enu = pos(t);
    tr.att.yaw_rad = geo::WrapTwoPi(DegToRad(yaw0_deg + 2.0 * t));
    tr.att.pitch_rad = DegToRad(5.0 + 1.0 * t);
    tr.att.roll_rad = geo::WrapPi(DegToRad(roll0_deg + 3.0 * t));
    tr.boresight = bore(t);
    s.truth.push_back(tr);
  }
  return s;
}

AttitudeOiResult RunScene(const Scene& s, const std::string& points_csv, AttitudeOiOptions opt = {}) {
  const io::CsvTable pts = io::CsvTable::Parse(points_csv, "points.csv");
  const ImagePoints ip = ReadImagePoints(pts, s.model);
  const formats::TurretLog log = formats::ReadTurretLog(io::CsvTable::Parse(s.turret_csv, "turret.csv"));
  const track::BoresightSource b = track::BoresightSource::FromLog(log, track::InterpMethod::kCubic, 0.1);
  return RunAttitudeOi(ip, s.model, s.cam, b, opt);
}

TEST(AttitudeOi, RecoversStationPoseAcrossYawAndRollWraps) {
  // Yaw 359° → 360.9°, roll 178.5° → 181.35°: the angles wrap inside the run. With 0.02 px noise
  // at ~20 m the attitude error is a few thousandths of a degree (kAttTolDeg leaves 10×).
  constexpr double kAttTolDeg = 0.02, kPosTolM = 0.02;
  const Scene s = MakeScene(20, 359.0, 178.5);
  const AttitudeOiResult r = RunScene(s, PointsCsv(s.truth, s.cam, s.model, 0.02, 1));
  ASSERT_EQ(r.rows.size(), s.truth.size());
  bool yaw_hi = false, yaw_lo = false, roll_pos = false, roll_neg = false;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const PoseRow& row = r.rows[k];
    const Truth& tr = s.truth[k];
    ASSERT_TRUE(row.has_pose) << k;
    EXPECT_EQ(row.status, RowStatus::kOk);
    EXPECT_LT(RadToDeg(std::abs(geo::AngleDiff(row.attitude.yaw_rad, tr.att.yaw_rad))), kAttTolDeg) << k;
    EXPECT_LT(RadToDeg(std::abs(row.attitude.pitch_rad - tr.att.pitch_rad)), kAttTolDeg) << k;
    EXPECT_LT(RadToDeg(std::abs(geo::AngleDiff(row.attitude.roll_rad, tr.att.roll_rad))), kAttTolDeg) << k;
    EXPECT_LT((row.p_enu_m - tr.p_enu).norm(), kPosTolM) << k;
    EXPECT_LT(row.rms_px, 0.1);
    EXPECT_FALSE(row.ambiguous);
    yaw_hi |= RadToDeg(row.attitude.yaw_rad) > 359.0;
    yaw_lo |= RadToDeg(row.attitude.yaw_rad) < 1.0;
    roll_pos |= RadToDeg(row.attitude.roll_rad) > 179.0;
    roll_neg |= RadToDeg(row.attitude.roll_rad) < -179.0;
  }
  EXPECT_TRUE(yaw_hi && yaw_lo && roll_pos && roll_neg);
  const std::string csv = PoseCsv(r).str();
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "frame,t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,status,reproj_rms_px,reproj_max_px,points_used,"
            "ambiguous,alt_yaw_deg,alt_pitch_deg,alt_roll_deg,sigma_e_m,sigma_n_m,sigma_u_m,sigma_yaw_deg,"
            "sigma_pitch_deg,sigma_roll_deg,rejected_id,note,boresight_az_deg,boresight_el_deg");
}

TEST(AttitudeOi, SigmaColumnsMatchTheScatter) {
  // 300 frames of one static pose, 0.3 px noise, sigma_px 0.3 given: the spread of the
  // estimates matches the mean sigma_* within sampling error (±20 %, > 4σ for 300 draws).
  // The turret log is exact here, so its contribution is switched off.
  constexpr double kRatioTol = 0.2;
  Scene s = MakeScene(1, 30.0, 10.0);
  std::vector<Truth> frames;
  std::string csv = "frame,t_s,id,x_px,y_px\n";
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0.0, 0.3);
  const Truth tr = s.truth[0];
  const Eigen::Matrix3d R = geo::RotationEnuFromBody(tr.att);
  for (int k = 0; k < 300; ++k) {
    for (std::size_t i = 0; i < s.model.size(); ++i) {
      const auto uv = s.cam.ProjectEnu(tr.p_enu + R * s.model.p_body[i], tr.boresight.az_rad, tr.boresight.el_rad);
      char buf[128];
      std::snprintf(buf, sizeof buf, "%d,%.6f,%s,%.6f,%.6f\n", k, 0.0 + 0.001 * k, s.model.ids[i].c_str(),
                    uv->x() + g(rng), uv->y() + g(rng));
      csv += buf;
    }
  }
  const ImagePoints ip = ReadImagePoints(io::CsvTable::Parse(csv, "p.csv"), s.model);
  AttitudeOiOptions opt;
  opt.sigma_px = 0.3;
  opt.turret_sigma_deg = 0.0;
  const AttitudeOiResult r =
      RunAttitudeOi(ip, s.model, s.cam, track::BoresightSource::Fixed(tr.boresight.az_rad, tr.boresight.el_rad), opt);
  Eigen::Matrix<double, 6, 1> sq = Eigen::Matrix<double, 6, 1>::Zero(), sig = sq;
  for (const PoseRow& row : r.rows) {
    ASSERT_TRUE(row.has_pose);
    Eigen::Matrix<double, 6, 1> e;
    e << row.p_enu_m - tr.p_enu, geo::AngleDiff(row.attitude.yaw_rad, tr.att.yaw_rad),
        row.attitude.pitch_rad - tr.att.pitch_rad, geo::AngleDiff(row.attitude.roll_rad, tr.att.roll_rad);
    sq += e.cwiseProduct(e);
    sig += row.sigma;
  }
  const double n = static_cast<double>(r.rows.size());
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(std::sqrt(sq(k) / n) / (sig(k) / n), 1.0, kRatioTol) << "output " << k;
  }
  EXPECT_NEAR(r.MeanChi2PerDof(), 1.0, 0.1);
}

TEST(AttitudeOi, RowStatusesForMissingPointsTurretGapsAndOutliers) {
  Scene s = MakeScene(12, 100.0, 0.0);
  // Frame 2: only 3 points (lost, few_points). Frame 5: five points seen, 4 would do.
  std::vector<std::pair<int, std::string>> drop;
  for (const char* id : {"nose", "tail", "fin", "lwing", "rwing"}) drop.emplace_back(2, id);
  for (const char* id : {"belly", "ltail", "canopy"}) drop.emplace_back(5, id);
  std::string csv = PointsCsv(s.truth, s.cam, s.model, 0.02, 2, drop);
  // Frame 7: one point moved 40 px (a mis-extraction) → rejected, pose kept.
  {
    const std::string key = "\n7," + std::to_string(s.truth[7].t_s) + ",fin,";
    const std::size_t at = csv.find(key);
    ASSERT_NE(at, std::string::npos);
    const std::size_t x0 = at + key.size();
    const std::size_t x1 = csv.find(',', x0);
    const double x = std::stod(csv.substr(x0, x1 - x0));
    csv.replace(x0, x1 - x0, std::to_string(x + 40.0));
  }
  // Frames 9–10: the turret log has a 0.3 s hole there.
  std::string turret;
  {
    std::istringstream in(s.turret_csv);
    std::string line;
    while (std::getline(in, line)) {
      const double t = line[0] == 't' ? -1 : std::stod(line);
      if (!(t > 0.42 && t < 0.52)) turret += line + "\n";
    }
  }
  s.turret_csv = turret;
  const AttitudeOiResult r = RunScene(s, csv);
  ASSERT_EQ(r.rows.size(), 12u);
  EXPECT_EQ(r.rows[2].status, RowStatus::kLost);
  EXPECT_EQ(r.rows[2].note, PoseNote::kFewPoints);
  EXPECT_EQ(r.rows[2].points_used, 3);
  EXPECT_EQ(r.rows[3].status, RowStatus::kReacquired);
  EXPECT_EQ(r.rows[5].status, RowStatus::kOk);
  EXPECT_EQ(r.rows[5].points_used, 5);
  EXPECT_EQ(r.rows[7].status, RowStatus::kOk);
  ASSERT_TRUE(r.rows[7].rejected_id.has_value());
  EXPECT_EQ(*r.rows[7].rejected_id, "fin");
  EXPECT_EQ(r.rows[7].points_used, 7);
  EXPECT_EQ(r.rows[9].status, RowStatus::kInvalid);
  EXPECT_EQ(r.rows[9].note, PoseNote::kTurret);
  EXPECT_EQ(r.rows[11].status, RowStatus::kReacquired);
  EXPECT_EQ(r.few_points, 1u);
  EXPECT_EQ(r.outliers_rejected, 1u);
  // Without outlier rejection frame 7 is invalid (reprojection) and keeps its RMS.
  AttitudeOiOptions strict;
  strict.no_reject = true;
  const AttitudeOiResult r2 = RunScene(s, csv, strict);
  EXPECT_EQ(r2.rows[7].status, RowStatus::kInvalid);
  EXPECT_EQ(r2.rows[7].note, PoseNote::kReprojection);
  EXPECT_GT(r2.rows[7].rms_px, 1.0);
  const std::string out = PoseCsv(r2).str();
  EXPECT_NE(out.find(",lost,,,3,,,,,,,,,,,,few_points,"), std::string::npos) << out;
}

TEST(AttitudeOi, PointsOfAMirroredTargetGiveNoPose) {
  // Frame 1 shows the target's mirror image (body y → −y; what a camera would see of the target
  // behind it, reflected through its centre): no proper pose in front of the camera fits a
  // non-planar target's mirror image, so the row is invalid (reprojection), never a wrong pose.
  Scene s = MakeScene(3, 200.0, 0.0);
  target::FeatureModel mirrored = s.model;
  for (auto& p : mirrored.p_body) p.y() = -p.y();
  const std::string normal = PointsCsv(s.truth, s.cam, s.model, 0.02, 3);
  const std::string mirror = PointsCsv(s.truth, s.cam, mirrored, 0.02, 3);
  std::istringstream a(normal), b(mirror);
  std::string la, lb, csv;
  while (std::getline(a, la) && std::getline(b, lb)) csv += (la.rfind("1,", 0) == 0 ? lb : la) + "\n";
  const AttitudeOiResult r = RunScene(s, csv);
  EXPECT_EQ(r.rows[0].status, RowStatus::kOk);
  EXPECT_EQ(r.rows[1].status, RowStatus::kInvalid);
  EXPECT_EQ(r.rows[1].note, PoseNote::kReprojection);
  EXPECT_GT(r.rows[1].rms_px, 1.0);
  EXPECT_EQ(r.rows[2].status, RowStatus::kReacquired);
}

TEST(AttitudeOi, DegenerateFrameIsInvalid) {
  // Four visible points on one line of the body (a degenerate view): invalid, degenerate.
  io::Json j = {{"points",
                 {{"a", {0.0, 0.0, 0.0}},
                  {"b", {0.2, 0.0, 0.0}},
                  {"c", {0.4, 0.0, 0.0}},
                  {"d", {0.6, 0.0, 0.0}},
                  {"e", {0.0, 0.3, 0.0}},
                  {"f", {0.1, 0.0, 0.3}}}}};
  Scene s = MakeScene(3, 40.0, 0.0);
  s.model = target::FeatureModelFromJson(j, "line.json");
  const std::string csv = PointsCsv(s.truth, s.cam, s.model, 0.02, 3, {{1, "e"}, {1, "f"}});
  const AttitudeOiResult r = RunScene(s, csv);
  EXPECT_EQ(r.rows[0].status, RowStatus::kOk);
  EXPECT_EQ(r.rows[1].status, RowStatus::kInvalid);
  EXPECT_EQ(r.rows[1].note, PoseNote::kDegenerate);
}

TEST(AttitudeOi, BadInputIsDataError) {
  const Scene s = MakeScene(2, 10.0, 0.0);
  const std::string good = PointsCsv(s.truth, s.cam, s.model, 0.0, 1);
  auto error_of = [&](const std::string& csv) -> std::string {
    try {
      RunScene(s, csv);
    } catch (const Error& e) {
      return std::to_string(static_cast<int>(e.code())) + " " + e.what();
    }
    return "no error";
  };
  // An id the target model does not have.
  std::string bad = good;
  bad.replace(bad.find(",fin,"), 5, ",wing3,");
  EXPECT_NE(error_of(bad).find("3 points.csv:"), std::string::npos);
  EXPECT_NE(error_of(bad).find("'wing3' is not in the target model"), std::string::npos);
  // The same id twice in a frame (formats::ReadImagePoints, the message of every image-points reader).
  bad = good;
  bad.replace(bad.find(",fin,"), 5, ",tail,");
  EXPECT_NE(error_of(bad).find("given twice in one frame"), std::string::npos);
  // A pixel outside the image (wrong camera model).
  bad = good;
  const std::size_t at = bad.find(",nose,") + 6;
  bad.replace(at, bad.find(',', at) - at, "9999.5");
  EXPECT_NE(error_of(bad).find("outside the 2448x2048 image"), std::string::npos);
  EXPECT_EQ(error_of(bad).substr(0, 2), "3 ");
  // Every frame with fewer than 4 points: processing failed (exit 1), nothing to write.
  std::vector<std::pair<int, std::string>> drop;
  for (int k = 0; k < 2; ++k) {
    for (std::size_t i = 0; i < 5; ++i) drop.emplace_back(k, s.model.ids[i]);
  }
  EXPECT_EQ(error_of(PointsCsv(s.truth, s.cam, s.model, 0.0, 1, drop)).substr(0, 2), "1 ");
  // A turret log that covers no frame.
  Scene late = s;
  late.turret_csv = "t_s,az_deg,el_deg\n100,10,5\n100.02,10,5\n";
  try {
    RunScene(late, good);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("turret.csv"), std::string::npos);
  }
}

// Issue 16 item 1: the oi options come from one table (the solver's nested in it): the choices read and
// write their enumerations, the switches are in the report as given, the bounds give the messages.
TEST(AttitudeOiOptions, TableChoicesSwitchesAndMessages) {
  const auto& table = AttitudeOiOptions::Table();
  AttitudeOiOptions o;
  const auto* second = table.Find("--second-start");
  ASSERT_NE(second, nullptr);
  EXPECT_TRUE(second->set_choice(&o, "never"));
  EXPECT_EQ(o.pnp.second_start, SecondStart::kNever);
  EXPECT_FALSE(second->set_choice(&o, "sometimes"));
  const auto* interp = table.Find("--turret-interp");
  ASSERT_NE(interp, nullptr);
  EXPECT_TRUE(interp->set_choice(&o, "linear"));
  EXPECT_EQ(o.turret_method, track::InterpMethod::kLinear);
  EXPECT_FALSE(interp->set_choice(&o, "local-cubic"));  // the turret takes linear or cubic only
  o.pure_oi = true;
  const io::Json j = o.ToJson();
  EXPECT_EQ(j.at("second_start"), "never");
  EXPECT_EQ(j.at("turret_interp"), "linear");
  EXPECT_EQ(j.at("pure_oi"), true);
  EXPECT_EQ(j.at("no_reject"), false);
  EXPECT_EQ(j.at("turret_max_gap_s"), 0.1);
  EXPECT_EQ(j.at("near_planar"), 0.05);

  std::string why;
  o = {};
  EXPECT_TRUE(o.Check(&why)) << why;
  o.min_points = 3;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--min-points must be in [4, 1000]");
  o = {};
  o.pnp.near_planar_ratio = 1.5;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--near-planar must be in [0, 1]");
}

}  // namespace
}  // namespace rk::pose
