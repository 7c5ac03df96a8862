// Grey projection, region growing, windowed grey-weighted centroid with a local
// background plane, and NCC template matching; method and assumptions in
// beacon_detect.h (seed 001 §2.1).
#include "extract/beacon_detect.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Eigen/Dense>

#include "numeric/robust_stats.h"

namespace rk::extract {
namespace {

inline double At(const cv::Mat& f, int x, int y) { return PixelValue(f, x, y); }

PixelBox Clip(PixelBox b, const cv::Mat& f) {
  b.x0 = std::max(b.x0, 0);
  b.y0 = std::max(b.y0, 0);
  b.x1 = std::min(b.x1, f.cols - 1);
  b.y1 = std::min(b.y1, f.rows - 1);
  return b;
}

PixelBox Expand(const PixelBox& b, int d) { return {b.x0 - d, b.y0 - d, b.x1 + d, b.y1 + d}; }

// Robust level and noise of samples (reordered in place): median and MAD (selected on |deviation| with
// the signed deviations kept for the clipped pass, so not numeric::UpperMedianAndMadInPlace), then
// the mean and standard deviation of the samples within 4 σ of the median
// (the MAD of integer data is coarsely quantised; the clipped moments are not).
NoiseStats Robust(std::vector<double>* s, double min_sigma) {
  NoiseStats st;
  if (s->empty()) return st;
  const std::size_t n = s->size();
  auto mid = s->begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(s->begin(), mid, s->end());
  const double med = *mid;
  // MAD: select on |deviation| while keeping the signed deviations for the
  // clipped pass below.
  for (double& v : *s) v = v - med;
  std::vector<double>& d = *s;
  auto abs_less = [](double a, double b) { return std::fabs(a) < std::fabs(b); };
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(n / 2), d.end(), abs_less);
  const double mad = std::fabs(d[n / 2]);
  const double sigma0 = std::max(1.4826 * mad, std::max(min_sigma, 0.5));
  const double clip = 4.0 * sigma0;
  double sum = 0.0, sum2 = 0.0;
  std::size_t m = 0;
  for (double v : d) {
    if (std::fabs(v) <= clip) {
      sum += v;
      sum2 += v * v;
      ++m;
    }
  }
  if (m < 3) {
    st.level_dn = med;
    st.sigma_dn = std::max(1.4826 * mad, min_sigma);
    return st;
  }
  const double mean = sum / static_cast<double>(m);
  const double var = std::max(0.0, sum2 / static_cast<double>(m) - mean * mean);
  st.level_dn = med + mean;
  st.sigma_dn = std::max(std::sqrt(var), min_sigma);
  return st;
}

template <class T>
void Project(const cv::Mat& f, std::vector<std::uint32_t>* row_sum, std::vector<std::uint32_t>* col_sum) {
  row_sum->assign(static_cast<std::size_t>(f.rows), 0);
  col_sum->assign(static_cast<std::size_t>(f.cols), 0);
  std::uint32_t* __restrict col = col_sum->data();
  const int w = f.cols;
  for (int y = 0; y < f.rows; ++y) {
    const T* __restrict p = f.ptr<T>(y);
    std::uint32_t s = 0;
    for (int x = 0; x < w; ++x) {
      const std::uint32_t v = p[x];
      col[x] += v;
      s += v;
    }
    (*row_sum)[static_cast<std::size_t>(y)] = s;
  }
}

// Morphological top-hat of a profile (profile − opening with a flat element of
// half length h): removes a slowly varying background, keeps peaks narrower than 2h.
void TopHat(const std::vector<std::uint32_t>& p, int h, std::vector<double>* out, std::vector<double>* work) {
  const int n = static_cast<int>(p.size());
  work->resize(p.size());
  out->resize(p.size());
  for (int i = 0; i < n; ++i) {
    double m = p[static_cast<std::size_t>(i)];
    for (int k = std::max(0, i - h); k <= std::min(n - 1, i + h); ++k) m = std::min(m, double(p[static_cast<std::size_t>(k)]));
    (*work)[static_cast<std::size_t>(i)] = m;
  }
  for (int i = 0; i < n; ++i) {
    double m = (*work)[static_cast<std::size_t>(i)];
    for (int k = std::max(0, i - h); k <= std::min(n - 1, i + h); ++k) m = std::max(m, (*work)[static_cast<std::size_t>(k)]);
    (*out)[static_cast<std::size_t>(i)] = p[static_cast<std::size_t>(i)] - m;
  }
}

// Up to k peak positions of a profile: the global argmax (eqs. 3–4) first, then
// local maxima above `thr` in decreasing height, at least `sep` apart.
void Peaks(const std::vector<double>& r, int k, double thr, int sep, std::vector<int>* peaks) {
  peaks->clear();
  const int n = static_cast<int>(r.size());
  if (n == 0) return;
  // Collect local maxima.
  std::vector<std::pair<double, int>> cand;
  cand.reserve(64);
  for (int i = 0; i < n; ++i) {
    const double v = r[static_cast<std::size_t>(i)];
    if (v < thr && !cand.empty()) continue;
    bool is_max = true;
    for (int d = 1; d <= 2 && is_max; ++d) {
      if (i - d >= 0 && r[static_cast<std::size_t>(i - d)] > v) is_max = false;
      if (i + d < n && r[static_cast<std::size_t>(i + d)] >= v) is_max = false;
    }
    if (is_max) cand.emplace_back(v, i);
  }
  std::sort(cand.begin(), cand.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& c : cand) {
    if (static_cast<int>(peaks->size()) >= k) break;
    if (!peaks->empty() && c.first < thr) break;
    bool far = true;
    for (int q : *peaks) far = far && std::abs(q - c.second) >= sep;
    if (far) peaks->push_back(c.second);
  }
}

double ProfileNoise(const std::vector<double>& r, std::vector<double>* work) {
  work->clear();
  for (std::size_t i = 1; i < r.size(); ++i) work->push_back(std::fabs(r[i] - r[i - 1]));
  if (work->empty()) return 1.0;
  // |difference| of two N(0, s²) has median 0.6745·√2·s.
  return std::max(numeric::UpperMedianInPlace(*work) / (0.6745 * std::sqrt(2.0)), 1.0);
}

}  // namespace

const io::OptionTable<DetectOptions>& DetectOptions::Table() {
  using B = io::Bounds;
  static const io::OptionTable<DetectOptions> table =
      io::OptionTable<DetectOptions>()
          .Real("--k-detect", &DetectOptions::k_detect, "", B::Positive(),
                "Seed threshold in noise sigmas above the local background")
          .Real("--k-grow", &DetectOptions::k_grow, "", B::Positive(), "Region-growing threshold in noise sigmas")
          .Integer("--gap", &DetectOptions::gap_px, "px", B::Closed(0, 4),
                   "Region-growing gap tolerance (px), merges the lamps")
          .Integer("--cluster-gap", &DetectOptions::cluster_gap_px, "px", B::Closed(0, 64),
                   "Regions this close (px) merge into one lamp cluster")
          .Integer("--max-extent", &DetectOptions::max_extent_px, "px", B::Closed(4, 512),
                   "Largest distance of a region pixel from its seed (px)")
          .Integer("--max-area", &DetectOptions::max_area_px, "px", B::AtLeast(1),
                   "Regions with more pixels are rejected")
          .Integer("--margin", &DetectOptions::margin_px, "px", B::Closed(1, 32),
                   "Centroid window: region + this margin (px)")
          .Integer("--ring", &DetectOptions::ring_px, "px", B::Closed(1, 16), "Width of the local-background ring (px)")
          .Flag("--bg-plane", &DetectOptions::background_plane,
                "Fit a background plane to the ring (for sky gradients) instead of a level")
          .Integer("--projection-peaks", &DetectOptions::projection_peaks, "", B::Closed(1, 64),
                   "Peaks per grey projection in full-frame search");
  return table;
}

bool DetectOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  auto fail = [&](const char* w) {
    if (why) *why = w;
    return false;
  };
  if (k_grow > k_detect) return fail("--k-grow must be <= --k-detect");
  if (max_candidates < 1) return fail("max candidates must be >= 1");
  if (!(min_noise_dn > 0)) return fail("noise floor must be > 0");
  return true;
}

SpotDetector::SpotDetector(const DetectOptions& opt) : opt_(opt) {
  const int side = 2 * opt_.max_extent_px + 1;
  visited_.assign(static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0);
  stack_.reserve(static_cast<std::size_t>(opt_.max_area_px) + 16);
  samples_.reserve(4096);
  found_.reserve(static_cast<std::size_t>(opt_.max_candidates));
}

NoiseStats SpotDetector::BorderStats(const cv::Mat& frame, PixelBox box) {
  box = Clip(box, frame);
  samples_.clear();
  if (box.empty()) return {};
  for (int x = box.x0; x <= box.x1; ++x) {
    samples_.push_back(At(frame, x, box.y0));
    if (box.y1 != box.y0) samples_.push_back(At(frame, x, box.y1));
  }
  for (int y = box.y0 + 1; y < box.y1; ++y) {
    samples_.push_back(At(frame, box.x0, y));
    if (box.x1 != box.x0) samples_.push_back(At(frame, box.x1, y));
  }
  return Robust(&samples_, opt_.min_noise_dn);
}

NoiseStats SpotDetector::FrameStats(const cv::Mat& frame, int stride) {
  samples_.clear();
  stride = std::max(stride, 1);
  for (int y = stride / 2; y < frame.rows; y += stride)
    for (int x = stride / 2; x < frame.cols; x += stride) samples_.push_back(At(frame, x, y));
  return Robust(&samples_, opt_.min_noise_dn);
}

bool SpotDetector::Grow(const cv::Mat& frame, int sx, int sy, double thr, SpotMeasurement* m) {
  const int E = opt_.max_extent_px;
  const int side = 2 * E + 1;
  std::fill(visited_.begin(), visited_.end(), 0);
  stack_.clear();
  auto idx = [&](int x, int y) { return (y - sy + E) * side + (x - sx + E); };
  PixelBox bb{sx, sy, sx, sy};
  int area = 0;
  double peak = At(frame, sx, sy);
  visited_[static_cast<std::size_t>(idx(sx, sy))] = 1;
  stack_.push_back(idx(sx, sy));
  const int r = opt_.gap_px + 1;
  while (!stack_.empty()) {
    const int id = stack_.back();
    stack_.pop_back();
    const int x = id % side - E + sx;
    const int y = id / side - E + sy;
    ++area;
    if (area > opt_.max_area_px) return false;
    bb.x0 = std::min(bb.x0, x);
    bb.x1 = std::max(bb.x1, x);
    bb.y0 = std::min(bb.y0, y);
    bb.y1 = std::max(bb.y1, y);
    for (int dy = -r; dy <= r; ++dy) {
      const int yy = y + dy;
      if (yy < 0 || yy >= frame.rows || std::abs(yy - sy) > E) continue;
      for (int dx = -r; dx <= r; ++dx) {
        const int xx = x + dx;
        if (xx < 0 || xx >= frame.cols || std::abs(xx - sx) > E) continue;
        const int j = idx(xx, yy);
        if (visited_[static_cast<std::size_t>(j)]) continue;
        const double v = At(frame, xx, yy);
        if (v < thr) continue;
        visited_[static_cast<std::size_t>(j)] = 1;
        peak = std::max(peak, v);
        stack_.push_back(j);
      }
    }
  }
  m->region = bb;
  m->area_px = area;
  m->peak_dn = peak;
  return true;
}

// Background level (and optionally plane) from the samples collected in
// samples_ (values) and work_/work2_ (offsets from the window centre), clipped
// at 4 σ around their median.
bool SpotDetector::FitSamples(double noise_sigma, double* b0, double* bx, double* by) {
  const std::size_t n = samples_.size();
  if (n < 6) return false;
  tmp_.assign(samples_.begin(), samples_.end());
  auto mid = tmp_.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(tmp_.begin(), mid, tmp_.end());
  const double med = *mid;
  const double clip = 4.0 * noise_sigma + 1.0;
  if (!opt_.background_plane) {
    double s = 0;
    std::size_t used = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::fabs(samples_[i] - med) > clip) continue;
      s += samples_[i];
      ++used;
    }
    if (used < 3) return false;
    *b0 = s / static_cast<double>(used);
    *bx = *by = 0.0;
    return true;
  }
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  std::size_t used = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::fabs(samples_[i] - med) > clip) continue;
    const Eigen::Vector3d a(1.0, work_[i], work2_[i]);
    A += a * a.transpose();
    rhs += a * samples_[i];
    ++used;
  }
  if (used < 6) return false;
  Eigen::Vector3d c = A.ldlt().solve(rhs);
  if (!c.allFinite()) c = Eigen::Vector3d(med, 0, 0);
  *b0 = c(0);
  *bx = c(1);
  *by = c(2);
  return true;
}

bool SpotDetector::MeasureCentroid(const cv::Mat& frame, const PixelBox& region, double noise_sigma,
                                   SpotMeasurement* m) {
  bool clipped = false;
  double b0 = 0, bx = 0, by = 0;
  // Pass 1: square window = region box + margin, background from the square ring.
  const PixelBox win = Expand(region, opt_.margin_px);
  const PixelBox wc = Clip(win, frame);
  if (wc.empty()) return false;
  {
    const PixelBox outer = Expand(win, opt_.ring_px);
    const PixelBox oc = Clip(outer, frame);
    if (oc.x0 != outer.x0 || oc.y0 != outer.y0 || oc.x1 != outer.x1 || oc.y1 != outer.y1) clipped = true;
    samples_.clear();
    work_.clear();
    work2_.clear();
    const double wx = 0.5 * (win.x0 + win.x1), wy = 0.5 * (win.y0 + win.y1);
    for (int y = oc.y0; y <= oc.y1; ++y) {
      const bool inside_rows = y >= win.y0 && y <= win.y1;
      for (int x = oc.x0; x <= oc.x1; ++x) {
        if (inside_rows && x >= win.x0 && x <= win.x1) {
          x = win.x1;  // skip the window interior
          continue;
        }
        samples_.push_back(At(frame, x, y));
        work_.push_back(x - wx);
        work2_.push_back(y - wy);
      }
    }
    if (!FitSamples(noise_sigma, &b0, &bx, &by)) return false;
  }
  double s = 0, sx = 0, sy = 0;
  {
    const double wx = 0.5 * (win.x0 + win.x1), wy = 0.5 * (win.y0 + win.y1);
    for (int y = wc.y0; y <= wc.y1; ++y) {
      const double brow = b0 + by * (y - wy);
      for (int x = wc.x0; x <= wc.x1; ++x) {
        const double w = At(frame, x, y) - (brow + bx * (x - wx));
        s += w;
        sx += w * x;
        sy += w * y;
      }
    }
  }
  if (!(s > 0)) return false;
  // Pass 2: disk centred on the rounded first centroid, radius = the farthest
  // region-box edge + margin, background from the annulus of width ring_px.
  // A disk holds the roundish cluster with fewer pure-noise pixels far from the
  // centre than a square (they dominate the centroid noise), and centring it
  // leaves the background residual no lever arm (|window centre − centroid| ≤ 0.5 px).
  const int rx = static_cast<int>(std::lround(sx / s)), ry = static_cast<int>(std::lround(sy / s));
  const int R = std::max({rx - region.x0, region.x1 - rx, ry - region.y0, region.y1 - ry}) + opt_.margin_px;
  const int Ro = R + opt_.ring_px;
  const int R2 = R * R + R, Ro2 = Ro * Ro + Ro;  // (r + 1/2)² rounded: a rounder digital disk
  if (rx - Ro < 0 || ry - Ro < 0 || rx + Ro >= frame.cols || ry + Ro >= frame.rows) clipped = true;
  const int y0 = std::max(ry - Ro, 0), y1 = std::min(ry + Ro, frame.rows - 1);
  const int x0 = std::max(rx - Ro, 0), x1 = std::min(rx + Ro, frame.cols - 1);
  samples_.clear();
  work_.clear();
  work2_.clear();
  for (int y = y0; y <= y1; ++y) {
    const int dy = y - ry;
    for (int x = x0; x <= x1; ++x) {
      const int dx = x - rx;
      const int d2 = dx * dx + dy * dy;
      if (d2 > R2 && d2 <= Ro2) {
        samples_.push_back(At(frame, x, y));
        work_.push_back(dx);
        work2_.push_back(dy);
      }
    }
  }
  if (!FitSamples(noise_sigma, &b0, &bx, &by)) return false;
  s = sx = sy = 0;
  double sxx_geom = 0, syy_geom = 0;
  for (int y = y0; y <= y1; ++y) {
    const int dy = y - ry;
    for (int x = x0; x <= x1; ++x) {
      const int dx = x - rx;
      if (dx * dx + dy * dy > R2) continue;
      const double w = At(frame, x, y) - (b0 + bx * dx + by * dy);
      s += w;
      sx += w * dx;
      sy += w * dy;
    }
  }
  if (!(s > 0)) return false;
  const double ux = sx / s, uy = sy / s;  // centroid relative to (rx, ry)
  double mxx = 0, myy = 0;
  for (int y = y0; y <= y1; ++y) {
    const int dy = y - ry;
    for (int x = x0; x <= x1; ++x) {
      const int dx = x - rx;
      if (dx * dx + dy * dy > R2) continue;
      const double w = At(frame, x, y) - (b0 + bx * dx + by * dy);
      mxx += w * (dx - ux) * (dx - ux);
      myy += w * (dy - uy) * (dy - uy);
      sxx_geom += (dx - ux) * (dx - ux);
      syy_geom += (dy - uy) * (dy - uy);
    }
  }
  m->x_px = rx + ux;
  m->y_px = ry + uy;
  m->flux_dn = s;
  m->noise_dn = noise_sigma;
  m->sigma_x_px = noise_sigma * std::sqrt(sxx_geom) / s;
  m->sigma_y_px = noise_sigma * std::sqrt(syy_geom) / s;
  m->size_px = std::sqrt(std::max(0.0, (mxx + myy) / s));
  m->background_dn = b0 + bx * ux + by * uy;
  m->bg_dx = bx;
  m->bg_dy = by;
  m->clipped = clipped;
  return true;
}

void SpotDetector::FindInBox(const cv::Mat& frame, PixelBox search, const NoiseStats& noise,
                             std::vector<SpotMeasurement>* out) {
  search = Clip(search, frame);
  if (search.empty()) return;
  const double thr_det = noise.level_dn + opt_.k_detect * noise.sigma_dn;
  const double thr_grow = noise.level_dn + opt_.k_grow * noise.sigma_dn;
  const std::size_t first = out->size();
  FindSeeds(frame, search, noise, thr_det, thr_grow, out);
  MergeClusters(frame, noise, first, out);
}

void SpotDetector::FindSeeds(const cv::Mat& frame, const PixelBox& search, const NoiseStats& noise, double thr_det,
                             double thr_grow, std::vector<SpotMeasurement>* out) {
  for (int y = search.y0; y <= search.y1; ++y) {
    for (int x = search.x0; x <= search.x1; ++x) {
      const double v = At(frame, x, y);
      if (v < thr_det) continue;
      // Local maximum in 3×3.
      bool is_max = true;
      for (int dy = -1; dy <= 1 && is_max; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= frame.rows) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx;
          if ((dx == 0 && dy == 0) || xx < 0 || xx >= frame.cols) continue;
          if (At(frame, xx, yy) > v) {
            is_max = false;
            break;
          }
        }
      }
      if (!is_max) continue;
      bool known = false;
      for (const auto& c : *out) known = known || c.region.Contains(x, y);
      if (known) continue;
      if (static_cast<int>(out->size()) >= opt_.max_candidates) return;
      SpotMeasurement m;
      if (!Grow(frame, x, y, thr_grow, &m)) {
        // Too large: remember its extent so that its other seeds are skipped.
        m.region = Clip(PixelBox{x - opt_.max_extent_px, y - opt_.max_extent_px, x + opt_.max_extent_px,
                                 y + opt_.max_extent_px},
                        frame);
        m.area_px = -1;
        out->push_back(m);
        continue;
      }
      if (!MeasureCentroid(frame, m.region, noise.sigma_dn, &m)) {
        m.area_px = -1;  // mark unusable but keep the region to skip its seeds
      }
      out->push_back(m);
    }
  }
}

// Lamps far apart (short range) grow as separate regions: merge regions whose
// boxes are within cluster_gap_px of each other (the union is re-measured).
void SpotDetector::MergeClusters(const cv::Mat& frame, const NoiseStats& noise, std::size_t first,
                                 std::vector<SpotMeasurement>* v) {
  const int G = opt_.cluster_gap_px;
  auto gap = [](const PixelBox& a, const PixelBox& b) {
    const int gx = std::max({0, a.x0 - b.x1, b.x0 - a.x1});
    const int gy = std::max({0, a.y0 - b.y1, b.y0 - a.y1});
    return std::max(gx, gy);
  };
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = first; i < v->size(); ++i) {
      auto& a = (*v)[i];
      if (a.area_px <= 0) continue;
      for (std::size_t j = i + 1; j < v->size(); ++j) {
        auto& b = (*v)[j];
        if (b.area_px <= 0 || gap(a.region, b.region) > G) continue;
        a.region = {std::min(a.region.x0, b.region.x0), std::min(a.region.y0, b.region.y0),
                    std::max(a.region.x1, b.region.x1), std::max(a.region.y1, b.region.y1)};
        a.area_px += b.area_px;
        a.peak_dn = std::max(a.peak_dn, b.peak_dn);
        b.area_px = 0;
        b.region = a.region;  // keeps its seeds skipped
        a.clipped = true;     // marker: re-measure below
        changed = true;
      }
    }
  }
  for (std::size_t i = first; i < v->size(); ++i) {
    auto& a = (*v)[i];
    if (a.area_px > 0 && a.clipped) {
      const int area = a.area_px;
      const double peak = a.peak_dn;
      if (!MeasureCentroid(frame, a.region, noise.sigma_dn, &a)) a.area_px = -1;
      else {
        a.area_px = area;
        a.peak_dn = peak;
      }
    }
  }
}

void SpotDetector::FindInFrame(const cv::Mat& frame, std::vector<SpotMeasurement>* out) {
  out->clear();
  if (frame.depth() == CV_8U) {
    Project<std::uint8_t>(frame, &row_sum_, &col_sum_);
  } else {
    Project<std::uint16_t>(frame, &row_sum_, &col_sum_);
  }
  frame_stats_ = FrameStats(frame, 16);
  const int h = std::max(16, opt_.max_extent_px / 2);
  std::vector<int> px, py;
  px.reserve(static_cast<std::size_t>(opt_.projection_peaks));
  py.reserve(static_cast<std::size_t>(opt_.projection_peaks));
  TopHat(col_sum_, h, &prof_, &work_);
  Peaks(prof_, opt_.projection_peaks, 5.0 * ProfileNoise(prof_, &work2_), 4, &px);
  TopHat(row_sum_, h, &prof_, &work_);
  Peaks(prof_, opt_.projection_peaks, 5.0 * ProfileNoise(prof_, &work2_), 4, &py);
  const int r = 16;
  found_.clear();
  for (int y : py)
    for (int x : px) FindInBox(frame, PixelBox{x - r, y - r, x + r, y + r}, frame_stats_, &found_);
  MergeClusters(frame, frame_stats_, 0, &found_);
  for (const auto& m : found_)
    if (m.area_px > 0) out->push_back(m);
}

void SpotDetector::PatchValues(const cv::Mat& frame, int cx, int cy, int half, const SpotMeasurement& m,
                               std::vector<float>* v) {
  const int side = 2 * half + 1;
  v->resize(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  std::size_t k = 0;
  for (int y = cy - half; y <= cy + half; ++y) {
    for (int x = cx - half; x <= cx + half; ++x, ++k) {
      if (x < 0 || y < 0 || x >= frame.cols || y >= frame.rows) {
        (*v)[k] = 0.0f;
        continue;
      }
      const double b = m.background_dn + m.bg_dx * (x - m.x_px) + m.bg_dy * (y - m.y_px);
      (*v)[k] = static_cast<float>(At(frame, x, y) - b);
    }
  }
}

namespace {
// Zero-mean, unit-norm in place; false if flat.
bool Normalise(float* v, std::size_t n) {
  double s = 0;
  for (std::size_t i = 0; i < n; ++i) s += v[i];
  const double mean = s / static_cast<double>(n);
  double ss = 0;
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = static_cast<float>(v[i] - mean);
    ss += static_cast<double>(v[i]) * v[i];
  }
  if (!(ss > 0)) return false;
  const float inv = static_cast<float>(1.0 / std::sqrt(ss));
  for (std::size_t i = 0; i < n; ++i) v[i] *= inv;
  return true;
}
}  // namespace

void SpotDetector::MakeTemplate(const cv::Mat& frame, const SpotMeasurement& m, SpotTemplate* tpl) {
  const int rx = static_cast<int>(std::lround(m.x_px)), ry = static_cast<int>(std::lround(m.y_px));
  int half = std::max({rx - m.region.x0, m.region.x1 - rx, ry - m.region.y0, m.region.y1 - ry}) + 2;
  half = std::clamp(half, 5, 24);
  tpl->half = half;
  PatchValues(frame, rx, ry, half, m, &tpl->values);
  if (!Normalise(tpl->values.data(), tpl->values.size())) tpl->values.clear();
  tpl->size_px = m.size_px;
  tpl->flux_dn = m.flux_dn;
}

double SpotDetector::Ncc(const cv::Mat& frame, const SpotMeasurement& m, const SpotTemplate& tpl) {
  if (!tpl.valid()) return -1.0;
  const int h = tpl.half;
  const int big = h + 1;
  const int bside = 2 * big + 1, side = 2 * h + 1;
  const int rx = static_cast<int>(std::lround(m.x_px)), ry = static_cast<int>(std::lround(m.y_px));
  PatchValues(frame, rx, ry, big, m, &patch_);
  tmp_.resize(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  double best = -1.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      std::size_t k = 0;
      for (int y = 0; y < side; ++y) {
        const float* row = &patch_[static_cast<std::size_t>((y + 1 + dy) * bside + 1 + dx)];
        for (int x = 0; x < side; ++x) tmp_[k++] = row[x];
      }
      if (!Normalise(tmp_.data(), tmp_.size())) continue;
      double c = 0;
      for (std::size_t i = 0; i < tmp_.size(); ++i) c += static_cast<double>(tmp_[i]) * tpl.values[i];
      best = std::max(best, c);
    }
  }
  return best;
}

}  // namespace rk::extract
