// LensPlotPng: residual vectors over the image (exaggerated; the scale is written on the image) and the
// image's coverage by board corners (cells shaded by how many corners fell in them), drawn with OpenCV.
#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "calibrate/lens_calibration.h"
#include "io/error.h"

namespace rk::calibrate {
namespace {

constexpr int kPlotMaxWidth = 1280;   // canvas width for large sensors (px) ...
constexpr int kPlotMinWidth = 960;    // ... and for small ones (room for the legend)
constexpr int kCoverageCells = 16;    // cells across the image (fewer down, square cells)
constexpr double kArrowFraction = 0.04;  // the 95th-percentile residual is drawn this fraction of the width long
constexpr int kTextBand = 48;         // legend band under the image (px)

// Largest 1-2-5 step number ≤ x (x > 0).
double RoundDown125(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * p <= x) return m * p;
  }
  return p;
}

double ResidualP95(const LensResult& res) {
  std::vector<double> r;
  for (const auto& v : res.views) {
    if (!v.used) continue;
    for (const auto& e : v.residual_px) r.push_back(std::hypot(e.x, e.y));
  }
  if (r.empty()) return 1.0;
  std::sort(r.begin(), r.end());
  return std::max(r[static_cast<std::size_t>(0.95 * static_cast<double>(r.size() - 1))], 1e-3);
}

// Shades cells by the number of corners of used views in them; returns the number of empty cells.
int DrawCoverage(const LensResult& res, double s, cv::Mat* canvas, int* cells_total) {
  const int nx = kCoverageCells;
  const int ny = std::max(1, static_cast<int>(std::lround(nx * static_cast<double>(res.height_px) / res.width_px)));
  std::vector<int> count(static_cast<std::size_t>(nx * ny), 0);
  for (const auto& v : res.views) {
    if (!v.used) continue;
    for (const auto& p : v.image_px) {
      const int cx = std::clamp(static_cast<int>(p.x / res.width_px * nx), 0, nx - 1);
      const int cy = std::clamp(static_cast<int>(p.y / res.height_px * ny), 0, ny - 1);
      ++count[static_cast<std::size_t>(cy * nx + cx)];
    }
  }
  const int most = std::max(1, *std::max_element(count.begin(), count.end()));
  int empty = 0;
  for (int cy = 0; cy < ny; ++cy) {
    for (int cx = 0; cx < nx; ++cx) {
      const int c = count[static_cast<std::size_t>(cy * nx + cx)];
      empty += c == 0;
      const cv::Point a(static_cast<int>(cx * res.width_px / nx * s), static_cast<int>(cy * res.height_px / ny * s));
      const cv::Point b(static_cast<int>((cx + 1) * res.width_px / nx * s),
                        static_cast<int>((cy + 1) * res.height_px / ny * s));
      const double f = std::sqrt(static_cast<double>(c) / most);
      const cv::Scalar colour = c == 0 ? cv::Scalar(40, 40, 110) : cv::Scalar(40, 60 + 120 * f, 40);  // BGR
      cv::rectangle(*canvas, a, b, colour, cv::FILLED);
      cv::rectangle(*canvas, a, b, cv::Scalar(70, 70, 70), 1);
    }
  }
  *cells_total = nx * ny;
  return empty;
}

void DrawResiduals(const LensResult& res, double s, double scale, cv::Mat* canvas) {
  for (const auto& v : res.views) {
    if (!v.found) continue;
    const cv::Scalar colour = v.used ? cv::Scalar(0, 230, 255) : cv::Scalar(60, 60, 255);  // used yellow, rejected red
    for (std::size_t k = 0; k < v.image_px.size() && k < v.residual_px.size(); ++k) {
      const cv::Point2d p(v.image_px[k].x * s, v.image_px[k].y * s);
      const cv::Point2d q = p + cv::Point2d(v.residual_px[k].x, v.residual_px[k].y) * (scale * s);
      cv::circle(*canvas, p, 1, cv::Scalar(220, 220, 220), cv::FILLED, cv::LINE_AA);
      cv::line(*canvas, p, q, colour, 1, cv::LINE_AA);
    }
  }
}

std::string Num(double x, int digits) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(digits);
  o << x;
  return o.str();
}

}  // namespace

std::string LensPlotPng(const LensResult& res) {
  RK_CHECK(res.width_px > 0 && res.height_px > 0, "no image size");
  const double s = std::min(static_cast<double>(kPlotMaxWidth) / res.width_px,
                            std::max(1.0, static_cast<double>(kPlotMinWidth) / res.width_px));
  const int w = static_cast<int>(std::lround(res.width_px * s)), h = static_cast<int>(std::lround(res.height_px * s));
  cv::Mat canvas(h + kTextBand, w, CV_8UC3, cv::Scalar(30, 30, 30));
  cv::Mat image = canvas(cv::Rect(0, 0, w, h));
  int cells = 0;
  const int empty = DrawCoverage(res, s, &image, &cells);
  const double scale = RoundDown125(kArrowFraction * res.width_px / ResidualP95(res));
  DrawResiduals(res, s, scale, &image);
  const std::string line1 = "residuals x" + Num(scale, scale < 1 ? 1 : 0) + " (yellow: used views, red: rejected); rms " +
                            Num(res.rms_px, 3) + " px; views used " + std::to_string(res.ViewsUsed()) + ", rejected " +
                            std::to_string(res.ViewsRejected()) + ", no board " + std::to_string(res.ViewsWithoutBoard());
  const std::string line2 = "coverage: green = corners in the cell (brighter = more), red = none (" +
                            std::to_string(empty) + " of " + std::to_string(cells) + " cells empty)";
  const double fs = 0.45;
  cv::putText(canvas, line1, cv::Point(6, h + 18), cv::FONT_HERSHEY_SIMPLEX, fs, cv::Scalar(230, 230, 230), 1, cv::LINE_AA);
  cv::putText(canvas, line2, cv::Point(6, h + 38), cv::FONT_HERSHEY_SIMPLEX, fs, cv::Scalar(230, 230, 230), 1, cv::LINE_AA);
  std::vector<uchar> png;
  if (!cv::imencode(".png", canvas, png)) throw ProcessingError("cannot encode the plot as PNG");
  return std::string(png.begin(), png.end());
}

}  // namespace rk::calibrate
