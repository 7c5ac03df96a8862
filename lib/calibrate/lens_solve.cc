// SolveLens: cv::calibrateCamera with OpenCV's 1σ, rejection of views far above the median RMS, the
// calibrated camera model and its JSON.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "calibrate/lens_calibration.h"
#include "io/error.h"

namespace rk::calibrate {
namespace {

struct LensSolve {
  cv::Mat K, dist, std_intrinsics;
  std::vector<cv::Mat> rvecs, tvecs;  // per used view
  std::vector<double> view_rms;  // per used view, in the order of `used`
  double rms_px = 0.0;
};

LensSolve RunCalibrateCamera(const std::vector<LensView>& views, const std::vector<std::size_t>& used, cv::Size size,
                             const LensOptions& opt) {
  std::vector<std::vector<cv::Point3f>> obj;
  std::vector<std::vector<cv::Point2f>> img;
  for (std::size_t i : used) {
    obj.push_back(views[i].board_mm);
    img.push_back(views[i].image_px);
  }
  LensSolve s;
  s.K = cv::Mat::eye(3, 3, CV_64F);  // fx/fy = 1 is the ratio --fix-aspect keeps
  s.dist = cv::Mat::zeros(5, 1, CV_64F);
  cv::Mat std_extrinsics, per_view;
  const cv::TermCriteria crit(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12);
  try {
    s.rms_px = cv::calibrateCamera(obj, img, size, s.K, s.dist, s.rvecs, s.tvecs, s.std_intrinsics, std_extrinsics,
                                   per_view, opt.OpenCvFlags(), crit);
  } catch (const cv::Exception& e) {
    throw ProcessingError("calibration failed (OpenCV: " + e.err + ")");
  }
  if (!std::isfinite(s.rms_px) || !cv::checkRange(s.K) || !cv::checkRange(s.dist)) {
    throw ProcessingError("calibration did not converge (non-finite result)");
  }
  for (int i = 0; i < per_view.rows; ++i) s.view_rms.push_back(per_view.at<double>(i));
  return s;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string Fixed(double x, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << x;
  return s.str();
}

// Throws ProcessingError when too few views are usable, with what became of the others.
void RequireViews(const std::vector<LensView>& views, std::size_t usable, const LensOptions& opt) {
  if (static_cast<int>(usable) >= opt.min_views) return;
  std::size_t no_board = 0;
  for (const auto& v : views) no_board += v.found ? 0 : 1;
  const std::size_t rejected = views.size() - no_board - usable;
  if (usable == 0 && rejected == 0) {
    throw ProcessingError("no " + BoardKindName(opt.board) + " of " + std::to_string(opt.cols) + "x" +
                          std::to_string(opt.rows) + " found in any of the " + std::to_string(views.size()) +
                          " images (check --board, --cols, --rows)");
  }
  throw ProcessingError("only " + std::to_string(usable) + " usable views of " + std::to_string(views.size()) +
                        " (" + std::to_string(no_board) + " without a board, " + std::to_string(rejected) +
                        " rejected); at least " + std::to_string(opt.min_views) + " needed (--min-views)");
}

// Residuals (detected − reprojected) and RMS of every found view under the final model.
void ComputeResiduals(std::vector<LensView>* views, const cv::Mat& K, const cv::Mat& dist) {
  for (auto& v : *views) {
    if (!v.found) continue;
    cv::Mat rvec, tvec;
    cv::solvePnP(v.board_mm, v.image_px, K, dist, rvec, tvec, false, cv::SOLVEPNP_ITERATIVE);
    std::vector<cv::Point2f> proj;
    cv::projectPoints(v.board_mm, rvec, tvec, K, dist, proj);
    v.residual_px.resize(proj.size());
    double ss = 0;
    for (std::size_t k = 0; k < proj.size(); ++k) {
      v.residual_px[k] = v.image_px[k] - proj[k];
      ss += v.residual_px[k].dot(v.residual_px[k]);
    }
    const double rms = std::sqrt(ss / static_cast<double>(std::max<std::size_t>(proj.size(), 1)));
    if (!v.used) v.rms_px = rms;  // used views keep calibrateCamera's own figure
  }
}

camera::CameraModel ModelFrom(const LensSolve& s, int w, int h, const LensOptions& opt) {
  camera::CameraModel cam;
  cam.width_px = w;
  cam.height_px = h;
  const double fx = s.K.at<double>(0, 0), fy = s.K.at<double>(1, 1);
  cam.focal_length_mm = fx * opt.pixel_size_mm;
  cam.pixel_size_mm = {opt.pixel_size_mm, cam.focal_length_mm / fy};
  cam.principal_point_px = {s.K.at<double>(0, 2), s.K.at<double>(1, 2)};
  for (int i = 0; i < 5; ++i) cam.distortion[static_cast<std::size_t>(i)] = s.dist.at<double>(i);
  return cam;
}

// The free intrinsics as columns of T (9 × p): (fx, fy, cx, cy, k1, k2, p1, p2, k3) = T · free, to first order.
// --fix-aspect keeps fx = a · fy (OpenCV estimates fy; a = fx / fy of the solution).
Eigen::MatrixXd FreeIntrinsics(const LensOptions& opt, double aspect) {
  std::vector<Eigen::Matrix<double, 9, 1>> cols;
  const auto unit = [](int i) { return Eigen::Matrix<double, 9, 1>::Unit(i); };
  if (opt.fix_aspect) {
    cols.push_back(aspect * unit(0) + unit(1));
  } else {
    cols.push_back(unit(0));
    cols.push_back(unit(1));
  }
  if (!opt.fix_principal_point) cols.insert(cols.end(), {unit(2), unit(3)});
  cols.insert(cols.end(), {unit(4), unit(5)});
  if (!opt.zero_tangent) cols.insert(cols.end(), {unit(6), unit(7)});
  if (!opt.fix_k3) cols.push_back(unit(8));
  Eigen::MatrixXd T(9, static_cast<Eigen::Index>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k) T.col(static_cast<Eigen::Index>(k)) = cols[k];
  return T;
}

// Covariance of the intrinsics with every view's pose marginalised: σ² (A − Σ Bᵢ Cᵢ⁻¹ Bᵢᵀ)⁻¹ over the Gauss–Newton
// normal matrix [[A, B], [Bᵀ, C]] of calibrateCamera's problem at its solution (cv::projectPoints' Jacobians),
// σ² = Σr² / (2N − parameters) over the 2N residual components. (calibrateCamera's own stdDeviationsIntrinsics
// divide by N − parameters, N the number of points, and so overstate every 1σ by about √2.)
Eigen::Matrix<double, 9, 9> IntrinsicCovariance(const std::vector<LensView>& views, const std::vector<std::size_t>& used,
                                                const LensSolve& s, const LensOptions& opt) {
  const Eigen::MatrixXd T = FreeIntrinsics(opt, s.K.at<double>(0, 0) / s.K.at<double>(1, 1));
  const Eigen::Index p = T.cols();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p, p);
  double ss = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < used.size(); ++k) {
    const LensView& v = views[used[k]];
    std::vector<cv::Point2f> proj;
    cv::Mat jac;  // 2N × (3 rotation, 3 translation, fx, fy, cx, cy, k1, k2, p1, p2, k3)
    cv::projectPoints(v.board_mm, s.rvecs[k], s.tvecs[k], s.K, s.dist, proj, jac);
    Eigen::MatrixXd J(jac.rows, 15);
    for (int r = 0; r < jac.rows; ++r) {
      for (int c = 0; c < 15; ++c) J(r, c) = jac.at<double>(r, c);
    }
    const Eigen::MatrixXd Ji = J.rightCols(9) * T;
    const Eigen::MatrixXd Jp = J.leftCols(6);
    const Eigen::Matrix<double, 6, 6> C = Jp.transpose() * Jp;
    const Eigen::MatrixXd B = Ji.transpose() * Jp;
    A += Ji.transpose() * Ji - B * C.ldlt().solve(B.transpose());
    for (std::size_t q = 0; q < proj.size(); ++q) {
      const cv::Point2f d = v.image_px[q] - proj[q];
      ss += d.dot(d);
    }
    n += proj.size();
  }
  const double dof = 2.0 * static_cast<double>(n) - static_cast<double>(p + 6 * static_cast<Eigen::Index>(used.size()));
  const double s2 = dof > 0 ? ss / dof : 0.0;
  Eigen::Matrix<double, 9, 9> cov = T * (s2 * A.inverse()) * T.transpose();
  return 0.5 * (cov + cov.transpose());
}

// The 1σ: roots of the covariance's diagonal (0 for a fixed term).
LensSigma SigmaFrom(const Eigen::Matrix<double, 9, 9>& cov) {
  const auto sd = [&](int i) { return std::sqrt(std::max(0.0, cov(i, i))); };
  LensSigma g;
  g.fx_px = sd(0);
  g.fy_px = sd(1);
  g.cx_px = sd(2);
  g.cy_px = sd(3);
  for (int i = 0; i < 5; ++i) g.distortion[static_cast<std::size_t>(i)] = sd(4 + i);
  return g;
}

// Warnings for parameters whose 1σ is large against their value (kSigmaWarnRatio, kDistortionSigmaWarnPx).
std::vector<std::string> SigmaWarnings(const camera::CameraModel& cam, const LensSigma& g) {
  std::vector<std::string> w;
  const auto rel = [&](const std::string& name, double value, double sigma) {
    if (sigma > kSigmaWarnRatio * std::abs(value)) {
      w.push_back(name + " is poorly determined: " + Fixed(value, 2) + " +- " + Fixed(sigma, 2) +
                  " px (1 sigma); tilt the board more and fill the image corners");
    }
  };
  rel("fx", cam.fx(), g.fx_px);
  rel("fy", cam.fy(), g.fy_px);
  rel("cx", cam.principal_point_px.x(), g.cx_px);
  rel("cy", cam.principal_point_px.y(), g.cy_px);
  // A distortion coefficient not distinguishable from 0 (1σ > |value|) whose 1σ still moves the image corner by
  // more than kDistortionSigmaWarnPx. (Each coefficient's own σ: k1, k2, k3 are strongly correlated, so their
  // σ taken alone overstate the uncertainty of the pixel map; a coefficient lost in its σ is the useful sign.)
  // Displacement at the image corner per unit coefficient: r³ f, r⁵ f, ≈3 r² f, ≈3 r² f, r⁷ f.
  const double xn = 0.5 * cam.width_px / cam.fx(), yn = 0.5 * cam.height_px / cam.fy();
  const double r2 = xn * xn + yn * yn, r = std::sqrt(r2), f = cam.fx();
  const double effect[5] = {r2 * r * f, r2 * r2 * r * f, 3 * r2 * f, 3 * r2 * f, r2 * r2 * r2 * r * f};
  const char* names[5] = {"k1", "k2", "p1", "p2", "k3"};
  const char* fix[5] = {"", "", " (--zero-tangent)", " (--zero-tangent)", " (--fix-k3)"};
  for (std::size_t i = 0; i < 5; ++i) {
    const double value = cam.distortion[i], sigma = g.distortion[i], px = sigma * effect[i];
    if (sigma > std::abs(value) && px > kDistortionSigmaWarnPx) {
      w.push_back(std::string(names[i]) + " = " + Fixed(value, 5) + " +- " + Fixed(sigma, 5) +
                  " (1 sigma) is not distinguishable from 0 and its 1 sigma moves the image corner by " + Fixed(px, 2) +
                  " px: fix it" + fix[i] + " or add views with the board in the image corners");
    }
  }
  return w;
}

}  // namespace

LensResult SolveLens(std::vector<LensView> views, int width_px, int height_px, const LensOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < views.size(); ++i) {
    views[i].used = views[i].found;
    if (views[i].found) used.push_back(i);
  }
  RequireViews(views, used.size(), opt);
  LensResult res;
  LensSolve s;
  while (true) {
    s = RunCalibrateCamera(views, used, cv::Size(width_px, height_px), opt);
    ++res.solves;
    const double limit = std::max(opt.reject_ratio * Median(s.view_rms), kRejectFloorPx);
    const double median = Median(s.view_rms);
    std::vector<std::size_t> keep;
    for (std::size_t k = 0; k < used.size(); ++k) {
      LensView& v = views[used[k]];
      v.rms_px = s.view_rms[k];
      if (s.view_rms[k] > limit) {
        v.used = false;
        v.reason = "rms " + Fixed(s.view_rms[k], 3) + " px > " + Fixed(opt.reject_ratio, 1) + " x median " +
                   Fixed(median, 3) + " px";
      } else {
        keep.push_back(used[k]);
      }
    }
    if (keep.size() == used.size()) break;
    used = keep;
    RequireViews(views, used.size(), opt);
  }
  res.width_px = width_px;
  res.height_px = height_px;
  res.rms_px = s.rms_px;
  res.camera = ModelFrom(s, width_px, height_px, opt);
  res.covariance = IntrinsicCovariance(views, used, s, opt);
  res.sigma = SigmaFrom(res.covariance);
  res.map_sigma = PredictedMapSigma(res.camera, res.covariance, std::max(1, std::max(width_px, height_px) / 64));
  ComputeResiduals(&views, s.K, s.dist);
  res.views = std::move(views);
  res.warnings = SigmaWarnings(res.camera, res.sigma);
  res.solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

int LensResult::ViewsUsed() const {
  return static_cast<int>(std::count_if(views.begin(), views.end(), [](const LensView& v) { return v.used; }));
}
int LensResult::ViewsWithoutBoard() const {
  return static_cast<int>(std::count_if(views.begin(), views.end(), [](const LensView& v) { return !v.found; }));
}
int LensResult::ViewsRejected() const {
  return static_cast<int>(views.size()) - ViewsUsed() - ViewsWithoutBoard();
}

}  // namespace rk::calibrate
