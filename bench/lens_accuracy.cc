// Lens-calibration accuracy experiments (figures in docs/benchmarks.md, "Issue 17 — rk-calibrate lens"); never asserts.
//   lens_accuracy N SEED SUPERSAMPLE [TILT_MIN TILT_MAX FILL_MIN FILL_MAX AIM]   640 x 480 chessboard views: corner
//       error against the truth per refiner, calibration map error (absolute, modulo rotation) against its prediction
//   lens_accuracy charuco N SEED REFINE      ChArUco corners against the truth, OpenCV's and refined
//   lens_accuracy big N [FULL]               the 5 Mpx views of bench_lens_calibration: refiners and their time
// $RK_EXP_BLUR (px): Gaussian blur of the rendered images (a lens PSF); $RK_EXP_WIN: cornerSubPix half-window.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>

#include "calibrate/lens_calibration.h"
#include "sim/lens_board.h"

using namespace rk;

static camera::CameraModel TruthCamera() {
  camera::CameraModel c;
  c.width_px = 640;
  c.height_px = 480;
  c.focal_length_mm = 3.0;
  c.pixel_size_mm = {3.0 / 600.0, 3.0 / 606.0};
  c.principal_point_px = {322.3, 236.8};
  c.distortion = {-0.25, 0.07, 0.0012, -0.0008, 0.0};
  return c;
}

static std::vector<cv::Point2f> TrueCorners(const camera::CameraModel& cam, const sim::BoardPose& p, int cols, int rows,
                                            double sq) {
  std::vector<cv::Point2f> out;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const auto q = cam.Project(p.R_cam_board * Eigen::Vector3d(c * sq, r * sq, 0) + p.t_cam_board_mm);
      out.emplace_back(static_cast<float>(q->x()), static_cast<float>(q->y()));
    }
  return out;
}

struct Err {
  double ss = 0, sx = 0, sy = 0;
  std::size_t n = 0;
  void Add(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b) {
    for (std::size_t k = 0; k < a.size(); ++k) {
      const cv::Point2f d = a[k] - b[k];
      ss += d.dot(d);
      sx += d.x;
      sy += d.y;
      ++n;
    }
  }
  double Rms() const { return std::sqrt(ss / n); }
};

// Predicted RMS map error from the intrinsic covariance (numerical map Jacobian per parameter).
static double PredictedMap(const camera::CameraModel& truth, const Eigen::MatrixXd& cov_intr, bool k3, int step) {
  const int np = k3 ? 9 : 8;
  std::vector<Eigen::Vector2d> grid;
  std::vector<Eigen::Vector3d> rays;
  for (int y = 0; y < truth.height_px; y += step)
    for (int x = 0; x < truth.width_px; x += step) {
      grid.emplace_back(x, y);
      rays.push_back(truth.NormalisedRay(grid.back()));
    }
  std::vector<Eigen::MatrixXd> G(grid.size(), Eigen::MatrixXd::Zero(2, np));
  for (int j = 0; j < np; ++j) {
    camera::CameraModel b = truth;
    double h = 1e-4;
    if (j == 0) { b.focal_length_mm += h * b.pixel_size_mm[0]; }
    if (j == 1) { b.pixel_size_mm[1] = b.focal_length_mm / (truth.fy() + h); }
    if (j == 2) b.principal_point_px.x() += h;
    if (j == 3) b.principal_point_px.y() += h;
    if (j >= 4) { h = 1e-7; b.distortion[static_cast<std::size_t>(j - 4)] += h; }
    for (std::size_t g = 0; g < grid.size(); ++g) G[g].col(j) = (*b.Project(rays[g]) - grid[g]) / h;
  }
  double s = 0;
  for (auto& g : G) s += (g * cov_intr * g.transpose()).trace();
  return std::sqrt(s / grid.size());
}

// CRB: σ² (JᵀJ)⁻¹ at the truth, intrinsics block (fx, fy, cx, cy, k1, k2, p1, p2[, k3]).
static Eigen::MatrixXd Crb(const camera::CameraModel& truth, const std::vector<sim::BoardPose>& poses, int cols, int rows,
                           double sq, double sigma, bool k3) {
  const int np = k3 ? 9 : 8, nv = static_cast<int>(poses.size()), N = np + 6 * nv;
  Eigen::MatrixXd JtJ = Eigen::MatrixXd::Zero(N, N);
  cv::Mat K = (cv::Mat_<double>(3, 3) << truth.fx(), 0, truth.principal_point_px.x(), 0, truth.fy(),
               truth.principal_point_px.y(), 0, 0, 1);
  cv::Mat dist(5, 1, CV_64F);
  for (int i = 0; i < 5; ++i) dist.at<double>(i) = truth.distortion[static_cast<std::size_t>(i)];
  std::vector<cv::Point3f> obj;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) obj.emplace_back(static_cast<float>(c * sq), static_cast<float>(r * sq), 0.f);
  for (int v = 0; v < nv; ++v) {
    cv::Mat R(3, 3, CV_64F), rvec, tvec(3, 1, CV_64F);
    for (int a = 0; a < 3; ++a) {
      tvec.at<double>(a) = poses[v].t_cam_board_mm(a);
      for (int b = 0; b < 3; ++b) R.at<double>(a, b) = poses[v].R_cam_board(a, b);
    }
    cv::Rodrigues(R, rvec);
    std::vector<cv::Point2f> proj;
    cv::Mat jac;
    cv::projectPoints(obj, rvec, tvec, K, dist, proj, jac);  // 2n × (3 rot, 3 t, 2 f, 2 c, 5 dist)
    const int n2 = jac.rows;
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n2, N);
    for (int r = 0; r < n2; ++r) {
      for (int c = 0; c < 6; ++c) J(r, np + 6 * v + c) = jac.at<double>(r, c);
      for (int c = 0; c < np; ++c) J(r, c) = jac.at<double>(r, 6 + c);
    }
    JtJ += J.transpose() * J;
  }
  const Eigen::MatrixXd cov = sigma * sigma * JtJ.inverse();
  return cov.topLeftCorner(np, np);
}

static double MapModuloRotation(const camera::CameraModel& a, const camera::CameraModel& b, int step) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  double rms = 0;
  for (int it = 0; it < 5; ++it) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    double ss = 0;
    std::size_t n = 0;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(w.norm(), w.norm() > 0 ? w.normalized() : Eigen::Vector3d::UnitZ())
                                  .toRotationMatrix();
    for (int y = 0; y < a.height_px; y += step)
      for (int x = 0; x < a.width_px; x += step) {
        const Eigen::Vector2d px(x, y);
        const Eigen::Vector3d ray = R * a.NormalisedRay(px);
        const Eigen::Vector2d e = *b.Project(ray) - px;
        Eigen::Matrix<double, 2, 3> J;
        for (int k = 0; k < 3; ++k) {
          Eigen::Vector3d d = Eigen::Vector3d::Zero();
          d(k) = 1e-7;
          J.col(k) = (*b.Project(ray + d.cross(ray)) - *b.Project(ray)) / 1e-7;
        }
        A += J.transpose() * J;
        rhs += J.transpose() * e;
        ss += e.squaredNorm();
        ++n;
      }
    rms = std::sqrt(ss / n);
    const Eigen::Vector3d dw = -A.ldlt().solve(rhs);
    w += dw;  // small-angle composition is fine here
  }
  return rms;
}

// Optional Gaussian blur (σ px, $RK_EXP_BLUR) of a rendered image: a lens's PSF.
static cv::Mat Blurred(const cv::Mat& img) {
  const char* b = std::getenv("RK_EXP_BLUR");
  if (!b || std::atof(b) <= 0) return img;
  cv::Mat out;
  cv::GaussianBlur(img, out, cv::Size(0, 0), std::atof(b));
  return out;
}

static double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

static std::vector<cv::Point2f> Ordered(const std::vector<cv::Point2f>& truth, const std::vector<cv::Point2f>& det) {
  auto t = truth;
  if (cv::norm(det[0] - truth[0]) > cv::norm(det[0] - truth.back())) std::reverse(t.begin(), t.end());
  return t;
}

static int Big(int n, int full) {
  camera::CameraModel cam;
  cam.focal_length_mm = 12.0;
  cam.principal_point_px = {1230.2, 1020.9};
  cam.distortion = {-0.12, 0.05, 0.0004, -0.0002, 0.0};
  const auto poses = sim::VariedBoardPoses(cam, -30, -30, 270, 180, n, 3);
  calibrate::LensOptions o;
  o.square_mm = 30;
  Err e_full, e_lib, e_acc, e_q4;
  double t_full = 0, t_lib = 0, t_acc = 0, t_q4 = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/tmp/rk_bench_lens/%02d.png", static_cast<int>(i));
    const cv::Mat img = cv::imread(name, cv::IMREAD_GRAYSCALE);
    const auto truec = TrueCorners(cam, poses[i], 9, 6, 30.0);
    double t0 = Now();
    if (full) {
      calibrate::LensView a;
      o.detect_max_px = 0;
      calibrate::DetectBoard(img, o, &a);
      t_full += Now() - t0;
      if (a.found) e_full.Add(a.image_px, Ordered(truec, a.image_px));
    }
    o.detect_max_px = 1600;
    calibrate::LensView b;
    t0 = Now();
    calibrate::DetectBoard(img, o, &b);
    t_lib += Now() - t0;
    if (!b.found) { std::printf("view %zu: not found on the copy\n", i); continue; }
    e_lib.Add(b.image_px, Ordered(truec, b.image_px));
    const double scale = 1600.0 / std::max(img.cols, img.rows);
    cv::Mat small;
    cv::resize(img, small, cv::Size(static_cast<int>(std::lround(img.cols * scale)), static_cast<int>(std::lround(img.rows * scale))), 0, 0, cv::INTER_AREA);
    const double sx = static_cast<double>(small.cols) / img.cols, sy = static_cast<double>(small.rows) / img.rows;
    const auto up = [&](std::vector<cv::Point2f>& c) {
      for (auto& p : c) p = cv::Point2f(static_cast<float>((p.x + 0.5) / sx - 0.5), static_cast<float>((p.y + 0.5) / sy - 0.5));
    };
    std::vector<cv::Point2f> c;
    t0 = Now();
    cv::findChessboardCornersSB(small, cv::Size(9, 6), c, cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY);
    up(c);
    cv::cornerSubPix(img, c, cv::Size(7, 7), cv::Size(-1, -1), cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
    t_acc += Now() - t0;
    e_acc.Add(c, Ordered(truec, c));
    std::vector<cv::Point2f> d;
    t0 = Now();
    cv::findChessboardCornersSB(small, cv::Size(9, 6), d, cv::CALIB_CB_NORMALIZE_IMAGE);
    up(d);
    cv::find4QuadCornerSubpix(img, d, cv::Size(7, 7));
    t_q4 += Now() - t0;
    e_q4.Add(d, Ordered(truec, d));
  }
  std::printf("5MP, %d views, corner error vs truth px RMS (mean x, y) and detection CPU-thread seconds:\n", n);
  if (full) std::printf("  full-size SB+ACCURACY             %.4f (%+.4f %+.4f) %.2f s\n", e_full.Rms(), e_full.sx / e_full.n, e_full.sy / e_full.n, t_full);
  std::printf("  copy SB + cornerSubPix (library)  %.4f (%+.4f %+.4f) %.2f s\n", e_lib.Rms(), e_lib.sx / e_lib.n, e_lib.sy / e_lib.n, t_lib);
  std::printf("  copy SB+ACCURACY + cornerSubPix   %.4f (%+.4f %+.4f) %.2f s\n", e_acc.Rms(), e_acc.sx / e_acc.n, e_acc.sy / e_acc.n, t_acc);
  std::printf("  copy SB + find4QuadCornerSubpix   %.4f (%+.4f %+.4f) %.2f s\n", e_q4.Rms(), e_q4.sx / e_q4.n, e_q4.sy / e_q4.n, t_q4);
  return 0;
}

static int Charuco(int n, std::uint64_t seed, bool refine) {
  const camera::CameraModel truth = TruthCamera();
  calibrate::LensOptions opt;
  opt.board = calibrate::BoardKind::kCharuco;
  opt.cols = 8;
  opt.rows = 6;
  opt.square_mm = 24.0;
  opt.marker_mm = 18.0;
  opt.fix_k3 = true;
  opt.pixel_size_mm = 3.0 / 600.0;
  const auto board = cv::aruco::CharucoBoard::create(8, 6, 24.f, 18.f, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50));
  cv::Mat drawn;
  board->draw(cv::Size(8 * 60, 6 * 60), drawn, 0, 1);
  cv::Mat with_margin(drawn.rows + 120, drawn.cols + 120, CV_8UC1, cv::Scalar(255));
  drawn.copyTo(with_margin(cv::Rect(60, 60, drawn.cols, drawn.rows)));
  const sim::BoardTexture inner = sim::ImageTexture(with_margin, 0.4);
  const sim::BoardTexture texture = [inner](double x, double y) { return inner(x + 24.0, y + 24.0); };
  const sim::BoardRenderer renderer(truth);
  const auto poses = sim::VariedBoardPoses(truth, -24, -24, 8 * 24 + 24, 6 * 24 + 24, n, seed);
  Err e_id, e_flip, e_ref;
  std::vector<calibrate::LensView> views, tviews;
  int i = 0, ncorners = 0;
  for (const auto& pose : poses) {
    sim::BoardViewOptions vo;
    vo.seed = seed + static_cast<std::uint64_t>(i++);
    const cv::Mat img = Blurred(renderer.Render(pose.R_cam_board, pose.t_cam_board_mm, texture, vo));
    calibrate::LensView v;
    calibrate::DetectBoard(img, opt, &v);
    if (!v.found) continue;
    ncorners += static_cast<int>(v.image_px.size());
    std::vector<cv::Point2f> t_id, t_flip;
    for (const auto& b : v.board_mm) {
      t_id.push_back([&] { auto q = truth.Project(pose.R_cam_board * Eigen::Vector3d(b.x, b.y, 0) + pose.t_cam_board_mm); return cv::Point2f(q->x(), q->y()); }());
      t_flip.push_back([&] { auto q = truth.Project(pose.R_cam_board * Eigen::Vector3d(b.x, 144.0 - b.y, 0) + pose.t_cam_board_mm); return cv::Point2f(q->x(), q->y()); }());
    }
    e_id.Add(v.image_px, t_id);
    e_flip.Add(v.image_px, t_flip);
    // OpenCV's own interpolated corners (what DetectBoard returned before its refinement)
    std::vector<std::vector<cv::Point2f>> mk;
    std::vector<int> mid, cid;
    std::vector<cv::Point2f> raw;
    cv::aruco::detectMarkers(img, board->dictionary, mk, mid);
    cv::aruco::interpolateCornersCharuco(mk, mid, img, board, raw, cid);
    std::vector<cv::Point2f> t_raw;
    for (int id : cid) {
      const auto& b = board->chessboardCorners[static_cast<std::size_t>(id)];
      auto q = truth.Project(pose.R_cam_board * Eigen::Vector3d(b.x, b.y, 0) + pose.t_cam_board_mm);
      t_raw.emplace_back(q->x(), q->y());
    }
    e_ref.Add(raw, t_raw);
    if (!refine && raw.size() == v.image_px.size()) v.image_px = raw;
    views.push_back(v);
    calibrate::LensView vt = v;
    vt.image_px = t_id;
    tviews.push_back(vt);
  }
  std::printf("charuco: %zu views, %d corners; corner error vs truth: as-is %.4f (mean %+.4f %+.4f), y-flipped board %.4f, OpenCV raw %.4f\n",
              views.size(), ncorners, e_id.Rms(), e_id.sx / e_id.n, e_id.sy / e_id.n, e_flip.Rms(), e_ref.Rms());
  const auto res = calibrate::SolveLens(views, 640, 480, opt);
  std::printf("  predicted map sigma %.4f (modulo rotation %.4f); measured modulo rotation %.4f\n", res.map_sigma.rms_px,
              res.map_sigma.modulo_rotation_rms_px, calibrate::MapDifferenceModuloRotationRmsPx(truth, res.camera, 8));
  std::printf("  solve: rms %.4f map %.4f; true corners: map %.5f\n", res.rms_px, calibrate::MapDifferenceRmsPx(truth, res.camera, 8),
              calibrate::MapDifferenceRmsPx(truth, calibrate::SolveLens(tviews, 640, 480, opt).camera, 8));
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "charuco") return Charuco(std::atoi(argv[2]), std::strtoull(argv[3], nullptr, 10), std::atoi(argv[4]));
  if (argc > 1 && std::string(argv[1]) == "big") return Big(std::atoi(argv[2]), argc > 3 ? std::atoi(argv[3]) : 1);
  const int n = argc > 1 ? std::atoi(argv[1]) : 16;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 17;
  const int ss = argc > 3 ? std::atoi(argv[3]) : 4;
  const camera::CameraModel truth = TruthCamera();
  const int cols = 9, rows = 6;
  const double sq = 20;
  const sim::BoardRenderer renderer(truth);
  sim::BoardPoseSpread spread;
  if (argc > 8) {
    spread.tilt_min_deg = std::atof(argv[4]);
    spread.tilt_max_deg = std::atof(argv[5]);
    spread.fill_min = std::atof(argv[6]);
    spread.fill_max = std::atof(argv[7]);
    spread.aim_fraction = std::atof(argv[8]);
  }
  const auto poses = sim::VariedBoardPoses(truth, -20, -20, 180, 120, n, seed, spread);
  std::printf("%zu poses\n", poses.size());
  calibrate::LensOptions o;
  o.cols = cols;
  o.rows = rows;
  o.square_mm = sq;
  o.pixel_size_mm = 3.0 / 600.0;
  o.fix_k3 = true;
  Err e_sb, e_sub, e_q4, e_sub_t;
  std::vector<calibrate::LensView> v_sb, v_sub, v_true;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    sim::BoardViewOptions vo;
    vo.seed = seed + i;
    vo.supersample = ss;
    const cv::Mat img = Blurred(renderer.Render(poses[i].R_cam_board, poses[i].t_cam_board_mm,
                                        sim::ChessboardTexture(cols, rows, sq), vo));
    const auto truec0 = TrueCorners(truth, poses[i], cols, rows, sq);
    calibrate::LensView v;
    calibrate::DetectBoard(img, o, &v);
    if (!v.found) { std::printf("view %zu not found\n", i); continue; }
    auto truec = truec0;  // in the detector's order (SB may start from the opposite corner)
    if (cv::norm(v.image_px[0] - truec0[0]) > cv::norm(v.image_px[0] - truec0.back())) std::reverse(truec.begin(), truec.end());
    e_sb.Add(v.image_px, truec);
    v_sb.push_back(v);
    calibrate::LensOptions os = o;
    os.subpix = true;
    calibrate::LensView vs;
    calibrate::DetectBoard(img, os, &vs);
    e_sub.Add(vs.image_px, truec);
    v_sub.push_back(vs);
    // cornerSubPix started from the truth
    std::vector<cv::Point2f> c2 = truec;
    const int win = std::getenv("RK_EXP_WIN") ? std::atoi(std::getenv("RK_EXP_WIN")) : 5;
    cv::cornerSubPix(img, c2, cv::Size(win, win), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
    e_sub_t.Add(c2, truec);
    std::vector<cv::Point2f> c3 = v.image_px;
    cv::find4QuadCornerSubpix(img, c3, cv::Size(5, 5));
    e_q4.Add(c3, truec);
    calibrate::LensView vt = v;
    vt.image_px = truec0;
    vt.board_mm.clear();
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) vt.board_mm.emplace_back(static_cast<float>(c * sq), static_cast<float>(r * sq), 0.f);
    v_true.push_back(vt);
  }
  std::printf("corner error vs truth (RMS, mean x, mean y) px:\n");
  std::printf("  SB           %.4f %+.4f %+.4f\n", e_sb.Rms(), e_sb.sx / e_sb.n, e_sb.sy / e_sb.n);
  std::printf("  SB+subpix    %.4f %+.4f %+.4f\n", e_sub.Rms(), e_sub.sx / e_sub.n, e_sub.sy / e_sub.n);
  std::printf("  truth+subpix %.4f %+.4f %+.4f\n", e_sub_t.Rms(), e_sub_t.sx / e_sub_t.n, e_sub_t.sy / e_sub_t.n);
  std::printf("  SB+find4quad %.4f %+.4f %+.4f\n", e_q4.Rms(), e_q4.sx / e_q4.n, e_q4.sy / e_q4.n);
  const auto report = [&](const char* name, const std::vector<calibrate::LensView>& views, double sigma) {
    const auto res = calibrate::SolveLens(views, 640, 480, o);
    const Eigen::MatrixXd C = Crb(truth, poses, cols, rows, sq, sigma, false);
    std::printf("%-14s rms %.4f map %.4f px, mod-rot %.4f px; CRB(sigma %.4f): map %.4f px, sd cx %.3f fx %.3f; opencv sd cx %.3f fx %.3f\n",
                name, res.rms_px, calibrate::MapDifferenceRmsPx(truth, res.camera, 4),
                MapModuloRotation(truth, res.camera, 8), sigma, PredictedMap(truth, C, false, 8), std::sqrt(C(2, 2)),
                std::sqrt(C(0, 0)), res.sigma.cx_px, res.sigma.fx_px);
    std::printf("   lib: mod-rot %.4f; predicted from the solve's covariance: map %.4f mod-rot %.4f; sqrt diag cov cx %.3f fx %.3f\n",
                calibrate::MapDifferenceModuloRotationRmsPx(truth, res.camera, 8), res.map_sigma.rms_px,
                res.map_sigma.modulo_rotation_rms_px, std::sqrt(res.covariance(2, 2)), std::sqrt(res.covariance(0, 0)));
  };
  report("SB", v_sb, e_sb.Rms() / std::sqrt(2.0));
  report("SB+subpix", v_sub, e_sub.Rms() / std::sqrt(2.0));
  // truth + gaussian noise at the subpix level, several draws
  std::mt19937_64 rng(5);
  const double sig = e_sub.Rms() / std::sqrt(2.0);
  std::normal_distribution<double> nd(0, sig);
  for (int d = 0; d < 3; ++d) {
    auto vn = v_true;
    for (auto& v : vn)
      for (auto& p : v.image_px) p += cv::Point2f(static_cast<float>(nd(rng)), static_cast<float>(nd(rng)));
    report("truth+noise", vn, sig);
  }
  return 0;
}
