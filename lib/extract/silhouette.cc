// Silhouette points of a cylindrical target; method in silhouette.h.
#include "extract/silhouette.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "numeric/robust_stats.h"

namespace rk::extract {

const char* SilhouetteStatusName(SilhouetteStatus s) {
  switch (s) {
    case SilhouetteStatus::kOk:
      return "ok";
    case SilhouetteStatus::kNotFound:
      return "not_found";
    case SilhouetteStatus::kTouchesBorder:
      return "touches_border";
    case SilhouetteStatus::kTooSmall:
      return "too_small";
    case SilhouetteStatus::kBadFit:
      return "bad_fit";
  }
  return "?";
}

const io::OptionTable<SilhouetteOptions>& SilhouetteOptions::Table() {
  using B = io::Bounds;
  using O = SilhouetteOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--k-detect", &O::k_detect, "", B::Closed(2, 100), "Detection threshold in sky-noise sigmas")
          .Integer("--min-area", &O::min_area_px, "px", B::Closed(4, 1e7), "Smallest target region (px)")
          .Integer("--border", &O::border_px, "px", B::Closed(2, 200), "Frame border band used for the sky plane (px)")
          .Real("--psf-sigma", &O::psf_sigma_px, "px", B::Closed(0, 10), "Optics blur sigma assumed for the margins (px)")
          .Real("--min-width", &O::min_width_px, "px", B::Closed(1, 1e4), "Narrower bodies are not measured (px)")
          .Real("--min-length-ratio", &O::min_length_ratio, "", B::AtLeast(1).Finite(),
                "Image length / width below this (near tail chase) is not measured");
  return table;
}

namespace {

struct Plane {
  double a = 0, b = 0, c = 0;
  double At(double x, double y) const { return a + b * x + c * y; }
};

// Least-squares plane through (x, y, value) samples, 3σ-clipped twice (σ from the MAD). False if too few.
bool FitPlane(const std::vector<Eigen::Vector3d>& s, Plane* p, double* sigma) {
  std::vector<char> use(s.size(), 1);
  for (int pass = 0; pass < 3; ++pass) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    std::size_t n = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (!use[i]) continue;
      const Eigen::Vector3d row(1.0, s[i].x(), s[i].y());
      A += row * row.transpose();
      rhs += row * s[i].z();
      ++n;
    }
    if (n < 10) return false;
    const Eigen::Vector3d q = A.ldlt().solve(rhs);
    *p = {q(0), q(1), q(2)};
    std::vector<double> res;
    res.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i)
      if (use[i]) res.push_back(std::abs(s[i].z() - p->At(s[i].x(), s[i].y())));
    *sigma = std::max(1.4826 * numeric::UpperMedian(res), 1e-6);
    if (pass == 2) break;
    for (std::size_t i = 0; i < s.size(); ++i)
      use[i] = std::abs(s[i].z() - p->At(s[i].x(), s[i].y())) <= 3.0 * *sigma;
  }
  return true;
}

// Bilinear sample of a CV_32FC1 image; outside the image → 0 (the sky of an α image).
inline double Bilinear(const cv::Mat& m, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const double tx = x - fx, ty = y - fy;
  auto at = [&](int xx, int yy) -> double {
    if (xx < 0 || yy < 0 || xx >= m.cols || yy >= m.rows) return 0.0;
    return m.ptr<float>(yy)[xx];
  };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

struct Frame2 {
  Eigen::Vector2d o, d, n;  // origin (α-image coordinates), unit axis, unit left normal (d.y, −d.x)
  Eigen::Vector2d At(double u, double v) const { return o + u * d + v * n; }
};

struct Profile {
  std::vector<double> u, S, C;
};

constexpr double kStep = 0.5;  // sampling step along and across the axis (px)

// Profiles across the axis. Without `prior`: every profile spans v ∈ [−V, V] and is integrated as is.
// With `prior` (a first pass on the same u grid): profile i spans its own target extent plus `margin`,
// [C_i − S_i/2 − margin, C_i + S_i/2 + margin], and a straight sky baseline through the mean α of its outer
// 1.5 px on either side is subtracted before integrating. The narrow window keeps the integrated sky
// error (noise, 8-bit steps of a sky gradient, a slightly tilted sky plane) small; without it C is biased
// by ∝ V³/S as the nose narrows.
Profile Sample(const cv::Mat& alpha, const Frame2& f, double u0, double u1, double V,
               const Profile* prior = nullptr, double margin = 0.0, bool subtract_baseline = false) {
  Profile p;
  const int nu = static_cast<int>(std::ceil((u1 - u0) / kStep)) + 1;
  std::vector<double> a;
  p.u.reserve(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i) {
    const double u = u0 + kStep * i;
    double vc = 0.0, half = V;
    if (prior) {
      vc = prior->C[static_cast<std::size_t>(i)];
      half = std::max(prior->S[static_cast<std::size_t>(i)], 0.0) / 2.0 + margin;
    }
    const int nv = static_cast<int>(std::ceil(2.0 * half / kStep)) + 1;
    const double v0 = vc - half;
    a.resize(static_cast<std::size_t>(nv));
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector2d q = f.At(u, v0 + kStep * j);
      a[static_cast<std::size_t>(j)] = Bilinear(alpha, q.x(), q.y());
    }
    double lo = 0, slope = 0, v_lo = v0;
    if (prior && subtract_baseline) {
      const int nb = std::min(3, nv / 4);
      double hi = 0;
      for (int j = 0; j < nb; ++j) {
        lo += a[static_cast<std::size_t>(j)];
        hi += a[static_cast<std::size_t>(nv - 1 - j)];
      }
      lo /= std::max(nb, 1);
      hi /= std::max(nb, 1);
      v_lo = v0 + kStep * 0.5 * (nb - 1);
      const double v_hi = v0 + kStep * (nv - 1 - 0.5 * (nb - 1));
      slope = (hi - lo) / (v_hi - v_lo);
    }
    double s = 0.0, sv = 0.0;
    for (int j = 0; j < nv; ++j) {
      const double v = v0 + kStep * j;
      const double x = a[static_cast<std::size_t>(j)] - (lo + slope * (v - v_lo));
      s += x;
      sv += x * v;
    }
    s *= kStep;
    sv *= kStep;
    p.u.push_back(u);
    p.S.push_back(s);
    p.C.push_back(std::abs(s) > 1e-9 ? sv / s : vc);
  }
  return p;
}

struct Line {
  double a = 0, b = 0, rms = 0;  // y = a + b x
  int n = 0;
};

// Least-squares line, 3σ-clipped twice. n = 0 if fewer than 3 points.
Line FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  Line L;
  std::vector<char> use(x.size(), 1);
  for (int pass = 0; pass < 3; ++pass) {
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!use[i]) continue;
      sw += 1;
      sx += x[i];
      sy += y[i];
      sxx += x[i] * x[i];
      sxy += x[i] * y[i];
    }
    if (sw < 3) {
      L.n = 0;
      return L;
    }
    const double det = sw * sxx - sx * sx;
    if (std::abs(det) < 1e-12) {
      L.n = 0;
      return L;
    }
    L.b = (sw * sxy - sx * sy) / det;
    L.a = (sy - L.b * sx) / sw;
    double ss = 0;
    int n = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!use[i]) continue;
      const double r = y[i] - L.a - L.b * x[i];
      ss += r * r;
      ++n;
    }
    L.rms = std::sqrt(ss / n);
    L.n = n;
    if (pass == 2) break;
    const double lim = std::max(3.0 * L.rms, 1e-6);
    for (std::size_t i = 0; i < x.size(); ++i) use[i] = std::abs(y[i] - L.a - L.b * x[i]) <= lim;
  }
  return L;
}

// ---- ExtractSilhouette in stages: 1 detect the region, 2 its coverage α, 3 initial axis, 4 side lines
// and axis from the profiles, 5 tail (and side lines again from the edges), 6 nose.

// Stage 1: the largest region that differs from the sky plane fitted on the border band.
struct Detection {
  cv::Mat img;  // the frame as CV_32F
  Plane sky;
  double sigma = 0;  // sky noise (DN)
  cv::Mat labels;    // connected components of the detection mask
  int label = -1;    // the region's label
  cv::Rect box;      // its bounding box
};

// Stage 2: the region's neighbourhood and its coverage.
struct Coverage {
  cv::Rect roi;           // in the frame
  cv::Mat region, grown;  // the region, and it grown by 3 σ_psf + 3 px, in the roi
  cv::Mat alpha;          // coverage α = (I − sky)/(B − sky) in the roi
};

// Stages 3–4: the axis frame, the region's extent along it and the body's side lines.
struct Body {
  Frame2 f;
  double umin = 0, umax = 0, vmax = 0;  // extent of the region in the axis frame
  Line e1, e2;                          // side lines v = a + b u
  double width = 0, u_first = 0, u_last = 0, u_cone = 0;
  Profile p;
};

// Stage 1. False when no region is found (res.status stays as it is) or it touches the border.
bool DetectRegion(const cv::Mat& frame, const SilhouetteOptions& opt, Detection* d, SilhouetteResult* res) {
  const int W = frame.cols, H = frame.rows;
  const int bw = std::min({opt.border_px, W / 4, H / 4});
  if (bw < 1) return false;
  cv::Mat& img = d->img;
  frame.convertTo(img, CV_32F);

  // Sky plane on the border band, detection.
  std::vector<Eigen::Vector3d> samples;
  const int stride = std::max(1, (W + H) / 1500);
  for (int y = 0; y < H; y += stride) {
    const float* row = img.ptr<float>(y);
    const bool edge_row = y < bw || y >= H - bw;
    for (int x = 0; x < W; x += edge_row ? stride : 1) {
      if (!edge_row && x == bw) x = W - bw;  // jump over the interior
      samples.emplace_back(x, y, row[x]);
    }
  }
  Plane& sky = d->sky;
  double& sigma = d->sigma;
  if (!FitPlane(samples, &sky, &sigma)) return false;
  res->sky_sigma_dn = sigma;
  cv::Mat mask(H, W, CV_8UC1);
  const double thr = opt.k_detect * sigma;
  for (int y = 0; y < H; ++y) {
    const float* row = img.ptr<float>(y);
    std::uint8_t* m = mask.ptr<std::uint8_t>(y);
    const double base = sky.a + sky.c * y;
    for (int x = 0; x < W; ++x) m[x] = std::abs(row[x] - (base + sky.b * x)) > thr ? 255 : 0;
  }
  cv::Mat stats, centroids;
  const int nl = cv::connectedComponentsWithStats(mask, d->labels, stats, centroids, 8, CV_32S);
  int best = -1, best_area = 0;
  for (int l = 1; l < nl; ++l) {
    const int a = stats.at<int>(l, cv::CC_STAT_AREA);
    if (a > best_area) {
      best_area = a;
      best = l;
    }
  }
  if (best < 0 || best_area < opt.min_area_px) return false;
  res->region_area_px = best_area;
  d->label = best;
  d->box = cv::Rect(stats.at<int>(best, cv::CC_STAT_LEFT), stats.at<int>(best, cv::CC_STAT_TOP),
                    stats.at<int>(best, cv::CC_STAT_WIDTH), stats.at<int>(best, cv::CC_STAT_HEIGHT));
  const cv::Rect& box = d->box;
  if (box.x == 0 || box.y == 0 || box.x + box.width == W || box.y + box.height == H) {
    res->status = SilhouetteStatus::kTouchesBorder;
    return false;
  }
  return true;
}

// Body level B: median of the frame over the region's interior (the region eroded by 3 σ_psf + 2 px, so
// that no edge pixel and no selection by value biases it; for very thin regions the stronger half of the
// region by |I − sky|). `sign`: +1 for a target brighter than the sky.
double BodyLevel(const cv::Mat& img, const Coverage& c, const std::vector<double>& inside, double sign,
                 const SilhouetteOptions& opt) {
  const cv::Rect& roi = c.roi;
  std::vector<double> level;
  {
    const int er = static_cast<int>(std::ceil(3.0 * opt.psf_sigma_px)) + 2;
    cv::Mat core;
    cv::erode(c.region, core, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * er + 1, 2 * er + 1)));
    for (int y = 0; y < roi.height; ++y) {
      const float* row = img.ptr<float>(roi.y + y);
      const std::uint8_t* cr = core.ptr<std::uint8_t>(y);
      for (int x = 0; x < roi.width; ++x)
        if (cr[x]) level.push_back(row[roi.x + x]);
    }
  }
  if (level.size() < 20) {
    level.clear();
    std::vector<double> mag;
    for (double v : inside) mag.push_back(sign * v);
    const double med = numeric::UpperMedian(mag);
    std::size_t i = 0;
    for (int y = 0; y < roi.height; ++y) {
      const float* row = img.ptr<float>(roi.y + y);
      const std::uint8_t* reg = c.region.ptr<std::uint8_t>(y);
      for (int x = 0; x < roi.width; ++x)
        if (reg[x] && mag[i++] >= med) level.push_back(row[roi.x + x]);
    }
  }
  return numeric::UpperMedian(level);
}

// Stage 2: local sky on a ring around the region, coverage α. False when the contrast is too low or of
// the wrong sign.
bool CoverageOf(const Detection& d, const SilhouetteOptions& opt, Coverage* c, SilhouetteResult* res) {
  const cv::Mat& img = d.img;
  const int W = img.cols, H = img.rows;
  const cv::Rect& box = d.box;
  const int grow = static_cast<int>(std::ceil(3.0 * opt.psf_sigma_px)) + 3;
  const int margin = grow + 8;
  cv::Rect& roi = c->roi;
  roi = cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin);
  roi &= cv::Rect(0, 0, W, H);
  c->region = (d.labels(roi) == d.label);
  cv::dilate(c->region, c->grown,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * grow + 1, 2 * grow + 1)));
  std::vector<Eigen::Vector3d> samples;
  for (int y = 0; y < roi.height; ++y) {
    const float* row = img.ptr<float>(roi.y + y);
    const std::uint8_t* g = c->grown.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x)
      if (!g[x]) samples.emplace_back(roi.x + x, roi.y + y, row[roi.x + x]);
  }
  Plane local;
  double local_sigma = 0;
  if (!FitPlane(samples, &local, &local_sigma)) local = d.sky;
  // α = (I − sky)/(B − sky) per pixel: the target has one radiance, the sky a gradient.
  std::vector<double> inside;
  for (int y = 0; y < roi.height; ++y) {
    const float* row = img.ptr<float>(roi.y + y);
    const std::uint8_t* reg = c->region.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x)
      if (reg[x]) inside.push_back(row[roi.x + x] - local.At(roi.x + x, roi.y + y));
  }
  const double sign = numeric::UpperMedian(inside) >= 0 ? 1.0 : -1.0;
  const double body = BodyLevel(img, *c, inside, sign, opt);
  c->alpha.create(roi.size(), CV_32FC1);
  double contrast_sum = 0;
  for (int y = 0; y < roi.height; ++y) {
    const float* row = img.ptr<float>(roi.y + y);
    float* a = c->alpha.ptr<float>(y);
    for (int x = 0; x < roi.width; ++x) {
      const double sk = local.At(roi.x + x, roi.y + y);
      const double cc = body - sk;
      a[x] = std::abs(cc) > 1e-9 ? static_cast<float>((row[roi.x + x] - sk) / cc) : 0.0f;
      contrast_sum += cc;
    }
  }
  const double contrast = contrast_sum / std::max(1, roi.area());
  res->contrast_dn = contrast;
  return std::abs(contrast) > 3.0 * d.sigma && (contrast > 0) == (sign > 0);
}

// Stage 3: initial axis from the moments of the region's coverage, and the region's extent along and
// across it. False when the coverage has no weight.
bool InitialAxis(const Coverage& c, Body* body) {
  const cv::Rect& roi = c.roi;
  double m0 = 0, mx = 0, my = 0;
  for (int y = 0; y < roi.height; ++y) {
    const float* a = c.alpha.ptr<float>(y);
    const std::uint8_t* g = c.grown.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x) {
      if (!g[x]) continue;
      const double w = std::clamp(static_cast<double>(a[x]), 0.0, 1.5);
      m0 += w;
      mx += w * x;
      my += w * y;
    }
  }
  if (!(m0 > 0)) return false;
  mx /= m0;
  my /= m0;
  double cxx = 0, cxy = 0, cyy = 0;
  for (int y = 0; y < roi.height; ++y) {
    const float* a = c.alpha.ptr<float>(y);
    const std::uint8_t* g = c.grown.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x) {
      if (!g[x]) continue;
      const double w = std::clamp(static_cast<double>(a[x]), 0.0, 1.5);
      cxx += w * (x - mx) * (x - mx);
      cxy += w * (x - mx) * (y - my);
      cyy += w * (y - my) * (y - my);
    }
  }
  const double theta = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  Frame2& f = body->f;
  f.o = Eigen::Vector2d(mx, my);
  f.d = Eigen::Vector2d(std::cos(theta), std::sin(theta));
  f.n = Eigen::Vector2d(f.d.y(), -f.d.x());
  double umin = 1e300, umax = -1e300, vmax = 0;
  for (int y = 0; y < roi.height; ++y) {
    const std::uint8_t* reg = c.region.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x) {
      if (!reg[x]) continue;
      const Eigen::Vector2d q = Eigen::Vector2d(x, y) - f.o;
      umin = std::min(umin, q.dot(f.d));
      umax = std::max(umax, q.dot(f.d));
      vmax = std::max(vmax, std::abs(q.dot(f.n)));
    }
  }
  body->umin = umin;
  body->umax = umax;
  body->vmax = vmax;
  return true;
}

// Indexes of the first and last profile samples where S reaches half of `smax`.
void HalfMaxExtent(const Profile& p, double smax, std::size_t* i0, std::size_t* i1) {
  *i0 = 0;
  *i1 = p.S.size() - 1;
  while (*i0 < p.S.size() && p.S[*i0] < 0.5 * smax) ++*i0;
  while (*i1 > *i0 && p.S[*i1] < 0.5 * smax) --*i1;
}

// Stage 4, one pass on the profile body->p: landmarks, body width, cone start and the side lines over
// the body. False (with the status) when the region is too small or the lines do not fit.
bool SideLinesFromProfile(const SilhouetteOptions& opt, double mrg, std::size_t i0, std::size_t i1, Body* body,
                          SilhouetteResult* res) {
  const Profile& p = body->p;
  // Landmarks robust to noise: u where S first / last reaches half its maximum. The tail extreme is at
  // most half a width before u_first (b ≤ w); the nose tip lies beyond u_last.
  const double u_first = body->u_first = p.u[i0];
  const double u_last = body->u_last = p.u[i1];
  // Body width: median over 25–55 % of [u_first, u_last] from the tail.
  std::vector<double> mid;
  for (std::size_t i = 0; i < p.u.size(); ++i) {
    const double t = (p.u[i] - u_first) / std::max(u_last - u_first, 1e-9);
    if (t >= 0.25 && t <= 0.55) mid.push_back(p.S[i]);
  }
  const double width = body->width = numeric::UpperMedian(mid);
  if (!(width >= opt.min_width_px)) {
    res->status = SilhouetteStatus::kTooSmall;
    return false;
  }
  // Body region: from past the tail ellipse (b ≤ width/2) to before the cone (S < 0.97 width).
  const double body_start = u_first + 0.5 * width + mrg;
  std::size_t ib = 0;
  while (ib < p.u.size() && p.u[ib] < body_start) ++ib;
  // Cone start: the running median of S (over 10 px) first falls below W − max(3 % W, 4 σ_S), σ_S the
  // profile-to-profile scatter of S (MAD); noise alone does not end the body early.
  const std::size_t half_win = 10;
  std::vector<double> smooth(p.S.size()), scatter;
  for (std::size_t i = 0; i < p.S.size(); ++i) {
    const std::size_t a = i > half_win ? i - half_win : 0, z = std::min(p.S.size() - 1, i + half_win);
    smooth[i] = numeric::UpperMedian(std::vector<double>(p.S.begin() + static_cast<std::ptrdiff_t>(a),
                                           p.S.begin() + static_cast<std::ptrdiff_t>(z) + 1));
  }
  for (std::size_t i = 0; i < p.u.size(); ++i) {
    const double t = (p.u[i] - u_first) / std::max(u_last - u_first, 1e-9);
    if (t >= 0.25 && t <= 0.55) scatter.push_back(std::abs(p.S[i] - smooth[i]));
  }
  const double sigma_s = 1.4826 * numeric::UpperMedian(scatter);
  const double drop = std::max(0.03 * width, 4.0 * sigma_s);
  std::size_t ic = ib;
  while (ic < p.u.size() && smooth[ic] >= width - drop) ++ic;
  body->u_cone = ic < p.u.size() ? p.u[ic] : u_last;
  const double body_end = body->u_cone - mrg;
  std::vector<double> bu, b1, b2;
  for (std::size_t i = ib; i < p.u.size() && p.u[i] <= body_end; ++i) {
    bu.push_back(p.u[i]);
    b1.push_back(p.C[i] + 0.5 * p.S[i]);
    b2.push_back(p.C[i] - 0.5 * p.S[i]);
  }
  if (bu.size() < 8) {
    res->status = SilhouetteStatus::kTooSmall;
    return false;
  }
  body->e1 = FitLine(bu, b1);
  body->e2 = FitLine(bu, b2);
  if (body->e1.n < 3 || body->e2.n < 3) {
    res->status = SilhouetteStatus::kBadFit;
    return false;
  }
  res->side_rms_px = std::sqrt(0.5 * (body->e1.rms * body->e1.rms + body->e2.rms * body->e2.rms));
  return true;
}

// Stage 4: profiles; nose end; side lines; the axis refined twice on the mid-line of the side lines.
// False (with the status) when the region is too small or does not fit a body.
bool RefineAxis(const cv::Mat& alpha, const SilhouetteOptions& opt, double mrg, Body* body, SilhouetteResult* res) {
  Frame2& f = body->f;
  double& umin = body->umin;
  double& umax = body->umax;
  const double V = body->vmax + mrg + 3.0;
  Profile& p = body->p;
  bool oriented = false;
  const double local_margin = 3.0 * opt.psf_sigma_px + 3.0;
  auto profile = [&]() {
    const Profile first = Sample(alpha, f, umin - mrg - 2.0, umax + mrg + 2.0, V);
    return Sample(alpha, f, umin - mrg - 2.0, umax + mrg + 2.0, V, &first, local_margin);
  };
  for (int iter = 0; iter < 3; ++iter) {
    p = profile();
    const double smax = *std::max_element(p.S.begin(), p.S.end());
    if (!(smax > 0)) return false;
    std::size_t i0 = 0, i1 = 0;
    HalfMaxExtent(p, smax, &i0, &i1);
    if (i1 <= i0 + 4) {
      res->status = SilhouetteStatus::kTooSmall;
      return false;
    }
    if (!oriented) {
      // Nose end = the narrower end (mean width over the outer 12 % of the extent).
      const std::size_t k = std::max<std::size_t>(2, (i1 - i0) * 12 / 100);
      double a = 0, b = 0;
      for (std::size_t i = 0; i < k; ++i) {
        a += p.S[i0 + i];
        b += p.S[i1 - i];
      }
      if (a < b) {  // the low-u end is the nose: turn the frame round
        f.d = -f.d;
        f.n = -f.n;
        std::swap(umin, umax);
        umin = -umin;
        umax = -umax;
        p = profile();
        HalfMaxExtent(p, smax, &i0, &i1);
      }
      oriented = true;
    }
    if (!SideLinesFromProfile(opt, mrg, i0, i1, body, res)) return false;
    if (iter == 2) break;
    // Mid-line v = a + b u → new origin and direction.
    const double am = 0.5 * (body->e1.a + body->e2.a), bm = 0.5 * (body->e1.b + body->e2.b);
    const Eigen::Vector2d o2 = f.At(0.0, am);
    const Eigen::Vector2d d2 = (f.d + bm * f.n).normalized();
    const double shift = (o2 - f.o).dot(d2);  // keep u ranges consistent
    f.o = o2;
    f.d = d2;
    f.n = Eigen::Vector2d(d2.y(), -d2.x());
    umin -= shift;
    umax -= shift;
  }
  if (res->side_rms_px > std::max(0.5, 0.1 * body->width)) {
    res->status = SilhouetteStatus::kBadFit;
    return false;
  }
  return true;
}

// Stage 5. Tail. Body plateau A(v): mean α at offset v from the centre line over the body (blurred near the
// edges). Along lines of constant v (|v| ≤ min(0.8 w, w − 3 s), A ≥ 0.5): rough edge e0 = first drop below
// A/2 walking out of the body; then e = e0 + h − ∫_{e0−h}^{e0+h} α du / A(v), h = 3 σ_psf + 2 (a short
// window keeps the integrated sky noise small). Each such edge is the outline averaged over the effective
// blur across the lines (PSF, pixel area and resampling, variance s²): e_meas(v) = e(v) + (s²/2) e''(v). s²
// is measured on the body's own side edges: for a blurred step, ∫ t (H(−t) − A(w + t)) dt = −s²/2. Fit e(v)
// = u0 − b [g(v) + (s²/2) g''(v)], g = sqrt(1 − (v/w)²), linear in (u0, b), b ≥ 0.
class TailFit {
 public:
  TailFit(const cv::Mat& alpha, const SilhouetteOptions& opt, double mrg, Body* body)
      : alpha_(alpha), f_(body->f), body_(body), mrg_(mrg) {
    body_u0_ = body->u_first + 0.5 * body->width + mrg;
    body_u1_ = std::max(body_u0_ + 1.0, body->u_cone - mrg);
    h_ = 3.0 * opt.psf_sigma_px + 2.0;
    blur2_ = MeasureBlur2();
    s_edge_ = std::max(0.3, std::sqrt(blur2_));
    n_edge_ = static_cast<int>(std::ceil(2.0 * h_ / kHu));
  }

  // Side lines from the edges, the tail fitted on them, and both again from nearer the tail (see below).
  // False when too few lines cross the tail.
  bool Run(SilhouetteResult* res) {
    res->edge_blur_px = std::sqrt(blur2_);
    SideLinesFromEdges(body_u0_);
    if (!FitTail(false)) return false;
    // The side lines are straight from the tail rim (u0) on; until the tail was located they started past the
    // widest possible ellipse (half a width). Refit them from 3 s past u0 — a shorter extrapolation to u0 —
    // and the tail on them. On a flat tail ellipse (b < 0.2 w: within ≈ 12° of side-on) the tail edges are
    // located by the matched filter too: its noise is ≈ 0.6× the window integral's, and the curvature offset
    // (s²/2) e'' the fit models holds for it only while the outline is flat (on rounder ellipses it biased the
    // points by up to 0.09 px on noise-free images, against 0.013 px for the integral).
    const double near = u0_ + 3.0 * std::sqrt(blur2_) + 1.0;
    const bool refit_sides = near < body_u0_ - 2.0, matched = b_ < 0.2 * HalfWidth(u0_);
    if (refit_sides) SideLinesFromEdges(near);
    if ((refit_sides || matched) && !FitTail(matched)) return false;
    res->tail_b_px = b_;
    return true;
  }

  double u0() const { return u0_; }
  double blur2() const { return blur2_; }
  double HalfWidth(double u) const {
    const Line& e1 = body_->e1;
    const Line& e2 = body_->e2;
    return 0.5 * ((e1.a + e1.b * u) - (e2.a + e2.b * u));
  }

 private:
  static constexpr double kHu = 0.25;  // step along the lines across an edge (px)

  double Centre(double u) const {
    const Line& e1 = body_->e1;
    const Line& e2 = body_->e2;
    return 0.5 * ((e1.a + e1.b * u) + (e2.a + e2.b * u));
  }

  // Mean α across the body at offset v from the centre line (averaged along the body).
  double Plateau(double v) const {
    double A = 0;
    int na = 0;
    for (double u = body_u0_; u <= body_u1_; u += kStep) {
      const Eigen::Vector2d q = f_.At(u, Centre(u) + v);
      A += Bilinear(alpha_, q.x(), q.y());
      ++na;
    }
    return A / std::max(na, 1);
  }

  // s² of the side edges: each side ∫ t (H(−t) − A) dt = −s²/2; two sides: −s².
  double MeasureBlur2() const {
    const double wb = HalfWidth(0.5 * (body_u0_ + body_u1_));
    double m = 0;
    for (int side = -1; side <= 1; side += 2) {
      for (double t = -h_; t <= h_ + 1e-9; t += kHu) {
        const double a = Plateau(side * (wb + t));
        m += t * ((t < 0 ? 1.0 : 0.0) - a) * kHu;
      }
    }
    return std::max(0.0, -m);
  }

  // Matched-filter edge location: a few Gauss–Newton steps of the blurred-step model α(x) = A Φ(±(e − x)/s)
  // over the window [e − h, e + h] of a line sampled by `at(x)` (sign +1: target at x < e). It weights each
  // sample by the model's slope there, so the samples far from the edge, which carry only noise, no longer
  // count as they do in a window integral (≈ 0.6× its noise). Unbiased for any symmetric edge spread (the
  // residual of a wrong width of the spread is odd about e, its weight even). Starts from a window-integral
  // estimate.
  template <typename At>
  double MatchedEdge(const At& at, double e, double A, double sign) const {
    for (int it = 0; it < 3; ++it) {
      double num = 0, den = 0;
      for (int i = 0; i <= n_edge_; ++i) {
        const double x = e - h_ + i * kHu;
        const double t = sign * (e - x) / s_edge_;
        const double g = A * std::exp(-0.5 * t * t) / (std::sqrt(2.0 * M_PI) * s_edge_) * sign;
        num += g * (at(x) - A * 0.5 * std::erfc(-t / std::sqrt(2.0)));
        den += g * g;
      }
      if (!(den > 0)) break;
      const double step = std::clamp(num / den, -0.5, 0.5);
      e += step;
      if (std::abs(step) < 1e-4) break;
    }
    return e;
  }

  // Window-integral edge location on the same window, from a rough edge x_e: ∫ α over [x_e − h, x_e − h +
  // n·hu] (trapezoid) is the covered length times A, so e = window start + ∫/A (sign +1: target at x < e) or
  // window end − ∫/A (sign −1). Exact for a blurred straight step; the start of MatchedEdge.
  template <typename At>
  double WindowEdge(const At& at, double x_e, double A, double sign) const {
    double integral = 0;
    for (int i = 0; i <= n_edge_; ++i)
      integral += ((i == 0 || i == n_edge_) ? 0.5 : 1.0) * at(x_e - h_ + i * kHu);
    integral *= kHu;
    return sign > 0 ? x_e - h_ + integral / A : x_e - h_ + n_edge_ * kHu - integral / A;
  }

  // 5a. Side lines again from the edges alone. A profile's S integrates the whole interior too, whose noise
  // carries no width information (≈ 2× the variance of the edge windows on a 28-px body) and whose mean
  // error (the body level B) scales with the width. Each edge: WindowEdge then MatchedEdge across it, with
  // A_± = the plateau just inside that edge (a shaded body has a different level on either side). The lines
  // are fitted over [from_u, body_u1].
  void SideLinesFromEdges(double from_u) {
    const double wb = HalfWidth(0.5 * (body_u0_ + body_u1_));
    const double A_hi = Plateau(wb - h_), A_lo = Plateau(-(wb - h_));
    if (!(A_hi >= 0.5 && A_lo >= 0.5 && wb >= 2.0 * h_)) return;  // narrower: the windows span the profile anyway
    std::vector<double> bu, b1, b2;
    for (double u = from_u; u <= body_u1_; u += kStep) {
      const double v_hi = body_->e1.a + body_->e1.b * u, v_lo = body_->e2.a + body_->e2.b * u;
      bu.push_back(u);
      auto across = [&](double v) {
        const Eigen::Vector2d q = f_.At(u, v);
        return Bilinear(alpha_, q.x(), q.y());
      };
      b1.push_back(MatchedEdge(across, WindowEdge(across, v_hi, A_hi, 1.0), A_hi, 1.0));
      b2.push_back(MatchedEdge(across, WindowEdge(across, v_lo, A_lo, -1.0), A_lo, -1.0));
    }
    const Line f1 = FitLine(bu, b1), f2 = FitLine(bu, b2);
    if (f1.n >= 3 && f2.n >= 3) {
      body_->e1 = f1;
      body_->e2 = f2;
    }
  }

  // The tail (u0, b) from the edges along lines of constant v; `matched`: MatchedEdge after WindowEdge.
  bool FitTail(bool matched) {
    const double u_first = body_->u_first;
    u0_ = u_first;
    b_ = 0;
    for (int iter = 0; iter < 2; ++iter) {
      const double w = HalfWidth(u0_);
      const double c = Centre(u0_);
      double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
      int count = 0;
      // Lines closer to a side edge than 3 s see that edge's blur too (the curvature model then fails).
      const double vmax = std::min(0.8 * w, w - 3.0 * std::sqrt(blur2_));
      for (double v = -vmax; v <= vmax + 1e-9; v += kStep) {
        const double A = Plateau(v);
        if (!(A >= 0.5)) continue;
        auto alpha_at = [&](double u) {
          const Eigen::Vector2d q = f_.At(u, c + v);
          return Bilinear(alpha_, q.x(), q.y());
        };
        double e0 = std::nan("");
        for (double u = u_first + w + mrg_; u >= u_first - w - mrg_ - 2.0; u -= kHu) {
          if (alpha_at(u) < 0.5 * A) {
            e0 = u + 0.5 * kHu;
            break;
          }
        }
        if (!std::isfinite(e0)) continue;
        double e = WindowEdge(alpha_at, e0, A, -1.0);        // target at u > e
        if (matched) e = MatchedEdge(alpha_at, e, A, -1.0);  // target at u > e
        const double q = std::max(1e-3, 1.0 - (v / w) * (v / w));
        const double g = -(std::sqrt(q) - 0.5 * blur2_ / (w * w * q * std::sqrt(q)));  // −(g + (s²/2) g'')
        s11 += 1;
        s12 += g;
        s22 += g * g;
        r1 += e;
        r2 += g * e;
        ++count;
      }
      if (count < 3) return false;
      const double det = s11 * s22 - s12 * s12;
      b_ = std::abs(det) > 1e-12 ? (s11 * r2 - s12 * r1) / det : 0.0;
      if (b_ < 0.0) b_ = 0.0;
      u0_ = (r1 - b_ * s12) / s11;
    }
    return true;
  }

  const cv::Mat& alpha_;
  const Frame2& f_;
  Body* body_;
  double mrg_;
  double body_u0_ = 0, body_u1_ = 0, h_ = 0, blur2_ = 0, s_edge_ = 0;
  int n_edge_ = 0;
  double u0_ = 0, b_ = 0;
};

// Stage 6, nose: straight S(u) and C(u) over the cone (u ≥ u_cone, s_lo ≤ S ≤ s_hi). True when S narrows.
bool FitCone(const Body& body, double s_lo, double s_hi, Line* ls, Line* lc) {
  const Profile& p = body.p;
  std::vector<double> cu, cs, cc;
  for (std::size_t i = 0; i < p.u.size(); ++i) {
    if (p.u[i] < body.u_cone) continue;
    if (p.S[i] >= s_lo && p.S[i] <= s_hi) {
      cu.push_back(p.u[i]);
      cs.push_back(p.S[i]);
      cc.push_back(p.C[i]);
    }
  }
  *ls = FitLine(cu, cs);
  *lc = FitLine(cu, cc);
  return ls->n >= 3 && ls->b < 0.0;
}

// Stage 6. A first fit over 0.15 W ≤ S ≤ 0.7 W gives the cone's slope k = dS/du; the final fit takes the
// whole straight part, S from max(0.08 W, 3 s |k|) (the blur rounds S only within 3 s of the tip) to
// min(0.9 W, W − 3 s |k|) (and of the cone base): a 1.5× longer lever cuts the tip's along-axis error by
// ≈ 40 % (noise) and 60 % (sampling), docs/benchmarks.md, issue 4. False (kBadFit) without a cone.
bool FitNose(const Body& body, double blur2, Line* ls, Line* lc, SilhouetteResult* res) {
  const double width = body.width;
  if (!FitCone(body, 0.15 * width, 0.7 * width, ls, lc)) {
    res->status = SilhouetteStatus::kBadFit;
    return false;
  }
  const double blur_s = 3.0 * std::abs(ls->b) * std::sqrt(blur2);
  const double s_lo = std::max(0.08 * width, blur_s), s_hi = std::min(0.9 * width, width - blur_s);
  Line ls2, lc2;
  if (s_hi > s_lo + 0.2 * width && FitCone(body, s_lo, s_hi, &ls2, &lc2)) {
    *ls = ls2;
    *lc = lc2;
  }
  return true;
}

}  // namespace

SilhouetteResult ExtractSilhouette(const cv::Mat& frame, const SilhouetteOptions& opt) {
  SilhouetteResult res;
  CV_Assert(frame.type() == CV_8UC1 || frame.type() == CV_16UC1);
  Detection det;
  if (!DetectRegion(frame, opt, &det, &res)) return res;
  Coverage cov;
  if (!CoverageOf(det, opt, &cov, &res)) return res;
  Body body;
  if (!InitialAxis(cov, &body)) return res;
  const double mrg = 3.0 * opt.psf_sigma_px + 2.0;
  if (!RefineAxis(cov.alpha, opt, mrg, &body, &res)) return res;
  TailFit tail(cov.alpha, opt, mrg, &body);
  if (!tail.Run(&res)) {
    res.status = SilhouetteStatus::kTooSmall;
    return res;
  }
  const double u0 = tail.u0();
  Line ls, lc;
  if (!FitNose(body, tail.blur2(), &ls, &lc, &res)) return res;
  const double u_tip = -ls.a / ls.b;
  const double v_tip = lc.a + lc.b * u_tip;
  res.width_px = 2.0 * tail.HalfWidth(u0);
  res.length_px = u_tip - u0;
  if (res.length_px < opt.min_length_ratio * res.width_px) {
    res.status = SilhouetteStatus::kTooSmall;
    return res;
  }
  const Eigen::Vector2d off(cov.roi.x, cov.roi.y);
  const Frame2& f = body.f;
  res.px[0] = f.At(u_tip, v_tip) + off;
  res.px[1] = f.At(u0, body.e1.a + body.e1.b * u0) + off;
  res.px[2] = f.At(u0, body.e2.a + body.e2.b * u0) + off;
  res.status = SilhouetteStatus::kOk;
  return res;
}

}  // namespace rk::extract
