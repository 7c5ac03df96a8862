// Rendering of the points scene (sim/points_scene.h): the sky gradient over the whole frame, then, in the
// target's region only, the blurred silhouette and the analytic markers, averaged over the sub-exposures;
// clouds in front; noise and quantisation.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "sim/points_scene.h"
#include "sim/sim_common.h"

namespace rk::sim {
namespace points_detail {

// Grey levels (8-bit DN).
constexpr double kSkyTopDn = 170, kSkyBottomDn = 215, kBodyDn = 45;
constexpr double kQuadDarkDn = 12, kQuadLightDn = 235;
// The highlight stays inside the disc: at the rim it adds < 0.1 DN, so the rim alone decides the centre.
constexpr double kDiscDn = 160, kHighlightDn = 70, kHighlightSigmaPx = 1.2, kHighlightOffset = 0.35;
constexpr double kLampDn = 180, kDarkDepthDn = 150, kTextureMeanDn = 110, kCloudDn = 235;
constexpr double kPlateMarginPx = 6.0;  // the look-alike's dark plate reaches this far past its checker (body px)
constexpr double kBlurStepPx = 0.25;    // auto blur steps: largest motion between two sub-exposures (px)
constexpr int kDeepScale = 16;          // 16-bit frames: 12-bit DN = 8-bit DN x 16

// The silhouette (body px at scale 1): nose at +x, wings to ±y; the upper half, mirrored for the lower.
constexpr double kHalfOutline[][2] = {{130, 0},    {118, -9},   {100, -18},  {30, -18},   {-20, -110}, {-45, -110},
                                      {-20, -18},  {-95, -18},  {-120, -50}, {-135, -50}, {-128, -18}, {-134, -8}};

std::vector<Eigen::Vector2d> Outline() {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : kHalfOutline) out.emplace_back(p[0], p[1]);
  const int n = static_cast<int>(std::size(kHalfOutline));
  for (int i = n - 1; i >= 1; --i) out.emplace_back(kHalfOutline[i][0], -kHalfOutline[i][1]);
  return out;
}

double SkyDn(double y, int height) { return kSkyTopDn + (kSkyBottomDn - kSkyTopDn) * (y + 0.5) / height; }

inline double Phi(double x) { return 0.5 * std::erfc(-x * M_SQRT1_2); }

// A marker placed in the image for one sub-exposure: its centre, axes and scale.
struct Placed {
  Eigen::Vector2d p;
  double c = 1, s = 0, scale = 1;
};

// Value of a marker (DN added to the blurred silhouette/sky) at the marker-axes point (u, v) (image px).
struct MarkerShade {
  const PointsSimulator::Marker* m = nullptr;
  double sigma = 0.8;
  bool plate = false;      // the look-alike: a dark plate around the checker
  double behind_dn = 0;    // the look-alike: what the plate hides (the pixel's value before it)
  mutable double amp_scale = -1;     // texture: the scale `amp` was computed for
  mutable std::vector<double> amp;   // texture: attenuated amplitudes of the waves

  // Blurred box of half side h along one axis, and the blurred odd (checker) box.
  void Axis(double u, double h, double* box, double* odd) const {
    const double a = Phi((u + h) / sigma), b = Phi((u - h) / sigma), c = Phi(u / sigma);
    *box = a - b;
    *odd = 2.0 * c - b - a;
  }
  double Quadrant(double u, double v, double h) const {
    double bu, ou, bv, ov;
    Axis(u, h, &bu, &ou);
    Axis(v, h, &bv, &ov);
    const double mid = 0.5 * (kQuadDarkDn + kQuadLightDn), amp = 0.5 * (kQuadLightDn - kQuadDarkDn);
    return (mid - kBodyDn) * bu * bv + amp * ou * ov;
  }
  static double Gauss(double r2, double sigma_body, double sigma_psf, double amplitude) {
    const double var = sigma_body * sigma_body + sigma_psf * sigma_psf;
    return amplitude * sigma_body * sigma_body / var * std::exp(-0.5 * r2 / var);
  }
  double Texture(double u, double v, double scale) const {
    const double h = m->half_px * scale;
    double bu, ou, bv, ov;
    Axis(u, h, &bu, &ou);
    Axis(v, h, &bv, &ov);
    const double w = bu * bv;
    if (w < 1e-12) return 0.0;
    if (scale != amp_scale) {
      // Each sinusoid's amplitude times the PSF's transfer function at its image frequency k / scale.
      amp_scale = scale;
      amp.clear();
      const double k2 = sigma * sigma / (scale * scale);
      for (const Eigen::Vector4d& wave : m->waves) {
        amp.push_back(wave[3] * std::exp(-0.5 * k2 * (wave[0] * wave[0] + wave[1] * wave[1])));
      }
    }
    double sum = kTextureMeanDn - kBodyDn;
    const double bx = u / scale, by = v / scale;
    for (std::size_t i = 0; i < amp.size(); ++i) {
      const Eigen::Vector4d& wave = m->waves[i];
      sum += amp[i] * std::cos(wave[0] * bx + wave[1] * by + wave[2]);
    }
    return w * sum;
  }
  double operator()(double u, double v, double scale) const {
    const std::string& method = m->method;
    if (method == "quadrant") {
      const double q = Quadrant(u, v, m->half_px * scale);
      if (!plate) return q;
      double bu, ou, bv, ov;
      Axis(u, (m->half_px + kPlateMarginPx) * scale, &bu, &ou);
      Axis(v, (m->half_px + kPlateMarginPx) * scale, &bv, &ov);
      return (kBodyDn - behind_dn) * bu * bv + q;
    }
    const double r = std::hypot(u, v);
    if (method == "circle") {
      const double R = m->half_px * scale, off = kHighlightOffset * R;
      const double du = u - off * std::cos(0.7), dv = v - off * std::sin(0.7);
      return (kDiscDn - kBodyDn) * Phi((R - r) / sigma) +
             Gauss(du * du + dv * dv, kHighlightSigmaPx * scale, sigma, kHighlightDn);
    }
    if (method == "centroid-bright") return Gauss(r * r, m->half_px * scale, sigma, kLampDn);
    if (method == "centroid-dark") return -kDarkDepthDn * Phi((m->half_px * scale - r) / sigma);
    return Texture(u, v, scale);
  }
};

// Adds the mean over the sub-exposures and the n x n lattice of `shade` around each placement to `img`
// (CV_32FC1 frame); `reach_px` bounds the marker's support in the image. A plate hides `behind` (the frame
// before the marker).
void AddMarker(cv::Mat* img, MarkerShade shade, const std::vector<Placed>& where, double reach_px, int n,
               const cv::Mat* behind = nullptr) {
  const double w = 1.0 / (n * n * static_cast<double>(where.size()));
  const bool plate = shade.plate;
  for (const Placed& pl : where) {
    const int x0 = std::max(0, static_cast<int>(std::floor(pl.p.x() - reach_px)));
    const int x1 = std::min(img->cols - 1, static_cast<int>(std::ceil(pl.p.x() + reach_px)));
    const int y0 = std::max(0, static_cast<int>(std::floor(pl.p.y() - reach_px)));
    const int y1 = std::min(img->rows - 1, static_cast<int>(std::ceil(pl.p.y() + reach_px)));
    for (int y = y0; y <= y1; ++y) {
      float* row = img->ptr<float>(y);
      for (int x = x0; x <= x1; ++x) {
        if (plate) shade.behind_dn = behind->at<float>(y, x);
        double sum = 0;
        for (int a = 0; a < n; ++a) {
          const double dy = y - 0.5 + (a + 0.5) / n - pl.p.y();
          for (int b = 0; b < n; ++b) {
            const double dx = x - 0.5 + (b + 0.5) / n - pl.p.x();
            sum += shade(pl.c * dx + pl.s * dy, -pl.s * dx + pl.c * dy, pl.scale);
          }
        }
        row[x] += static_cast<float>(w * sum);
      }
    }
  }
}

// The silhouette's blurred coverage in `roi` (mean over the poses), on an n-times finer grid: polygon fill,
// Gaussian blur of std sigma * n, area average; then sky + (body - sky) coverage.
void DrawSilhouette(cv::Mat* img, const cv::Rect& roi, const std::vector<PointsSimulator::Pose>& poses, int n,
                    double sigma) {
  const cv::Size fine(roi.width * n, roi.height * n);
  // Scratch images kept per thread: fresh pages cost more than the drawing (docs/rk-sim.md "Speed").
  thread_local cv::Mat acc, mask, cover;
  acc.create(fine, CV_32FC1);
  acc.setTo(0);
  mask.create(fine, CV_8UC1);
  constexpr int kShift = 8;
  const std::vector<Eigen::Vector2d> outline = Outline();
  for (const PointsSimulator::Pose& pose : poses) {
    std::vector<cv::Point> pts;
    for (const Eigen::Vector2d& b : outline) {
      const Eigen::Vector2d q = pose.Apply(b);
      // Fine pixel centres: image x = roi.x - 0.5 + (X + 0.5) / n.
      const double fx = (q.x() - roi.x + 0.5) * n - 0.5, fy = (q.y() - roi.y + 0.5) * n - 0.5;
      pts.emplace_back(static_cast<int>(std::lround(fx * (1 << kShift))),
                       static_cast<int>(std::lround(fy * (1 << kShift))));
    }
    mask.setTo(0);
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{pts}, cv::Scalar(1), cv::LINE_8, kShift);
    cv::accumulate(mask, acc);
  }
  acc *= 1.0 / static_cast<double>(poses.size());
  cv::GaussianBlur(acc, acc, cv::Size(0, 0), sigma * n, sigma * n, cv::BORDER_REPLICATE);
  cv::resize(acc, cover, roi.size(), 0, 0, cv::INTER_AREA);
  for (int y = 0; y < roi.height; ++y) {
    float* row = img->ptr<float>(roi.y + y);
    const float* cv_row = cover.ptr<float>(y);
    const double sky = SkyDn(roi.y + y, img->rows);
    for (int x = 0; x < roi.width; ++x) row[roi.x + x] = static_cast<float>(sky + (kBodyDn - sky) * cv_row[x]);
  }
}

// The frame region the target touches in any sub-exposure (markers, silhouette, PSF), clipped.
cv::Rect TargetRoi(const PointsSimulator& sim, const std::vector<PointsSimulator::Pose>& poses, double sigma) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  const auto grow = [&](const Eigen::Vector2d& p, double r) {
    x0 = std::min(x0, p.x() - r), y0 = std::min(y0, p.y() - r), x1 = std::max(x1, p.x() + r), y1 = std::max(y1, p.y() + r);
  };
  for (const PointsSimulator::Pose& pose : poses) {
    for (const Eigen::Vector2d& v : Outline()) grow(pose.Apply(v), 5 * sigma + 2);
    for (const auto& m : sim.markers()) grow(pose.Apply(m.body), m.support_px * pose.scale + 5 * sigma + 2);
  }
  const cv::Rect frame(0, 0, sim.options().width, sim.options().height);
  const cv::Rect r(static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
                   static_cast<int>(std::ceil(x1 - x0)) + 1, static_cast<int>(std::ceil(y1 - y0)) + 1);
  return r & frame;
}

void DrawClouds(cv::Mat* img, const PointsSimulator& sim, double t) {
  for (const PointsSimulator::Cloud& c : sim.clouds()) {
    const Eigen::Vector2d centre = c.centre_px + c.velocity_px_s * t;
    const double reach = c.core_px + c.edge_px + 1;
    const cv::Rect box = cv::Rect(static_cast<int>(std::floor(centre.x() - reach)),
                                  static_cast<int>(std::floor(centre.y() - reach)), static_cast<int>(2 * reach) + 2,
                                  static_cast<int>(2 * reach) + 2) &
                         cv::Rect(0, 0, img->cols, img->rows);
    for (int y = box.y; y < box.y + box.height; ++y) {
      float* row = img->ptr<float>(y);
      for (int x = box.x; x < box.x + box.width; ++x) {
        const double a = c.Opacity(Eigen::Vector2d(x, y), t);
        if (a > 0) row[x] = static_cast<float>((1.0 - a) * row[x] + a * kCloudDn);
      }
    }
  }
}

}  // namespace points_detail

// `steps` evenly inside the exposure, centred on the frame time.
std::vector<double> PointsSimulator::ExposureTimes(int k) const {
  const double t = TimeS(k);
  int steps = opt_.blur_steps;
  if (opt_.exposure_s <= 0) return {t};
  if (steps == 0) {
    // The fastest body point (the outline's vertices) over the exposure.
    double motion = 0;
    const Pose a = PoseAt(t - 0.5 * opt_.exposure_s), b = PoseAt(t + 0.5 * opt_.exposure_s);
    for (const Eigen::Vector2d& v : points_detail::Outline()) motion = std::max(motion, (a.Apply(v) - b.Apply(v)).norm());
    steps = std::clamp(static_cast<int>(std::ceil(motion / points_detail::kBlurStepPx)), 1, 64);
  }
  std::vector<double> out;
  for (int j = 0; j < steps; ++j) out.push_back(t + opt_.exposure_s * ((j + 0.5) / steps - 0.5));
  return out;
}

cv::Mat PointsSimulator::Signal(int k) const { return Signal(k, opt_.SupersampleN()); }

cv::Mat PointsSimulator::Signal(int k, int n) const {
  cv::Mat img;
  RenderSignal(k, n, &img);
  return img;
}

void PointsSimulator::RenderSignal(int k, int n, cv::Mat* out) const {
  using namespace points_detail;
  out->create(opt_.height, opt_.width, CV_32FC1);
  cv::Mat& img = *out;
  for (int y = 0; y < img.rows; ++y) img.row(y).setTo(SkyDn(y, img.rows));
  const std::vector<double> times = ExposureTimes(k);
  std::vector<Pose> poses;
  for (double t : times) poses.push_back(PoseAt(t));
  const double sigma = opt_.psf_sigma_px;
  const cv::Rect roi = TargetRoi(*this, poses, sigma);
  if (roi.area() > 0) {
    DrawSilhouette(&img, roi, poses, n, sigma);
    for (const Marker& m : markers_) {
      std::vector<Placed> where;
      for (const Pose& pose : poses) {
        where.push_back({pose.Apply(m.body), std::cos(pose.theta_rad), std::sin(pose.theta_rad), pose.scale});
      }
      MarkerShade shade;
      shade.m = &m, shade.sigma = sigma;
      AddMarker(&img, shade, where, m.support_px * poses.back().scale * 1.01 + 5 * sigma + 1, n);
    }
  }
  if (LookalikeShown(k)) {
    const Marker& q2 = markers_[1];
    std::vector<Placed> where;
    for (std::size_t j = 0; j < times.size(); ++j) {
      where.push_back({LookalikeAt(times[j]), std::cos(poses[j].theta_rad), std::sin(poses[j].theta_rad),
                       poses[j].scale});
    }
    const double reach = (q2.half_px + kPlateMarginPx) * M_SQRT2 * poses.back().scale * 1.01 + 5 * sigma + 1;
    const cv::Mat behind = img.clone();
    MarkerShade shade;
    shade.m = &q2, shade.sigma = sigma, shade.plate = true;
    AddMarker(&img, shade, where, reach, n, &behind);
  }
  DrawClouds(&img, *this, TimeS(k));
}

cv::Mat PointsSimulator::Frame(int k) const {
  using points_detail::kDeepScale;
  const bool deep = opt_.bits == 16;
  const double unit = deep ? kDeepScale : 1.0, max_dn = deep ? 4095.0 : 255.0;
  const double read = opt_.read_noise_dn * unit, gain = opt_.gain_e_per_dn / unit;
  // Shot and read noise as one Gaussian of variance mean / gain + read² (the Poisson is normal above a few
  // electrons: the sky and the markers have hundreds), by whole-frame vector operations in place on images
  // kept per thread (a 5-megapixel float image's fresh pages cost ~70 ms here, the operations ~1 ms each).
  thread_local cv::Mat mean, normal, sd;
  RenderSignal(k, opt_.SupersampleN(), &mean);
  if (deep) mean.convertTo(mean, CV_32FC1, unit);
  cv::max(mean, 0.0, mean);
  std::mt19937_64 stream = RandomStream(opt_.seed, kPointsNoiseStream, static_cast<std::uint64_t>(k));
  cv::RNG rng(stream());
  normal.create(mean.size(), CV_32FC1);
  rng.fill(normal, cv::RNG::NORMAL, 0.0, 1.0);
  if (gain > 0) {
    mean.convertTo(sd, CV_32FC1, 1.0 / gain, read * read);
    cv::sqrt(sd, sd);
    cv::multiply(sd, normal, sd);
    cv::add(mean, sd, mean);
  } else if (read > 0) {
    cv::scaleAdd(normal, read, mean, mean);
  }
  cv::min(mean, max_dn, mean);
  cv::Mat out;
  mean.convertTo(out, deep ? CV_16UC1 : CV_8UC1);  // rounds to the nearest, clips at 0
  return out;
}

}  // namespace rk::sim
