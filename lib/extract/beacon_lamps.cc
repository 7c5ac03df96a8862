// Per-lamp centroid estimator with time-averaged flux shares; method,
// assumptions and noise model in beacon_lamps.h.
#include "extract/beacon_lamps.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rk::extract {

LampEstimator::LampEstimator(const DetectOptions& opt) : opt_(opt) {
  comp_.reserve(kMaxLamps + 1);
  lamps_.reserve(kMaxLamps);
  disk_.reserve(kMaxLamps);
  shares_.reserve(kMaxLamps);
  reordered_.reserve(kMaxLamps);
  match_.reserve(kMaxLamps);
}

namespace {

// A pixel's signal above the cluster's background plane.
double Signal(const cv::Mat& frame, const SpotMeasurement& cl, int x, int y) {
  const double bg = cl.background_dn + cl.bg_dx * (x - cl.x_px) + cl.bg_dy * (y - cl.y_px);
  return PixelValue(frame, x, y) - bg;
}

}  // namespace

bool LampEstimator::Measure(const cv::Mat& frame, const SpotMeasurement& cl, std::vector<LampMeasurement>* lamps) {
  lamps->clear();
  const int m = opt_.margin_px;
  const int x0 = cl.region.x0 - m, y0 = cl.region.y0 - m, x1 = cl.region.x1 + m, y1 = cl.region.y1 + m;
  if (x0 < 0 || y0 < 0 || x1 >= frame.cols || y1 >= frame.rows || cl.noise_dn <= 0) return false;
  const double thr_grow = opt_.k_grow * cl.noise_dn, thr_det = opt_.k_detect * cl.noise_dn;
  if (!LabelComponents(frame, cl, x0, y0, x1, y1, thr_grow)) return false;
  // Lamps: components reaching the detection threshold; their disks.
  disk_.clear();
  for (const Component& c : comp_) {
    if (c.peak < thr_det || !(c.sw > 0)) continue;
    Disk d;
    d.cx = static_cast<int>(std::lround(c.swx / c.sw));
    d.cy = static_cast<int>(std::lround(c.swy / c.sw));
    const int r = std::max({d.cx - c.x0, c.x1 - d.cx, d.cy - c.y0, c.y1 - d.cy}) + m;
    d.r2 = r * r + r;  // (r + 1/2)² rounded, as the cluster disk
    disk_.push_back(d);
  }
  if (disk_.size() < 2 || static_cast<int>(disk_.size()) > kMaxLamps) return false;
  for (std::size_t i = 0; i < disk_.size(); ++i) {
    for (std::size_t j = 0; j < disk_.size(); ++j) {
      if (i == j) continue;
      const int dx = disk_[j].cx - disk_[i].cx, dy = disk_[j].cy - disk_[i].cy;
      if (dx * dx + dy * dy <= disk_[i].r2) return false;  // another lamp inside the disk: not resolved
    }
  }
  if (!PartitionDisks(frame, cl)) return false;
  const double var_pix = cl.noise_dn * cl.noise_dn;
  for (const Disk& d : disk_) {
    if (!(d.s > 0)) return false;
    LampMeasurement l;
    const double ux = d.sx / d.s, uy = d.sy / d.s;
    l.x_px = d.cx + ux;
    l.y_px = d.cy + uy;
    l.flux_dn = d.s;
    // Σ_p (dx − ux)² = Σ dx² − 2 ux Σ dx + n ux² over the lamp's pixels.
    l.var_x_px2 = var_pix * std::max(0.0, d.gxx - 2 * ux * d.gx + d.n * ux * ux) / (d.s * d.s);
    l.var_y_px2 = var_pix * std::max(0.0, d.gyy - 2 * uy * d.gy + d.n * uy * uy) / (d.s * d.s);
    l.var_flux_dn2 = var_pix * d.n;
    lamps->push_back(l);
  }
  return true;
}

// 8-connected components of the window [x0, x1] × [y0, y1] (pixels ≥ b + k_grow σ) in comp_; false if there
// are more than kMaxLamps.
bool LampEstimator::LabelComponents(const cv::Mat& frame, const SpotMeasurement& cl, int x0, int y0, int x1, int y1,
                                    double thr_grow) {
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  label_.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), -1);
  comp_.clear();
  constexpr int reach = 1;  // 8-connected (beacon_lamps.h)
  for (int sy = y0; sy <= y1; ++sy) {
    for (int sx = x0; sx <= x1; ++sx) {
      const std::size_t si = static_cast<std::size_t>((sy - y0) * w + (sx - x0));
      if (label_[si] >= 0 || Signal(frame, cl, sx, sy) < thr_grow) continue;
      if (static_cast<int>(comp_.size()) > kMaxLamps) return false;
      const int id = static_cast<int>(comp_.size());
      Component c;
      c.x0 = c.x1 = sx;
      c.y0 = c.y1 = sy;
      label_[si] = id;
      stack_.clear();
      stack_.push_back(static_cast<int>(si));
      while (!stack_.empty()) {
        const int p = stack_.back();
        stack_.pop_back();
        const int x = x0 + p % w, y = y0 + p / w;
        const double v = Signal(frame, cl, x, y);
        c.sw += v;
        c.swx += v * x;
        c.swy += v * y;
        c.peak = std::max(c.peak, v);
        c.x0 = std::min(c.x0, x);
        c.x1 = std::max(c.x1, x);
        c.y0 = std::min(c.y0, y);
        c.y1 = std::max(c.y1, y);
        for (int yy = std::max(y0, y - reach); yy <= std::min(y1, y + reach); ++yy) {
          for (int xx = std::max(x0, x - reach); xx <= std::min(x1, x + reach); ++xx) {
            const std::size_t q = static_cast<std::size_t>((yy - y0) * w + (xx - x0));
            if (label_[q] >= 0 || Signal(frame, cl, xx, yy) < thr_grow) continue;
            label_[q] = id;
            stack_.push_back(static_cast<int>(q));
          }
        }
      }
      comp_.push_back(c);
    }
  }
  return true;
}

// The lamp disks' pixel sums (disk_); false if a disk leaves the frame.
bool LampEstimator::PartitionDisks(const cv::Mat& frame, const SpotMeasurement& cl) {
  // Each pixel of a disk goes to the nearest lamp centre.
  int bx0 = frame.cols, by0 = frame.rows, bx1 = -1, by1 = -1;
  for (const Disk& d : disk_) {
    const int r = static_cast<int>(std::sqrt(static_cast<double>(d.r2)));
    bx0 = std::min(bx0, d.cx - r);
    by0 = std::min(by0, d.cy - r);
    bx1 = std::max(bx1, d.cx + r);
    by1 = std::max(by1, d.cy + r);
  }
  if (bx0 < 0 || by0 < 0 || bx1 >= frame.cols || by1 >= frame.rows) return false;
  for (int y = by0; y <= by1; ++y) {
    for (int x = bx0; x <= bx1; ++x) {
      int best = -1, best_d2 = std::numeric_limits<int>::max();
      for (std::size_t i = 0; i < disk_.size(); ++i) {
        const int dx = x - disk_[i].cx, dy = y - disk_[i].cy;
        const int d2 = dx * dx + dy * dy;
        if (d2 <= disk_[i].r2 && d2 < best_d2) {
          best = static_cast<int>(i);
          best_d2 = d2;
        }
      }
      if (best < 0) continue;
      Disk& d = disk_[static_cast<std::size_t>(best)];
      const double v = Signal(frame, cl, x, y);
      const int dx = x - d.cx, dy = y - d.cy;
      d.s += v;
      d.sx += v * dx;
      d.sy += v * dy;
      d.gx += dx;
      d.gy += dy;
      d.gxx += dx * dx;
      d.gyy += dy * dy;
      ++d.n;
    }
  }
  return true;
}

LampEstimate LampEstimator::Combine(const std::vector<LampMeasurement>& lamps, double cx_px, double cy_px) {
  const std::size_t n = lamps.size();
  // Match to the averaged lamps by offset from the cluster centroid.
  bool matched = n >= 2 && shares_.size() == n;
  if (matched) {
    double dmin2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        dmin2 = std::min(dmin2, std::pow(lamps[i].x_px - lamps[j].x_px, 2) + std::pow(lamps[i].y_px - lamps[j].y_px, 2));
    const double tol2 = dmin2 / 9.0;  // a third of the smallest spacing
    match_.assign(n, -1);
    for (std::size_t i = 0; i < n && matched; ++i) {
      const double ox = lamps[i].x_px - cx_px, oy = lamps[i].y_px - cy_px;
      int best = -1;
      double best_d2 = tol2;
      for (std::size_t j = 0; j < n; ++j) {
        const double d2 = std::pow(ox - shares_[j].dx_px, 2) + std::pow(oy - shares_[j].dy_px, 2);
        if (d2 < best_d2) {
          best = static_cast<int>(j);
          best_d2 = d2;
        }
      }
      if (best < 0 || std::find(match_.begin(), match_.end(), best) != match_.end()) matched = false;
      match_[i] = best;
    }
  }
  if (matched) {
    frames_ += 1.0;
    const double alpha = 1.0 / std::min(frames_, static_cast<double>(kShareFrames));
    // Reorder the averages to the order of `lamps` (match_ is a permutation).
    reordered_.resize(n);
    for (std::size_t i = 0; i < n; ++i) reordered_[i] = shares_[static_cast<std::size_t>(match_[i])];
    shares_.swap(reordered_);
    for (std::size_t i = 0; i < n; ++i)
      shares_[i].flux_mean_dn += alpha * (lamps[i].flux_dn - shares_[i].flux_mean_dn);
  } else {
    shares_.resize(n);
    for (std::size_t i = 0; i < n; ++i) shares_[i].flux_mean_dn = lamps[i].flux_dn;
    frames_ = 1.0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    shares_[i].dx_px = lamps[i].x_px - cx_px;
    shares_[i].dy_px = lamps[i].y_px - cy_px;
  }
  // Effective number of frames in the averages: a running mean, then an
  // exponential one of weight α = 1/N (variance α/(2 − α) of one frame's).
  const double n_eff = frames_ < kShareFrames ? frames_ : 2.0 * kShareFrames - 1.0;
  double fsum = 0.0;
  for (const Share& s : shares_) fsum += s.flux_mean_dn;
  LampEstimate e;
  e.lamps = static_cast<int>(n);
  if (!(fsum > 0)) return e;
  for (std::size_t i = 0; i < n; ++i) {
    const double share = shares_[i].flux_mean_dn / fsum;
    e.x_px += share * lamps[i].x_px;
    e.y_px += share * lamps[i].y_px;
  }
  double vx = 0.0, vy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double share = shares_[i].flux_mean_dn / fsum;
    const double var_share = lamps[i].var_flux_dn2 / (fsum * fsum) / n_eff;
    vx += share * share * lamps[i].var_x_px2 + var_share * std::pow(lamps[i].x_px - e.x_px, 2);
    vy += share * share * lamps[i].var_y_px2 + var_share * std::pow(lamps[i].y_px - e.y_px, 2);
  }
  e.sigma_x_px = std::sqrt(vx);
  e.sigma_y_px = std::sqrt(vy);
  return e;
}

bool LampEstimator::Estimate(const cv::Mat& frame, const SpotMeasurement& cluster, LampEstimate* out) {
  if (!Measure(frame, cluster, &lamps_)) {
    Reset();
    return false;
  }
  *out = Combine(lamps_, cluster.x_px, cluster.y_px);
  return out->lamps > 0 && std::isfinite(out->x_px + out->y_px);
}

}  // namespace rk::extract
