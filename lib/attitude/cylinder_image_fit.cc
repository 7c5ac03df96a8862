// Image-based refinement of a cylinder's pose; model and method in cylinder_image_fit.h.
#include "attitude/cylinder_image_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "numeric/levenberg_marquardt.h"
#include "target/cylinder.h"
#include "target/silhouette_image.h"

namespace rk::attitude {
namespace {

constexpr int kNonlinear = 7;  // tail centre E, N, U; yaw; pitch; nose-cone length; PSF σ
constexpr int kLinear = 5;     // sky s0, s1, s2; body b0, b1
using Params = Eigen::Matrix<double, kNonlinear, 1>;

constexpr double kMinSigmaPx = 0.05, kMaxSigmaPx = 5.0;
constexpr double kMaxAxisStepRad = 0.0175;

// Everything a residual evaluation needs that does not change during the fit.
class Problem {
 public:
  // `active` (CV_8U, roi.size()): the pixels fitted (non-zero), the rest of the window only feeds the blur.
  Problem(const cv::Mat& window, const cv::Mat& active, cv::Rect roi, const camera::CameraModel& cam, double az,
          double el, const target::CylinderShape& target, int rim_samples, int kernel_size,
          const Eigen::Vector3d& origin, const Eigen::Matrix3d& basis)
      : roi_(roi),
        cam_(cam),
        az_(az),
        el_(el),
        target_(target),
        rim_samples_(rim_samples),
        kernel_size_(kernel_size),
        origin_(origin),
        basis_(basis) {
    const Eigen::Index n = cv::countNonZero(active);
    data_.resize(n);
    xs_.resize(n);
    ys_.resize(n);
    at_.resize(static_cast<std::size_t>(n));
    Eigen::Index k = 0;
    for (int i = 0; i < roi.height; ++i) {
      const double* row = window.ptr<double>(i);
      const std::uint8_t* on = active.ptr<std::uint8_t>(i);
      for (int j = 0; j < roi.width; ++j) {
        if (!on[j]) continue;
        data_(k) = row[j];
        xs_(k) = roi.width > 1 ? 2.0 * j / (roi.width - 1) - 1.0 : 0.0;
        ys_(k) = roi.height > 1 ? 2.0 * i / (roi.height - 1) - 1.0 : 0.0;
        at_[static_cast<std::size_t>(k)] = {i, j};
        ++k;
      }
    }
    sw_ = Eigen::VectorXd::Ones(data_.size());
    wdata_ = data_;
    a_.resize(n);
    v_.resize(n);
  }

  Eigen::Index size() const { return data_.size(); }

  // Residual data − model with the linear parameters at their least-squares values; false if the outline
  // cannot be projected.
  bool Residual(const Params& p, Eigen::VectorXd* r, Eigen::Matrix<double, kLinear, 1>* lin = nullptr) {
    ++evaluations_;
    target::CylinderPose pose;
    pose.tail_centre_enu = TailCentre(p);
    pose.yaw_rad = p(3);
    pose.pitch_rad = p(4);
    target::CylinderShape shape = target_;
    shape.nose_length_m = std::clamp(p(5), 0.02 * target_.length_m, 0.98 * target_.length_m);
    const std::vector<Eigen::Vector2d> poly =
        target::SilhouettePolygon(cam_, pose, shape, az_, el_, rim_samples_);
    if (poly.size() < 3) return false;
    // Coverage blurred in single precision (half the blur's cost; its rounding, ~1e-7, is far below the
    // 0.02-px difference steps' change of α, ~1e-2).
    const cv::Mat cov = target::RasterizeConvexPolygon(poly, roi_);
    const double sigma = std::clamp(p(6), kMinSigmaPx, kMaxSigmaPx);
    const cv::Mat g = cv::getGaussianKernel(kernel_size_, sigma, CV_32F);
    cv::sepFilter2D(cov, alpha_, CV_32F, g, g, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);

    // Image axis and tail half-width for the body shading term.
    const target::SilhouettePoints3d pts = target::SilhouettePointsOf(pose, shape);
    const auto tail1 = cam_.ProjectEnu(pts.tail1, az_, el_), tail2 = cam_.ProjectEnu(pts.tail2, az_, el_),
               nose = cam_.ProjectEnu(pts.nose, az_, el_);
    if (!tail1 || !tail2 || !nose) return false;
    const Eigen::Vector2d tail = 0.5 * (*tail1 + *tail2);
    Eigen::Vector2d dir = *nose - tail;
    dir = dir.norm() > 0 ? dir.normalized() : Eigen::Vector2d(1, 0);
    const Eigen::Vector2d nrm(-dir.y(), dir.x());
    const double w = std::max(0.5 * (*tail1 - *tail2).norm(), 1e-6);

    // Weighted least squares of the linear parameters, their normal equations accumulated pixel by pixel:
    // design row sw · (1 − α, (1 − α) x̃, (1 − α) ỹ, α, α v).
    Eigen::Matrix<double, kLinear, kLinear> N = Eigen::Matrix<double, kLinear, kLinear>::Zero();
    Eigen::Matrix<double, kLinear, 1> b = Eigen::Matrix<double, kLinear, 1>::Zero();
    const Eigen::Vector2d nw = nrm / w;
    const double v0 = (Eigen::Vector2d(roi_.x, roi_.y) - tail).dot(nw);
    for (Eigen::Index k = 0; k < size(); ++k) {
      const auto [i, j] = at_[static_cast<std::size_t>(k)];
      a_(k) = alpha_.at<float>(i, j);
      v_(k) = std::clamp(v0 + j * nw.x() + i * nw.y(), -1.0, 1.0);
      const Eigen::Matrix<double, kLinear, 1> c = Row(k);
      for (int u = 0; u < kLinear; ++u) {
        for (int q = u; q < kLinear; ++q) N(u, q) += c(u) * c(q);  // upper triangle
      }
      b += c * wdata_(k);
    }
    const Eigen::Matrix<double, kLinear, 1> x = N.template selfadjointView<Eigen::Upper>().ldlt().solve(b);
    if (!x.allFinite()) return false;
    r->resize(size());
    for (Eigen::Index k = 0; k < size(); ++k) (*r)(k) = wdata_(k) - Row(k).dot(x);
    if (lin) *lin = x;
    return true;
  }

  // Weights 1/(c0 + c1 · model) for the noise variance of each pixel (read + shot noise), from the model
  // values `model` (DN).
  void SetWeights(const Eigen::VectorXd& model, double c0, double c1) {
    sw_ = (c0 + c1 * model.array()).max(1e-6 * c0).rsqrt().matrix();
    wdata_ = sw_.cwiseProduct(data_);
  }
  // Unwhitened model values for whitened residuals r.
  Eigen::VectorXd Model(const Eigen::VectorXd& r) const { return data_ - r.cwiseQuotient(sw_); }
  Eigen::VectorXd Unwhiten(const Eigen::VectorXd& r) const { return r.cwiseQuotient(sw_); }

  int evaluations() const { return evaluations_; }
  Eigen::Vector3d TailCentre(const Params& p) const { return origin_ + basis_ * p.head<3>(); }

 private:
  // Whitened design row of pixel k at the last model's α and shading coordinate.
  Eigen::Matrix<double, kLinear, 1> Row(Eigen::Index k) const {
    const double a = a_(k), s = 1.0 - a;
    Eigen::Matrix<double, kLinear, 1> c;
    c << s, s * xs_(k), s * ys_(k), a, a * v_(k);
    return sw_(k) * c;
  }

  cv::Rect roi_;
  const camera::CameraModel& cam_;
  double az_, el_;
  target::CylinderShape target_;
  int rim_samples_, kernel_size_;
  Eigen::Vector3d origin_;
  Eigen::Matrix3d basis_;
  Eigen::VectorXd data_, xs_, ys_, sw_, wdata_, a_, v_;
  cv::Mat alpha_;                         // the last model's blurred coverage (CV_32F, the window)
  std::vector<std::pair<int, int>> at_;  // (row, column) in the window of each fitted pixel
  int evaluations_ = 0;
};

// One Levenberg–Marquardt pass of the fit (numeric/levenberg_marquardt.h's Problem): parameters p in units
// of the steps h, Jacobian by forward differences (half the model evaluations of central ones; the steps move
// the outline by 0.02 px, so the O(h) error is ~1 % of a column and LM's minimum, set by the residual, is
// the same), the axis-step cap and the PSF-σ bounds on a candidate.
struct LmPass {
  Problem& prob;
  const Params& h;
  Params& p;
  Eigen::VectorXd& r;  // residuals at p
  Eigen::MatrixXd J;   // last Jacobian, per step h(c): scaled units
  double step_tol = 0.0, drop_tol = 0.0;
  Params q = Params::Zero();
  Eigen::VectorXd rq = Eigen::VectorXd();  // residuals at q
  Eigen::VectorXd rp = Eigen::VectorXd();  // residuals at a difference step

  bool Linearize(Eigen::Matrix<double, kNonlinear, kNonlinear>* A, Params* g) {
    for (int c = 0; c < kNonlinear; ++c) {
      Params pp = p;
      pp(c) += h(c);
      if (!prob.Residual(pp, &rp)) return false;
      J.col(c) = rp - r;
    }
    A->noalias() = J.transpose() * J;
    *g = J.transpose() * r;
    return true;
  }
  bool TryStep(const Params& du, double* cost) {
    q = p + du.cwiseProduct(h);
    // A step turning the axis by more than 1° leaves the start's basin (the mirror minimum is a few
    // degrees away near side-on): damp more instead.
    if (std::abs(q(3) - p(3)) > kMaxAxisStepRad || std::abs(q(4) - p(4)) > kMaxAxisStepRad) return false;
    q(6) = std::clamp(q(6), kMinSigmaPx, kMaxSigmaPx);
    if (!prob.Residual(q, &rq)) return false;
    *cost = rq.squaredNorm();
    return true;
  }
  void Accept() {
    p = q;
    r = rq;
  }
  // At the minimum to the tolerance: the Gauss–Newton step's predicted decrease gᵀA⁻¹g is below drop_tol ×
  // the residual variance (the start of a warm fit often is: no step is tried).
  bool AtMinimum(const Eigen::Matrix<double, kNonlinear, kNonlinear>& A, const Params& g, double cost) const {
    const Params step = A.ldlt().solve(g);
    const double decrease = g.dot(step);
    return step.allFinite() && decrease <= drop_tol * cost / static_cast<double>(prob.size());
  }
  bool Converged(const Params& du, double cost_before, double cost_after) const {
    const double drop = cost_before - cost_after;
    return du.cwiseAbs().maxCoeff() < step_tol ||
           drop <= drop_tol * cost_after / static_cast<double>(prob.size());
  }
};

// The fit's window: the initial outline (nose cone at 1/4 of the length) grown by `margin`, inside the frame;
// false when the outline itself leaves the frame. The pixels fitted (`active`, CV_8U over the window): those
// within `margin` of the initial outline, inside or out — the rest of the box carries nothing about the pose
// and only the sky plane's far corners (a 298-px target on a diagonal: 16 k of 55 k pixels).
bool InitialWindow(const cv::Mat& frame, const camera::CameraModel& cam, double az_rad, double el_rad,
                   const target::CylinderShape& target, const Eigen::Vector3d& tail_centre_enu, double yaw_rad,
                   double pitch_rad, int margin, cv::Rect* roi, cv::Mat* active) {
  target::CylinderPose pose0;
  pose0.tail_centre_enu = tail_centre_enu;
  pose0.yaw_rad = yaw_rad;
  pose0.pitch_rad = pitch_rad;
  target::CylinderShape shape0 = target;
  shape0.nose_length_m = 0.25 * target.length_m;
  const std::vector<Eigen::Vector2d> poly0 = target::SilhouettePolygon(cam, pose0, shape0, az_rad, el_rad, 64);
  if (poly0.size() < 3) return false;
  const cv::Rect outline = target::PolygonWindow(poly0, 0);
  if (outline.x < 0 || outline.y < 0 || outline.br().x > frame.cols || outline.br().y > frame.rows) return false;
  *roi = target::PolygonWindow(poly0, margin);
  *roi &= cv::Rect(0, 0, frame.cols, frame.rows);
  const cv::Mat cov = target::RasterizeConvexPolygon(poly0, *roi);
  cv::Mat inside = cov > 0.0f;
  cv::dilate(inside, *active, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * margin + 1, 2 * margin + 1)),
             cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  return true;
}

// Tail centre as offsets from its start along two directions across the line of sight and one along it: the
// range is seen far more weakly (through the image scale) than the lateral position, and with its own
// coordinate Marquardt's scaling damps it by its own curvature (in ENU coordinates LM crept along the
// range–yaw valley for ten iterations).
Eigen::Matrix3d AlongSightBasis(const Eigen::Vector3d& tail_centre_enu) {
  const Eigen::Vector3d los = tail_centre_enu.normalized();
  Eigen::Vector3d across = los.cross(Eigen::Vector3d::UnitZ());
  if (across.norm() < 1e-6) across = los.cross(Eigen::Vector3d::UnitX());
  across.normalize();
  Eigen::Matrix3d basis;
  basis << across, los.cross(across), los;
  return basis;
}

// Nose-cone length: best of a coarse scan from `start` (the cost is flat in it far from the truth only near
// the tip). Returns the cost (infinite if no model could be evaluated), the parameters in p, residuals in r;
// `start` is a copy, so p may be the caller's start.
double ScanNoseLength(Problem& prob, const Params start, double length_m, Params* p, Eigen::VectorXd* r) {
  Eigen::VectorXd rt;
  double cost = std::numeric_limits<double>::infinity();
  for (double frac : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}) {
    Params q = start;
    q(5) = frac * length_m;
    if (prob.Residual(q, &rt) && rt.squaredNorm() < cost) {
      cost = rt.squaredNorm();
      *p = q;
      *r = rt;
    }
  }
  return cost;
}

// The noise variance per pixel modelled as c0 + c1 · signal (read + shot noise: the sky and the body differ
// by their shot noise), fitted to the squared (unwhitened) residuals r; a constant where the fit is unusable.
Eigen::Vector2d NoiseModel(const Problem& prob, const Eigen::VectorXd& r) {
  const Eigen::VectorXd m = prob.Model(r), u2 = prob.Unwhiten(r).array().square().matrix();
  Eigen::Matrix2d Nv;
  Nv << static_cast<double>(m.size()), m.sum(), m.sum(), m.squaredNorm();
  const Eigen::Vector2d c = Nv.ldlt().solve(Eigen::Vector2d(u2.sum(), m.dot(u2)));
  const double mean = u2.mean();
  const bool usable = c.allFinite() && c(1) >= 0.0 && c(0) > 0.05 * mean;
  return usable ? c : Eigen::Vector2d(mean, 0.0);
}

// The noise model of the residuals r of the unweighted pass becomes the weights.
void WeightByNoiseModel(Problem& prob, const Eigen::VectorXd& r) {
  const Eigen::Vector2d c = NoiseModel(prob, r);
  prob.SetWeights(prob.Model(r), c(0), c(1));
}

// The start of the fit: a warm start's nuisance parameters and weights (the previous frame's noise model
// at the start's model values), else the best nose-cone length of a coarse scan, unweighted. Returns the
// cost (infinite if no model could be evaluated), the residuals in r.
double StartFit(Problem& prob, const CylinderImageFitStart* start, double length_m, Params* p, Eigen::VectorXd* r) {
  if (!start) return ScanNoseLength(prob, *p, length_m, p, r);
  (*p)(5) = start->nose_cone_length_m;
  (*p)(6) = std::clamp(start->psf_sigma_px, kMinSigmaPx, kMaxSigmaPx);
  if (!prob.Residual(*p, r)) return std::numeric_limits<double>::infinity();
  prob.SetWeights(prob.Model(*r), start->noise_c0, start->noise_c1);
  if (!prob.Residual(*p, r)) return std::numeric_limits<double>::infinity();
  return r->squaredNorm();
}

}  // namespace

const io::OptionTable<CylinderImageFitOptions>& CylinderImageFitOptions::Table() {
  using O = CylinderImageFitOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--fit-psf-sigma", &O::initial_psf_sigma_px, "px", io::Bounds::LeftOpen(0, 5),
                "Image fit: starting value of the optics blur sigma (px; fitted)")
          .Integer("--fit-max-iterations", &O::max_iterations, "", io::Bounds::AtLeast(1),
                   "Image fit: Levenberg-Marquardt iteration limit");
  return table;
}

bool CylinderImageFitOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (rim_samples < 16 || !(margin_px >= 1.0 && margin_px <= 100.0)) {
    *why = "the image fit needs rim_samples >= 16 and a margin in [1, 100] px";
    return false;
  }
  return true;
}

const char* CylinderImageFitStatusName(CylinderImageFitStatus s) {
  switch (s) {
    case CylinderImageFitStatus::kConverged:
      return "converged";
    case CylinderImageFitStatus::kNotConverged:
      return "not_converged";
    case CylinderImageFitStatus::kFailed:
      return "failed";
  }
  return "failed";
}

CylinderImageFitResult FitCylinderImage(const cv::Mat& frame, const camera::CameraModel& cam, double az_rad,
                                        double el_rad, const target::CylinderShape& target,
                                        const Eigen::Vector3d& tail_centre_enu, double yaw_rad,
                                        double pitch_rad, const CylinderImageFitOptions& opt,
                                        const CylinderImageFitStart* start) {
  CylinderImageFitResult out;
  if (frame.empty() || frame.channels() != 1 || (frame.depth() != CV_8U && frame.depth() != CV_16U))
    return out;
  if (start && !(start->nose_cone_length_m > 0.0 && start->psf_sigma_px > 0.0 && start->noise_c0 > 0.0 &&
                 start->noise_c1 >= 0.0)) {
    start = nullptr;  // not a usable start: a cold fit
  }

  // Window: the initial outline (nose cone at 1/4 of the length) + 4σ_max + margin, inside the frame.
  const double sigma_cap = std::max(2.0 * opt.initial_psf_sigma_px, 1.5);
  const int margin = static_cast<int>(std::ceil(4.0 * sigma_cap + opt.margin_px));
  cv::Rect roi;
  cv::Mat active;
  if (!InitialWindow(frame, cam, az_rad, el_rad, target, tail_centre_enu, yaw_rad, pitch_rad, margin, &roi,
                     &active)) {
    return out;
  }
  cv::Mat window;
  frame(roi).convertTo(window, CV_64F);
  const int kernel = 2 * static_cast<int>(std::ceil(4.0 * sigma_cap)) + 1;
  const Eigen::Matrix3d basis = AlongSightBasis(tail_centre_enu);
  Problem prob(window, active, roi, cam, az_rad, el_rad, target, opt.rim_samples, kernel, tail_centre_enu, basis);

  // Steps that move the outline by ~0.02 px: the forward-difference steps and the parameter scaling.
  const double R = tail_centre_enu.norm(), f = cam.fx();
  Params h;
  h << 0.02 * R / f, 0.02 * R / f, 0.02 * R * R / (f * target.length_m), 0.02 * R / (f * target.length_m),
      0.02 * R / (f * target.length_m), 0.02 * R / f, 0.02;
  Params p;
  p << 0.0, 0.0, 0.0, yaw_rad, pitch_rad, 0.25 * target.length_m, opt.initial_psf_sigma_px;

  // Nose-cone length: best of a coarse scan (or the previous frame's, with its weights).
  Eigen::VectorXd r;
  double cost = StartFit(prob, start, target.length_m, &p, &r);
  if (!std::isfinite(cost)) return out;

  // Levenberg–Marquardt from p (numeric::LevenbergMarquardt with the damping below); false if a model
  // cannot be evaluated. Converged: a step moves the outline by less than step_tol × 0.02 px, or lowers the
  // cost by less than drop_tol × the residual variance (a parameter change of ~sqrt(drop_tol) of its σ; the
  // range along the line of sight is too weakly seen for a step test alone).
  LmPass lm{prob, h, p, r, Eigen::MatrixXd(prob.size(), kNonlinear)};
  Eigen::Matrix<double, kNonlinear, kNonlinear> A;
  Params g;
  int it = 0;
  // λ starts small: the start is within a few σ (the previous frame's axis, the three points' position) and
  // the problem is ill-conditioned along the range–yaw valley, where a large λ made LM creep (8 iterations
  // for a warm start at λ0 = 1e-2, 2–3 at 1e-5); the axis-step cap guards the far steps.
  const numeric::LmDamping damping{.initial = 1e-5, .diagonal_floor = 0.0, .increase = 8.0,
                                   .decrease = 0.25, .min = 1e-12, .max_tries = 10,
                                   .accept_equal_cost = true, .linearize_at_solution = false};
  const auto levenberg_marquardt = [&](int max_iterations, double step_tol, double drop_tol,
                                       bool* converged) {
    lm.step_tol = step_tol;
    lm.drop_tol = drop_tol;
    if (!lm.Linearize(&A, &g)) return false;
    const numeric::LmSummary summary =
        numeric::LevenbergMarquardt<kNonlinear>(lm, cost, damping, max_iterations, &A, &g);
    it += summary.iterations;
    cost = summary.cost;
    *converged = summary.status == numeric::LmStatus::kConverged;
    return summary.status == numeric::LmStatus::kConverged ||
           summary.status == numeric::LmStatus::kMaxIterations;
  };

  // Pass 1 unweighted; then the noise variance per pixel modelled as c0 + c1 · signal (read + shot noise:
  // the sky and the body differ by their shot noise) from the squared residuals, and pass 2 weighted by it —
  // the maximum-likelihood fit for that noise.
  // Pass 1 stops early (the weights need only a near solution: 0.1 σ), pass 2 at ≈ 0.03 σ (a predicted or actual drop below 1e-3 of the residual variance; below that the forward-difference gradient is at its rounding). A warm start
  // has its weights already: pass 2 only.
  bool converged = false;
  if (!start) {
    if (!levenberg_marquardt(opt.max_iterations, 1e-2, 1e-2, &converged)) return out;
    WeightByNoiseModel(prob, r);
    if (!prob.Residual(p, &r)) return out;
    cost = r.squaredNorm();
  }
  if (!levenberg_marquardt(opt.max_iterations, 1e-3, 1e-3, &converged)) return out;

  // Final covariance from the last Jacobian (at the previous iterate: within 2e-5 px of the solution).
  const Eigen::Index dof = prob.size() - kNonlinear - kLinear;
  if (dof <= 0) return out;
  const double s2 = cost / static_cast<double>(dof);
  const Eigen::Matrix<double, kNonlinear, kNonlinear> Ai = A.inverse();
  if (!Ai.allFinite()) return out;
  Eigen::Matrix<double, kLinear, 1> lin;
  if (!prob.Residual(p, &r, &lin)) return out;

  out.status = converged ? CylinderImageFitStatus::kConverged : CylinderImageFitStatus::kNotConverged;
  out.tail_centre_enu = prob.TailCentre(p);
  out.yaw_rad = geo::WrapTwoPi(p(3));
  out.pitch_rad = p(4);
  out.axis_enu = geo::DirectionFromAzEl(p(3), p(4));
  out.nose_cone_length_m = p(5);
  out.psf_sigma_px = p(6);
  out.sigma_yaw_rad = std::sqrt(s2 * Ai(3, 3)) * h(3);
  out.sigma_pitch_rad = std::sqrt(s2 * Ai(4, 4)) * h(4);
  out.rms_dn = std::sqrt(prob.Unwhiten(r).squaredNorm() / static_cast<double>(prob.size()));
  out.contrast_dn = lin(3) - lin(0);
  out.iterations = it;
  out.evaluations = prob.evaluations();
  out.pixels = static_cast<int>(prob.size());
  const Eigen::Vector2d noise = NoiseModel(prob, r);
  out.noise_c0 = noise(0);
  out.noise_c1 = noise(1);
  return out;
}

}  // namespace rk::attitude
