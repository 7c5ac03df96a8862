// Image of the cylindrical target against the sky; model in silhouette_image.h.
#include "target/silhouette_image.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace rk::target {
namespace {

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain; counter-clockwise in a y-up frame, collinear points dropped.
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && Cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && Cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// Sutherland–Hodgman clip of a convex polygon by the half-plane coord(axis) >= v (keep_above) or <= v.
void ClipAxis(const std::vector<Eigen::Vector2d>& in, int axis, double v, bool keep_above,
              std::vector<Eigen::Vector2d>* out) {
  out->clear();
  const std::size_t n = in.size();
  if (n == 0) return;
  auto inside = [&](const Eigen::Vector2d& p) { return keep_above ? p(axis) >= v : p(axis) <= v; };
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % n];
    const bool ia = inside(a), ib = inside(b);
    if (ia) out->push_back(a);
    if (ia != ib) {
      const double t = (v - a(axis)) / (b(axis) - a(axis));
      Eigen::Vector2d p = a + t * (b - a);
      p(axis) = v;
      out->push_back(p);
    }
  }
}

}  // namespace

cv::Rect PolygonWindow(const std::vector<Eigen::Vector2d>& poly, int margin) {
  if (poly.empty()) return {};
  double x0 = poly[0].x(), x1 = x0, y0 = poly[0].y(), y1 = y0;
  for (const auto& p : poly) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  cv::Rect r(static_cast<int>(std::floor(x0)) - margin, static_cast<int>(std::floor(y0)) - margin, 0, 0);
  r.width = static_cast<int>(std::ceil(x1)) + margin - r.x + 1;
  r.height = static_cast<int>(std::ceil(y1)) + margin - r.y + 1;
  return r;
}

double PolygonArea(const std::vector<Eigen::Vector2d>& poly) {
  double s = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % n];
    s += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(s);
}

std::vector<Eigen::Vector2d> SilhouettePolygon(const camera::CameraModel& cam, const CylinderPose& pose,
                                               const CylinderShape& shape, double az_rad, double el_rad,
                                               int rim_samples) {
  const Eigen::Vector3d a = pose.Axis();
  Eigen::Vector3d e1 = a.cross(Eigen::Vector3d::UnitZ());
  if (e1.norm() < 1e-6) e1 = a.cross(Eigen::Vector3d::UnitX());
  e1.normalize();
  const Eigen::Vector3d e2 = a.cross(e1);
  const double r = 0.5 * shape.diameter_m;
  const Eigen::Vector3d base = pose.tail_centre_enu + (shape.length_m - shape.nose_length_m) * a;
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(static_cast<std::size_t>(2 * rim_samples + 1));
  for (int i = 0; i < rim_samples; ++i) {
    const double phi = 2.0 * M_PI * i / rim_samples;
    const Eigen::Vector3d off = r * (std::cos(phi) * e1 + std::sin(phi) * e2);
    for (const Eigen::Vector3d& c : {pose.tail_centre_enu, base}) {
      const auto p = cam.ProjectEnu(c + off, az_rad, el_rad);
      if (!p) return {};
      pts.push_back(*p);
    }
  }
  const auto tip = cam.ProjectEnu(pose.tail_centre_enu + shape.length_m * a, az_rad, el_rad);
  if (!tip) return {};
  pts.push_back(*tip);
  return ConvexHull(std::move(pts));
}

cv::Mat RasterizeConvexPolygon(const std::vector<Eigen::Vector2d>& poly, const cv::Rect& roi) {
  cv::Mat cov(roi.size(), CV_32FC1, cv::Scalar(0));
  const int n = static_cast<int>(poly.size());
  if (n < 3 || roi.height <= 0 || roi.width <= 0) return cov;
  // Each row's band (the polygon clipped to the row's slab) is clipped from a reduced polygon: vertex 0 and
  // the end points of every edge reaching the slab. The vertices left out lie in runs outside the slab on one
  // side, whose end points are kept: both clips give the same band, vertex for vertex, as from the whole
  // polygon (so the same areas to the bit), at the cost of the edges near the row instead of all of them.
  std::vector<std::vector<int>> near(static_cast<std::size_t>(roi.height));
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = poly[static_cast<std::size_t>(k)];
    const Eigen::Vector2d& b = poly[static_cast<std::size_t>((k + 1) % n)];
    const double y0 = std::min(a.y(), b.y()) - roi.y, y1 = std::max(a.y(), b.y()) - roi.y;
    const int i0 = std::max(0, static_cast<int>(std::floor(y0 - 0.5)) - 1);
    const int i1 = std::min(roi.height - 1, static_cast<int>(std::ceil(y1 + 0.5)) + 1);
    for (int i = i0; i <= i1; ++i) {  // ascending without repeats: edges come in order
      std::vector<int>& idx = near[static_cast<std::size_t>(i)];
      if (idx.empty() || idx.back() != k) idx.push_back(k);
      if (k + 1 < n) idx.push_back(k + 1);  // the closing edge's end is vertex 0, always taken
    }
  }
  std::vector<Eigen::Vector2d> sub, a, band, b, cell;
  for (int i = 0; i < roi.height; ++i) {
    std::vector<int>& idx = near[static_cast<std::size_t>(i)];
    if (idx.empty()) continue;
    sub.assign(1, poly[0]);
    for (int k : idx) {
      if (k != 0) sub.push_back(poly[static_cast<std::size_t>(k)]);
    }
    const double y = roi.y + i, ya = y - 0.5, yb = y + 0.5;
    ClipAxis(sub, 1, ya, true, &a);
    ClipAxis(a, 1, yb, false, &band);
    if (band.size() < 3) continue;
    // The band is convex with its top and bottom edges on y = ya and y = yb: a pixel whose four corners lie
    // on those edges is inside (area 1).
    double xmin = band[0].x(), xmax = band[0].x();
    double la = HUGE_VAL, ra = -HUGE_VAL, lb = HUGE_VAL, rb = -HUGE_VAL;
    for (const auto& p : band) {
      xmin = std::min(xmin, p.x());
      xmax = std::max(xmax, p.x());
      if (p.y() == ya) la = std::min(la, p.x()), ra = std::max(ra, p.x());
      if (p.y() == yb) lb = std::min(lb, p.x()), rb = std::max(rb, p.x());
    }
    const double full_lo = std::max(la, lb), full_hi = std::min(ra, rb);
    const int j0 = std::max(0, static_cast<int>(std::floor(xmin + 0.5)) - roi.x);
    const int j1 = std::min(roi.width - 1, static_cast<int>(std::floor(xmax + 0.5)) - roi.x);
    float* row = cov.ptr<float>(i);
    for (int j = j0; j <= j1; ++j) {
      const double x = roi.x + j;
      if (x - 0.5 >= full_lo && x + 0.5 <= full_hi) {
        row[j] = 1.0f;
        continue;
      }
      ClipAxis(band, 0, x - 0.5, true, &b);
      ClipAxis(b, 0, x + 0.5, false, &cell);
      if (cell.size() >= 3) row[j] = static_cast<float>(std::min(1.0, PolygonArea(cell)));
    }
  }
  return cov;
}

namespace {

// SilhouetteSignal in arithmetic T (float for the renderer, double for Fisher-information derivatives).
template <typename T>
cv::Mat SignalIn(const camera::CameraModel& cam, const CylinderPose& pose, const CylinderShape& shape,
                 double az_rad, double el_rad, const SilhouetteScene& o, double scale) {
  const int W = cam.width_px, H = cam.height_px;
  cv::Mat signal(H, W, cv::DataType<T>::type);
  for (int y = 0; y < H; ++y) {
    const T v = static_cast<T>(
        scale * (o.sky_dn + o.sky_gradient_dn * (static_cast<double>(y) / std::max(1, H - 1) - 0.5)));
    T* row = signal.ptr<T>(y);
    for (int x = 0; x < W; ++x) row[x] = v;
  }
  const std::vector<Eigen::Vector2d> poly = SilhouettePolygon(cam, pose, shape, az_rad, el_rad);
  // Exact projections of the SPEC.md §3 points: the image axis and half width for the shading.
  const SilhouettePoints3d pts = SilhouettePointsOf(pose, shape);
  const auto nose_px = cam.ProjectEnu(pts.nose, az_rad, el_rad),
             tail1_px = cam.ProjectEnu(pts.tail1, az_rad, el_rad),
             tail2_px = cam.ProjectEnu(pts.tail2, az_rad, el_rad);
  if (poly.size() >= 3 && nose_px && tail1_px && tail2_px) {
    const int margin = static_cast<int>(std::ceil(5.0 * o.psf_sigma_px)) + 2;
    cv::Rect roi = PolygonWindow(poly, margin);
    roi &= cv::Rect(0, 0, W, H);
    if (roi.area() > 0) {
      cv::Mat cov = RasterizeConvexPolygon(poly, roi);
      if (cov.type() != cv::DataType<T>::type) cov.convertTo(cov, cv::DataType<T>::type);
      if (o.psf_sigma_px > 0.0) {
        const int k = 2 * static_cast<int>(std::ceil(4.0 * o.psf_sigma_px)) + 1;
        cv::GaussianBlur(cov, cov, cv::Size(k, k), o.psf_sigma_px, o.psf_sigma_px, cv::BORDER_CONSTANT);
      }
      const Eigen::Vector2d tail = 0.5 * (*tail1_px + *tail2_px);
      Eigen::Vector2d dir = *nose_px - tail;
      dir = dir.norm() > 0 ? dir.normalized() : Eigen::Vector2d(1, 0);
      const Eigen::Vector2d nrm(-dir.y(), dir.x());
      const double w = std::max(0.5 * (*tail1_px - *tail2_px).norm(), 1e-6);
      for (int i = 0; i < roi.height; ++i) {
        const T* c = cov.ptr<T>(i);
        T* s = signal.ptr<T>(roi.y + i);
        for (int j = 0; j < roi.width; ++j) {
          if (c[j] == T(0)) continue;
          const Eigen::Vector2d p(roi.x + j, roi.y + i);
          const double v = std::clamp((p - tail).dot(nrm) / w, -1.0, 1.0);
          const double body = scale * (o.body_dn + o.shading_dn * v);
          s[roi.x + j] += static_cast<T>(c[j] * (body - s[roi.x + j]));
        }
      }
    }
  }
  return signal;
}

}  // namespace

cv::Mat SilhouetteSignal(const camera::CameraModel& cam, const CylinderPose& pose, const CylinderShape& shape,
                         double az_rad, double el_rad, const SilhouetteScene& scene, double dn_scale,
                         int depth) {
  return depth == CV_64F ? SignalIn<double>(cam, pose, shape, az_rad, el_rad, scene, dn_scale)
                         : SignalIn<float>(cam, pose, shape, az_rad, el_rad, scene, dn_scale);
}

}  // namespace rk::target
