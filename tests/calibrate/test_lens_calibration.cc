// rk-calibrate lens (lib/calibrate/lens_calibration.h) against truth: boards rendered through a known camera
// with distortion (sim/lens_board.h), and OpenCV's own calibration of its sample images (Debian opencv-doc).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calibrate/lens_calibration.h"
#include "io/error.h"
#include "sim/lens_board.h"

namespace rk::calibrate {
namespace {

// A parameter estimate is consistent when it lies within this many of its 1σ of the truth (99.7 % each).
constexpr double kSigmaBound = 3.0;
// Issue 17's target: the calibrated pixel map agrees with the true one to 0.1 px RMS over the image. Met modulo a
// common rotation of the rays (which the pointing calibration absorbs as mount angles) by the recommended field
// view set (20 views, tilts 30–50°, boards 40–70 % of the width, aimed over 90 % of the image): 0.06 px for this
// seed, 0.07 px RMS over ten seeds. Not met absolutely: the principal point's 1σ (≈ 0.3 px with these 0.06 px
// corners) shifts the whole map; the predicted absolute error (from the covariance) is ≈ 0.4 px and the measured
// one agrees with it (docs/benchmarks.md). The absolute error is held to this multiple of its prediction (a
// single draw of a ~χ² with few degrees of freedom: ratios up to 1.6 seen over ten seeds).
constexpr double kMapTargetPx = 0.1;
constexpr double kMapOverPrediction = 2.0;
// Circle grids (10 views of 44 centres, 0.01 px RMS): 0.11 px measured; a looser map tolerance.
constexpr double kLooseMapTolerancePx = 0.2;
// ChArUco (10 views of an 8 × 6 board, 24 mm squares, 18 mm markers): OpenCV's interpolated corners lie
// +0.47 px off in both axes (0.69 px RMS from the truth), refined by RefineCharucoCorners to 0.08 px, unbiased.
// The corners are held to these: the refinement off, or a window reaching the markers, fails them.
constexpr double kCharucoCornerRmsPx = 0.15;
constexpr double kCharucoCornerBiasPx = 0.05;  // |mean error| per axis over all corners (≈ 0.005 px measured)
constexpr double kCharucoRmsPx = 0.3;          // solve residual (0.074 px measured)
// This view set determines the map poorly (predicted absolute σ 1.6 px, 0.33 px modulo rotation, from the
// covariance): the map is held to its prediction, a single draw of a ~χ² with few degrees of freedom.
constexpr double kCharucoMapOverPrediction = 3.0;

// A 640 × 480 camera with strong barrel distortion, fx ≠ fy and an off-centre principal point.
camera::CameraModel TruthCamera() {
  camera::CameraModel c;
  c.width_px = 640;
  c.height_px = 480;
  c.focal_length_mm = 3.0;
  c.pixel_size_mm = {3.0 / 600.0, 3.0 / 606.0};  // fx = 600, fy = 606
  c.principal_point_px = {322.3, 236.8};
  c.distortion = {-0.25, 0.07, 0.0012, -0.0008, 0.0};
  return c;
}

LensOptions ChessOptions() {
  LensOptions o;
  o.board = BoardKind::kChessboard;
  o.cols = 9;
  o.rows = 6;
  o.square_mm = 20.0;
  o.pixel_size_mm = 3.0 / 600.0;
  return o;
}

// Renders `n` views of the board of `opt` with `texture` (outline x0..x1, y0..y1 mm) and detects them.
std::vector<LensView> RenderAndDetect(const sim::BoardTexture& texture, const LensOptions& opt, double x0, double y0,
                                      double x1, double y1, int n, std::uint64_t seed) {
  const camera::CameraModel cam = TruthCamera();
  const sim::BoardRenderer renderer(cam);
  std::vector<LensView> views;
  int i = 0;
  for (const auto& pose : sim::VariedBoardPoses(cam, x0, y0, x1, y1, n, seed)) {
    sim::BoardViewOptions vo;
    vo.seed = seed + static_cast<std::uint64_t>(i);
    const cv::Mat img = renderer.Render(pose.R_cam_board, pose.t_cam_board_mm, texture, vo);
    LensView v;
    v.name = "view" + std::to_string(i++);
    DetectBoard(img, opt, &v);
    views.push_back(v);
  }
  return views;
}

// The chessboard views: 16 for the accuracy test, 8 others for the robustness tests (each test runs in its own
// process under ctest, so each renders only what it needs).
std::vector<LensView> ChessViews(int n, std::uint64_t seed) {
  const LensOptions o = ChessOptions();
  return RenderAndDetect(sim::ChessboardTexture(o.cols, o.rows, o.square_mm), o, -20, -20, 180, 120, n, seed);
}

void ExpectWithinSigma(const char* name, double estimate, double truth, double sigma) {
  const double z = (estimate - truth) / sigma;
  std::printf("  %-3s estimate %12.6f truth %12.6f 1sigma %10.6f error %+6.2f sigma\n", name, estimate, truth, sigma, z);
  EXPECT_LE(std::abs(z), kSigmaBound) << name;
}

void ExpectParametersWithinSigma(const LensResult& res, const camera::CameraModel& truth, bool k3_free) {
  ExpectWithinSigma("fx", res.camera.fx(), truth.fx(), res.sigma.fx_px);
  ExpectWithinSigma("fy", res.camera.fy(), truth.fy(), res.sigma.fy_px);
  ExpectWithinSigma("cx", res.camera.principal_point_px.x(), truth.principal_point_px.x(), res.sigma.cx_px);
  ExpectWithinSigma("cy", res.camera.principal_point_px.y(), truth.principal_point_px.y(), res.sigma.cy_px);
  const char* names[5] = {"k1", "k2", "p1", "p2", "k3"};
  for (std::size_t i = 0; i < (k3_free ? 5u : 4u); ++i) {
    ExpectWithinSigma(names[i], res.camera.distortion[i], truth.distortion[i], res.sigma.distortion[i]);
  }
}

// Every estimated parameter within 3σ of the truth, with k3 free and with k3 fixed at its true 0, for the field view
// set docs/rk-calibrate.md recommends; the pixel map's RMS error over the image modulo a rotation within the target,
// the absolute one as predicted (see kMapTargetPx). Also the camera JSON and the plot.
TEST(LensCalibration, FieldViewSetParametersWithinThreeSigmaAndMapWithinTarget) {
  LensOptions opt = ChessOptions();
  opt.subpix = true;  // findChessboardCornersSB alone leaves ≈ 0.1 px RMS on these sharp images
  sim::BoardPoseSpread field;
  field.tilt_min_deg = 30;
  field.tilt_max_deg = 50;
  field.fill_min = 0.4;
  field.fill_max = 0.7;
  field.aim_fraction = 0.9;
  const camera::CameraModel truth = TruthCamera();
  const sim::BoardRenderer renderer(truth);
  std::vector<LensView> views;
  for (const auto& pose : sim::VariedBoardPoses(truth, -20, -20, 180, 120, 20, 17, field)) {
    sim::BoardViewOptions vo;
    vo.seed = 17 + views.size();
    LensView v;
    v.name = "view" + std::to_string(views.size());
    DetectBoard(renderer.Render(pose.R_cam_board, pose.t_cam_board_mm, sim::ChessboardTexture(9, 6, 20.0), vo), opt,
                &v);
    EXPECT_TRUE(v.found) << v.name;
    views.push_back(v);
  }
  ASSERT_EQ(views.size(), 20u);
  const LensResult free_k3 = SolveLens(views, 640, 480, opt);
  EXPECT_EQ(free_k3.ViewsUsed(), static_cast<int>(views.size()));
  std::printf("  k3 free: rms %.4f px over %d views\n", free_k3.rms_px, free_k3.ViewsUsed());
  ExpectParametersWithinSigma(free_k3, truth, true);
  opt.fix_k3 = true;
  const LensResult res = SolveLens(views, 640, 480, opt);
  std::printf("  k3 fixed: rms %.4f px\n", res.rms_px);
  ExpectParametersWithinSigma(res, truth, false);
  for (const LensResult* r : {&free_k3, &res}) {
    const double map = MapDifferenceRmsPx(truth, r->camera, 4), rot = MapDifferenceModuloRotationRmsPx(truth, r->camera, 4);
    std::printf("  map error over the image: %.4f px RMS (predicted %.4f), modulo rotation %.4f px (predicted %.4f; "
                "target %.2f)\n", map, r->map_sigma.rms_px, rot, r->map_sigma.modulo_rotation_rms_px, kMapTargetPx);
    EXPECT_LE(rot, kMapTargetPx);
    EXPECT_LE(map, kMapOverPrediction * r->map_sigma.rms_px);
  }
  // fx ≠ fy goes into pixel_size_mm[1]; focal_length_mm from fx and --pixel-size-mm.
  EXPECT_DOUBLE_EQ(res.camera.pixel_size_mm[0], opt.pixel_size_mm);
  EXPECT_NEAR(res.camera.focal_length_mm / res.camera.pixel_size_mm[1], res.camera.fy(), 1e-9);
  for (const auto& w : res.warnings) ADD_FAILURE() << w;
  // The camera JSON reads back as the model, with the calibration object.
  const io::Json j = res.CameraJson(opt, "2026-11-26T12:00:00Z");
  const camera::CameraModel back = camera::CameraModelFromJson(j, "camera.json");
  EXPECT_NEAR(back.fx(), res.camera.fx(), 1e-9);
  EXPECT_NEAR(back.fy(), res.camera.fy(), 1e-9);
  EXPECT_EQ(back.distortion[4], 0.0);
  const io::Json& cal = j.at("calibration");
  EXPECT_EQ(cal.at("views_used").size(), views.size());
  EXPECT_TRUE(cal.at("sigma").at("distortion")[4].is_null());  // k3 fixed: no sigma
  EXPECT_GT(cal.at("sigma").at("fx_px").get<double>(), 0.0);
  EXPECT_EQ(cal.at("date"), "2026-11-26T12:00:00Z");
  EXPECT_DOUBLE_EQ(cal.at("rms_px").get<double>(), res.rms_px);
  // The plot: a PNG at least 960 px wide (small images are drawn larger), with a legend band below.
  const std::string png = LensPlotPng(res);
  const cv::Mat img = cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 960);
  EXPECT_GT(img.rows, 720);
}

// Large images are searched on a scaled copy (--detect-max-px) and refined at full size: the corners are as close
// to the truth as a full-size search refined the same way (here 640 × 480 searched on a 400 px copy).
TEST(LensCalibration, ChessboardFoundOnScaledCopyAndRefinedAtFullSize) {
  // The copy only locates the board; findChessboardCornersSB then runs at full size on the board's box (without
  // the histogram equalisation): corners as close to the truth as the whole-frame search's, within a margin
  // (measured 0.0718 against 0.0964 px on these views: the equalisation costs the whole-frame search accuracy).
  constexpr double kCopyOverFullRms = 1.05;
  const camera::CameraModel truth = TruthCamera();
  const sim::BoardRenderer renderer(truth);
  LensOptions full = ChessOptions(), copy = ChessOptions();
  full.detect_max_px = 0;
  copy.detect_max_px = 400;
  double ss_full = 0, ss_copy = 0;
  int i = 0;
  for (const auto& pose : sim::VariedBoardPoses(truth, -20, -20, 180, 120, 6, 23)) {
    sim::BoardViewOptions vo;
    vo.seed = static_cast<std::uint64_t>(++i);
    const cv::Mat img = renderer.Render(pose.R_cam_board, pose.t_cam_board_mm, sim::ChessboardTexture(9, 6, 20.0), vo);
    LensView a, b;
    DetectBoard(img, full, &a);
    DetectBoard(img, copy, &b);
    ASSERT_TRUE(a.found && b.found) << i;
    // The truth in the detector's order (findChessboardCornersSB may start from the opposite corner).
    const auto error2 = [&](const LensView& v) {
      double ss = 0;
      for (std::size_t k = 0; k < v.image_px.size(); ++k) {
        const cv::Point3f& bm = v.board_mm[k];
        const auto q = truth.Project(pose.R_cam_board * Eigen::Vector3d(bm.x, bm.y, 0) + pose.t_cam_board_mm);
        ss += std::pow(v.image_px[k].x - q->x(), 2) + std::pow(v.image_px[k].y - q->y(), 2);
      }
      return ss;
    };
    const auto ordered = [&](LensView v) {  // reverse the detections when they start at the board's far corner
      const auto q0 = truth.Project(pose.R_cam_board * Eigen::Vector3d(0, 0, 0) + pose.t_cam_board_mm);
      if (std::hypot(v.image_px[0].x - q0->x(), v.image_px[0].y - q0->y()) > 10) {
        std::reverse(v.image_px.begin(), v.image_px.end());
      }
      return v;
    };
    ss_full += error2(ordered(a));
    ss_copy += error2(ordered(b));
  }
  const double n = 6 * 54;
  std::printf("  corner error vs truth: whole frame %.4f px RMS, 400 px copy + the board's box %.4f px\n",
              std::sqrt(ss_full / n), std::sqrt(ss_copy / n));
  EXPECT_LE(std::sqrt(ss_copy / n), kCopyOverFullRms * std::sqrt(ss_full / n));
}

TEST(LensCalibration, ViewsWithoutBoardSkippedAndOutlierViewRejected) {
  std::vector<LensView> views = ChessViews(8, 23);
  for (const auto& v : views) ASSERT_TRUE(v.found) << v.name;
  std::vector<LensView> good = views;
  good.erase(good.begin() + 3);
  LensView blank;
  blank.name = "blank";
  DetectBoard(cv::Mat(480, 640, CV_8UC1, cv::Scalar(128)), ChessOptions(), &blank);
  EXPECT_FALSE(blank.found);
  views.push_back(blank);
  views[3].name = "bumped";
  for (std::size_t k = 0; k < views[3].image_px.size(); ++k) views[3].image_px[k].x += (k % 2 ? 2.0f : -2.0f);
  const LensResult res = SolveLens(views, 640, 480, ChessOptions());
  EXPECT_EQ(res.ViewsUsed(), 7);
  EXPECT_EQ(res.ViewsWithoutBoard(), 1);
  EXPECT_EQ(res.ViewsRejected(), 1);
  EXPECT_FALSE(res.views[3].used);
  EXPECT_NE(res.views[3].reason.find("median"), std::string::npos) << res.views[3].reason;
  EXPECT_EQ(res.views[8].reason, "no board");
  EXPECT_GE(res.solves, 2);
  // Rejecting the bad view gives the model of the good views alone.
  const LensResult ref = SolveLens(good, 640, 480, ChessOptions());
  EXPECT_NEAR(res.camera.fx(), ref.camera.fx(), 1e-6);
  EXPECT_NEAR(res.camera.distortion[0], ref.camera.distortion[0], 1e-9);
  // Too few views: exit 1 with the reason.
  try {
    SolveLens({views[0], views[1], blank}, 640, 480, ChessOptions());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kProcessing);
    EXPECT_NE(std::string(e.what()).find("at least 3"), std::string::npos) << e.what();
  }
  try {
    SolveLens({blank, blank}, 640, 480, ChessOptions());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kProcessing);
    EXPECT_NE(std::string(e.what()).find("found in any"), std::string::npos) << e.what();
  }
}

TEST(LensCalibration, FrontoParallelBoardWarns) {
  // Boards square to the optical axis (tilts < 3°) leave the focal length unobservable: a warning.
  const camera::CameraModel cam = TruthCamera();
  const LensOptions opt = ChessOptions();
  std::vector<LensView> views;
  const sim::BoardRenderer renderer(cam);
  const double offsets[4][2] = {{-25, -20}, {20, -15}, {-15, 20}, {25, 15}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.03 * (i % 2 ? 1 : -1), Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Vector3d t(-80 + offsets[i][0], -50 + offsets[i][1], 420);
    LensView v;
    v.name = "flat" + std::to_string(i);
    DetectBoard(renderer.Render(R, t, sim::ChessboardTexture(9, 6, 20), {}), opt, &v);
    ASSERT_TRUE(v.found) << v.name;
    views.push_back(v);
  }
  LensOptions o = opt;
  o.fix_k3 = true;
  const LensResult res = SolveLens(views, 640, 480, o);
  ASSERT_FALSE(res.warnings.empty());
  EXPECT_NE(res.warnings.front().find("poorly determined"), std::string::npos) << res.warnings.front();
}

TEST(LensCalibration, AsymmetricCircleGrid) {
  LensOptions opt = ChessOptions();
  opt.board = BoardKind::kCircles;
  opt.cols = 4;
  opt.rows = 11;
  opt.square_mm = 10.0;
  opt.fix_k3 = true;
  const auto views = RenderAndDetect(sim::CircleGridTexture(4, 11, 10.0), opt, -20, -20, 90, 120, 10, 5);
  int found = 0;
  for (const auto& v : views) found += v.found;
  EXPECT_GE(found, 8);
  const LensResult res = SolveLens(views, 640, 480, opt);
  const double map_rms = MapDifferenceRmsPx(TruthCamera(), res.camera, 8);
  std::printf("  circles: %d views, rms %.4f px, map error %.4f px\n", res.ViewsUsed(), res.rms_px, map_rms);
  EXPECT_LE(map_rms, kLooseMapTolerancePx);
}

TEST(LensCalibration, Charuco) {
  LensOptions opt = ChessOptions();
  opt.board = BoardKind::kCharuco;
  opt.cols = 8;
  opt.rows = 6;
  opt.square_mm = 24.0;
  opt.marker_mm = 18.0;
  opt.fix_k3 = true;
  const auto board = cv::aruco::CharucoBoard::create(8, 6, 24.f, 18.f,
                                                     cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50));
  cv::Mat drawn;
  board->draw(cv::Size(8 * 60, 6 * 60), drawn, 0, 1);  // 60 texture px per square: 0.4 mm per px
  cv::Mat with_margin(drawn.rows + 120, drawn.cols + 120, CV_8UC1, cv::Scalar(255));
  drawn.copyTo(with_margin(cv::Rect(60, 60, drawn.cols, drawn.rows)));
  // The texture's origin is its top-left corner; the board's (0, 0) sits one margin (24 mm) inside.
  const sim::BoardTexture inner = sim::ImageTexture(with_margin, 0.4);
  const sim::BoardTexture texture = [inner](double x, double y) { return inner(x + 24.0, y + 24.0); };
  constexpr int kViews = 10;
  constexpr std::uint64_t kSeed = 9;
  const auto views = RenderAndDetect(texture, opt, -24, -24, 8 * 24 + 24, 6 * 24 + 24, kViews, kSeed);
  // The true corners: the same poses (RenderAndDetect keeps one view per pose, found or not).
  const camera::CameraModel truth = TruthCamera();
  const auto poses = sim::VariedBoardPoses(truth, -24, -24, 8 * 24 + 24, 6 * 24 + 24, kViews, kSeed);
  ASSERT_EQ(views.size(), poses.size());
  int found = 0, n = 0;
  double sx = 0.0, sy = 0.0, s2 = 0.0;
  for (std::size_t k = 0; k < views.size(); ++k) {
    if (!views[k].found) continue;
    ++found;
    for (std::size_t i = 0; i < views[k].board_mm.size(); ++i) {
      const cv::Point3f& b = views[k].board_mm[i];
      const auto q = truth.Project(poses[k].R_cam_board * Eigen::Vector3d(b.x, b.y, b.z) + poses[k].t_cam_board_mm);
      ASSERT_TRUE(q.has_value());
      const double ex = views[k].image_px[i].x - q->x(), ey = views[k].image_px[i].y - q->y();
      sx += ex;
      sy += ey;
      s2 += ex * ex + ey * ey;
      ++n;
    }
  }
  EXPECT_GE(found, 8);
  ASSERT_GT(n, 0);
  const double corner_rms = std::sqrt(s2 / n);
  std::printf("  charuco corners: %d, RMS %.4f px from the truth, mean %+.4f %+.4f px\n", n, corner_rms, sx / n, sy / n);
  EXPECT_LE(corner_rms, kCharucoCornerRmsPx);
  EXPECT_LE(std::abs(sx / n), kCharucoCornerBiasPx);
  EXPECT_LE(std::abs(sy / n), kCharucoCornerBiasPx);
  const LensResult res = SolveLens(views, 640, 480, opt);
  const double map_rms = MapDifferenceRmsPx(truth, res.camera, 8);
  const double map_rot = MapDifferenceModuloRotationRmsPx(truth, res.camera, 8);
  std::printf("  charuco: %d views, rms %.4f px, map error %.4f px (predicted %.4f), modulo rotation %.4f (%.4f)\n",
              res.ViewsUsed(), res.rms_px, map_rms, res.map_sigma.rms_px, map_rot, res.map_sigma.modulo_rotation_rms_px);
  EXPECT_LE(res.rms_px, kCharucoRmsPx);
  EXPECT_LE(map_rms, kCharucoMapOverPrediction * res.map_sigma.rms_px);
  EXPECT_LE(map_rot, kCharucoMapOverPrediction * res.map_sigma.modulo_rotation_rms_px);
}

// True corners of `poses` (projected through `cam`) with Gaussian noise of `sigma_px`: views for the solver alone.
std::vector<LensView> NoisyTrueViews(const camera::CameraModel& cam, const std::vector<sim::BoardPose>& poses,
                                     double sigma_px, std::mt19937_64* rng) {
  const LensOptions o = ChessOptions();
  std::normal_distribution<double> noise(0.0, sigma_px);
  std::vector<LensView> views;
  for (const auto& pose : poses) {
    LensView v;
    v.name = "view" + std::to_string(views.size());
    v.found = true;
    for (int r = 0; r < o.rows; ++r) {
      for (int c = 0; c < o.cols; ++c) {
        const Eigen::Vector3d p(c * o.square_mm, r * o.square_mm, 0.0);
        const auto q = cam.Project(pose.R_cam_board * p + pose.t_cam_board_mm);
        v.image_px.emplace_back(static_cast<float>(q->x() + noise(*rng)), static_cast<float>(q->y() + noise(*rng)));
        v.board_mm.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.f);
      }
    }
    views.push_back(v);
  }
  return views;
}

// The intrinsics' covariance (our Jacobians from cv::projectPoints, poses marginalised) against cv::calibrateCamera's
// own stdDeviationsIntrinsics, which divide Σr² by N − p (N points) where the 2N residual components call for
// 2N − p: ours must be OpenCV's × √((N − p)/(2N − p)). With every term free, with --fix-aspect (fx = a fy: fx and fy
// fully correlated) and with --fix-k3 --zero-tangent (their rows zero).
TEST(LensCalibration, IntrinsicCovarianceDiagonalIsOpenCvSigmaRescaled) {
  // The same normal matrix at the same solution, assembled independently: equal to the solver's convergence.
  constexpr double kSameSigmaRelative = 1e-3;
  std::mt19937_64 rng(4);
  const camera::CameraModel truth = TruthCamera();
  const auto views = NoisyTrueViews(truth, sim::VariedBoardPoses(truth, -20, -20, 180, 120, 12, 8), 0.05, &rng);
  const int free_intrinsics[3] = {9, 8, 6};
  for (int variant = 0; variant < 3; ++variant) {
    LensOptions opt = ChessOptions();
    opt.fix_aspect = variant == 1;
    opt.fix_k3 = opt.zero_tangent = variant == 2;
    const LensResult res = SolveLens(views, 640, 480, opt);
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img;
    for (const auto& v : views) obj.push_back(v.board_mm), img.push_back(v.image_px);
    cv::Mat K = cv::Mat::eye(3, 3, CV_64F), dist = cv::Mat::zeros(5, 1, CV_64F), sd, sd_ext, per_view;
    std::vector<cv::Mat> rv, tv;
    cv::calibrateCamera(obj, img, cv::Size(640, 480), K, dist, rv, tv, sd, sd_ext, per_view, opt.OpenCvFlags(),
                        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));
    const double n = static_cast<double>(views.size() * views[0].image_px.size());
    const double p = free_intrinsics[variant] + 6.0 * static_cast<double>(views.size());
    const double rescale = std::sqrt((n - p) / (2 * n - p));
    for (int i = 0; i < 9; ++i) {
      const double theirs = sd.at<double>(i) * rescale;
      if (theirs == 0.0) continue;  // fixed in OpenCV's parameterisation (fx under --fix-aspect)
      EXPECT_NEAR(std::sqrt(res.covariance(i, i)), theirs, kSameSigmaRelative * theirs)
          << "variant " << variant << " parameter " << i;
    }
    EXPECT_TRUE(res.covariance.isApprox(res.covariance.transpose()));
    if (variant == 1) {  // fx = a fy: correlation 1
      EXPECT_NEAR(res.covariance(0, 1) / std::sqrt(res.covariance(0, 0) * res.covariance(1, 1)), 1.0, 1e-9);
    }
    if (variant == 2) {
      EXPECT_EQ(res.covariance(8, 8), 0.0);
    }
  }
}

// PredictedMapSigma linearises the map in the intrinsics by central differences: for a small parameter change δ
// (covariance δδᵀ) it predicts the map difference MapDifferenceRmsPx measures directly, and likewise modulo rotation.
TEST(LensCalibration, LinearisedMapMatchesMapDifference) {
  // δ is 1e-3 of typical 1σ-scale errors squared away: the linearisation error is second order (relative ~1e-3).
  constexpr double kLinearisationRelative = 0.01;
  const camera::CameraModel truth = TruthCamera();
  const double deltas[4][9] = {{0.3, 0, 0, 0, 0, 0, 0, 0, 0},
                               {0, 0, 0.5, -0.4, 0, 0, 0, 0, 0},
                               {0.2, -0.1, 0.3, 0.1, 2e-4, -5e-4, 1e-5, -2e-5, 3e-4},
                               {0, 0, 0, 0, 1e-3, 0, 0, 0, 0}};
  for (const auto& d : deltas) {
    const Eigen::Map<const Eigen::Matrix<double, 9, 1>> delta(d);
    camera::CameraModel moved = truth;
    moved.focal_length_mm = (truth.fx() + delta(0)) * truth.pixel_size_mm[0];
    moved.pixel_size_mm[1] = moved.focal_length_mm / (truth.fy() + delta(1));
    moved.principal_point_px += delta.segment<2>(2);
    for (std::size_t k = 0; k < 5; ++k) moved.distortion[k] += delta(4 + static_cast<Eigen::Index>(k));
    const MapSigma lin = PredictedMapSigma(truth, delta * delta.transpose(), 8);
    const double direct = MapDifferenceRmsPx(truth, moved, 8);
    const double direct_rot = MapDifferenceModuloRotationRmsPx(truth, moved, 8);
    std::printf("  map %.5f px (linearised %.5f), modulo rotation %.5f px (linearised %.5f)\n", direct, lin.rms_px,
                direct_rot, lin.modulo_rotation_rms_px);
    EXPECT_NEAR(lin.rms_px, direct, kLinearisationRelative * direct);
    EXPECT_NEAR(lin.modulo_rotation_rms_px, direct_rot, kLinearisationRelative * direct + 1e-6);
  }
  // A pure principal-point shift is nearly a rotation: little is left after removing the best one.
  Eigen::Matrix<double, 9, 9> cov = Eigen::Matrix<double, 9, 9>::Zero();
  cov(2, 2) = 1.0;
  const MapSigma pp = PredictedMapSigma(truth, cov, 8);
  EXPECT_LT(pp.modulo_rotation_rms_px, 0.5 * pp.rms_px);
}

// The predicted map error (from the covariance) is the real one: over Monte Carlo solves of noisy true corners, the
// mean squared map error against the truth over the mean squared prediction lies in an NEES-like band.
TEST(LensCalibration, PredictedMapSigmaMatchesMonteCarlo) {
  constexpr int kRuns = 40;
  // 40 runs of a squared error with ~a few effective degrees of freedom: the ratio's spread is ±25 % or so.
  constexpr double kRatioLow = 0.6, kRatioHigh = 1.5;
  std::mt19937_64 rng(11);
  const camera::CameraModel truth = TruthCamera();
  const auto poses = sim::VariedBoardPoses(truth, -20, -20, 180, 120, 16, 17);
  LensOptions opt = ChessOptions();
  opt.fix_k3 = true;
  double err2 = 0, pred2 = 0, err2_rot = 0, pred2_rot = 0;
  for (int run = 0; run < kRuns; ++run) {
    const LensResult res = SolveLens(NoisyTrueViews(truth, poses, 0.05, &rng), 640, 480, opt);
    err2 += std::pow(MapDifferenceRmsPx(truth, res.camera, 10), 2);
    err2_rot += std::pow(MapDifferenceModuloRotationRmsPx(truth, res.camera, 10), 2);
    pred2 += std::pow(res.map_sigma.rms_px, 2);
    pred2_rot += std::pow(res.map_sigma.modulo_rotation_rms_px, 2);
  }
  const double ratio = err2 / pred2, ratio_rot = err2_rot / pred2_rot;
  std::printf("  map: measured %.4f px RMS, predicted %.4f (ratio of squares %.2f); modulo rotation %.4f / %.4f (%.2f)\n",
              std::sqrt(err2 / kRuns), std::sqrt(pred2 / kRuns), ratio, std::sqrt(err2_rot / kRuns),
              std::sqrt(pred2_rot / kRuns), ratio_rot);
  EXPECT_GE(ratio, kRatioLow);
  EXPECT_LE(ratio, kRatioHigh);
  EXPECT_GE(ratio_rot, kRatioLow);
  EXPECT_LE(ratio_rot, kRatioHigh);
}

// OpenCV's sample images (9 × 6 inner corners, 25 mm, 640 × 480; left10.jpg is missing: 13 views) and its own
// calibration of them, left_intrinsics.yml: flags 2 = CALIB_FIX_ASPECT_RATIO, all 13 views, corners from
// samples/cpp/calibration.cpp (findChessboardCorners + cornerSubPix 11 × 11).
const char* kOpenCvData = "/usr/share/doc/opencv-doc/examples/data";
const int kOpenCvViews[13] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14};
// The same corners and flags through SolveLens: every parameter within this many of its 1σ of OpenCV's file
// (the file was made by an older OpenCV, whose corner refinement and solver stop differ slightly).
constexpr double kSameCornersSigma = 0.5;
// Our default detector (findChessboardCornersSB) on the same images: its corners differ (left02.jpg: 0.27 px RMS
// here, 1.18 px in OpenCV's file, whose cornerSubPix corners there are off), so the models differ by about their
// σ. Stated tolerances: fx within 1 %, cx, cy within 3 px. (The distortion coefficients are strongly correlated
// and differ by several σ each; the pixel maps are compared, for the record, at the corners seen.)
constexpr double kOwnDetectorFocalTolerance = 0.01;
constexpr double kOwnDetectorCentreTolerancePx = 3.0;

struct OpenCvFile {
  cv::Mat K, dist;
  camera::CameraModel Model() const {
    camera::CameraModel c;
    c.width_px = 640;
    c.height_px = 480;
    c.pixel_size_mm = {1.0, K.at<double>(0, 0) / K.at<double>(1, 1)};
    c.focal_length_mm = K.at<double>(0, 0);
    c.principal_point_px = {K.at<double>(0, 2), K.at<double>(1, 2)};
    for (int i = 0; i < 5; ++i) c.distortion[static_cast<std::size_t>(i)] = dist.at<double>(i);
    return c;
  }
};

OpenCvFile ReadOpenCvFile() {
  cv::FileStorage fs(std::string(kOpenCvData) + "/left_intrinsics.yml", cv::FileStorage::READ);
  OpenCvFile f;
  fs["camera_matrix"] >> f.K;
  fs["distortion_coefficients"] >> f.dist;
  return f;
}

LensOptions OpenCvSampleOptions() {
  LensOptions opt;
  opt.board = BoardKind::kChessboard;
  opt.cols = 9;
  opt.rows = 6;
  opt.square_mm = 25.0;
  opt.fix_aspect = true;   // the file's flags
  opt.reject_ratio = 1e9;  // and all 13 views
  opt.threads = 2;
  return opt;
}

void PrintModel(const char* what, const camera::CameraModel& c) {
  std::printf("  %-6s fx %.3f fy %.3f cx %.3f cy %.3f k %.5f %.5f %.5f %.5f %.5f\n", what, c.fx(), c.fy(),
              c.principal_point_px.x(), c.principal_point_px.y(), c.distortion[0], c.distortion[1], c.distortion[2],
              c.distortion[3], c.distortion[4]);
}

TEST(LensCalibration, ReproducesOpenCvSampleCalibrationWithItsCorners) {
  if (!std::filesystem::exists(std::string(kOpenCvData) + "/left_intrinsics.yml")) {
    GTEST_SKIP() << "opencv-doc not installed (scripts/setup.sh installs it)";
  }
  const OpenCvFile file = ReadOpenCvFile();
  const LensOptions opt = OpenCvSampleOptions();
  std::vector<LensView> views;
  for (int n : kOpenCvViews) {
    char path[256];
    std::snprintf(path, sizeof path, "%s/left%02d.jpg", kOpenCvData, n);
    const cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
    LensView v;
    v.name = path;
    v.found = cv::findChessboardCorners(gray, cv::Size(9, 6), v.image_px,
                                        cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_FAST_CHECK | cv::CALIB_CB_NORMALIZE_IMAGE);
    ASSERT_TRUE(v.found) << path;
    cv::cornerSubPix(gray, v.image_px, cv::Size(11, 11), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.0001));
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 9; ++c) v.board_mm.emplace_back(25.f * c, 25.f * r, 0.f);
    }
    views.push_back(v);
  }
  const LensResult res = SolveLens(views, 640, 480, opt);
  PrintModel("ours", res.camera);
  PrintModel("file", file.Model());
  EXPECT_EQ(res.ViewsUsed(), 13);
  const auto within = [](const char* name, double ours, double file, double sigma) {
    std::printf("  %-3s ours %11.5f file %11.5f 1sigma %9.5f difference %+5.2f sigma\n", name, ours, file, sigma,
                (ours - file) / sigma);
    EXPECT_LE(std::abs(ours - file), kSameCornersSigma * sigma) << name;
  };
  within("fx", res.camera.fx(), file.K.at<double>(0, 0), res.sigma.fx_px);
  within("fy", res.camera.fy(), file.K.at<double>(1, 1), res.sigma.fy_px);
  within("cx", res.camera.principal_point_px.x(), file.K.at<double>(0, 2), res.sigma.cx_px);
  within("cy", res.camera.principal_point_px.y(), file.K.at<double>(1, 2), res.sigma.cy_px);
  const char* names[5] = {"k1", "k2", "p1", "p2", "k3"};
  for (int i = 0; i < 5; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    within(names[k], res.camera.distortion[k], file.dist.at<double>(i), res.sigma.distortion[k]);
  }
}

TEST(LensCalibration, OpenCvSampleWithOurDetector) {
  if (!std::filesystem::exists(std::string(kOpenCvData) + "/left_intrinsics.yml")) {
    GTEST_SKIP() << "opencv-doc not installed (scripts/setup.sh installs it)";
  }
  const OpenCvFile file = ReadOpenCvFile();
  // left0%d.jpg reads left01..left09, left1%d.jpg left11..left14 (a pattern starts at 0 or 1 and stops at a gap).
  const LensResult res = CalibrateLens(
      {std::string(kOpenCvData) + "/left0%d.jpg", std::string(kOpenCvData) + "/left1%d.jpg"}, OpenCvSampleOptions());
  EXPECT_EQ(res.ViewsUsed(), 13);
  PrintModel("ours", res.camera);
  PrintModel("file", file.Model());
  double ss = 0;
  std::size_t n = 0;
  for (const auto& v : res.views) {
    for (const auto& p : v.image_px) {
      const auto q = res.camera.Project(file.Model().NormalisedRay(Eigen::Vector2d(p.x, p.y)));
      ss += (*q - Eigen::Vector2d(p.x, p.y)).squaredNorm();
      ++n;
    }
  }
  const double map_px = std::sqrt(ss / static_cast<double>(n));
  std::printf("  rms %.4f px; sigma fx %.3f cx %.3f cy %.3f; map difference at the corners seen %.3f px RMS\n", res.rms_px, res.sigma.fx_px,
              res.sigma.cx_px, res.sigma.cy_px, map_px);
  EXPECT_NEAR(res.camera.fx(), file.K.at<double>(0, 0), kOwnDetectorFocalTolerance * file.K.at<double>(0, 0));
  EXPECT_NEAR(res.camera.principal_point_px.x(), file.K.at<double>(0, 2), kOwnDetectorCentreTolerancePx);
  EXPECT_NEAR(res.camera.principal_point_px.y(), file.K.at<double>(1, 2), kOwnDetectorCentreTolerancePx);
}

// Not a test: writes the benchmark's 20 five-megapixel views (bench/bench_lens_calibration.cc) to
// $RK_LENS_VIEWS_DIR as %02d.png, so the ASan build can time `rk-calibrate lens` on them (OpenCV's detector and
// solver are not instrumented). Run with --gtest_also_run_disabled_tests --gtest_filter=*WriteFiveMegapixel*.
TEST(LensCalibration, DISABLED_WriteFiveMegapixelViews) {
  const char* dir = std::getenv("RK_LENS_VIEWS_DIR");
  ASSERT_NE(dir, nullptr);
  camera::CameraModel cam;  // 2448 × 2048, 3.45 µm, 12 mm, as the benchmark
  cam.focal_length_mm = 12.0;
  cam.principal_point_px = {1230.2, 1020.9};
  cam.distortion = {-0.12, 0.05, 0.0004, -0.0002, 0.0};
  const sim::BoardRenderer renderer(cam);
  const auto poses = sim::VariedBoardPoses(cam, -30, -30, 270, 180, 20, 3);
  sim::BoardViewOptions vo;
  vo.supersample = 2;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    vo.seed = i + 1;
    char name[32];
    std::snprintf(name, sizeof name, "/%02d.png", static_cast<int>(i));
    cv::imwrite(dir + std::string(name),
                renderer.Render(poses[i].R_cam_board, poses[i].t_cam_board_mm, sim::ChessboardTexture(9, 6, 30.0), vo));
  }
}

}  // namespace
}  // namespace rk::calibrate
