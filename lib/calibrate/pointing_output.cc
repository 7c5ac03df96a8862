#include "calibrate/pointing_output.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::calibrate {
namespace {

// A parameter's value and σ in its file unit: degrees for angles, mm for the focal length, s for τ.
double InFileUnit(int k, double v, const camera::CameraModel& input) {
  if (k == kParamFocal) return v * input.focal_length_mm;
  if (k == kParamTimeOffset) return v;
  return geo::RadToDeg(v);
}
const char* FileUnit(int k) { return k == kParamFocal ? "mm" : k == kParamTimeOffset ? "s" : "deg"; }

io::Json CameraBlock(const PointingSolution& s, const camera::CameraModel& input) {
  const camera::CameraModel c = s.Camera(input);
  io::Json j = {{"mount_deg",
                 {{"yaw", geo::RadToDeg(c.mount_yaw_rad)},
                  {"pitch", geo::RadToDeg(c.mount_pitch_rad)},
                  {"roll", geo::RadToDeg(c.mount_roll_rad)}}},
                {"focal_length_mm", c.focal_length_mm},
                {"time_offset_s", c.time_offset_s}};
  j["sigma"] = c.calibration["sigma"];
  return j;
}

io::Json ResidualRows(const PointingSolution& s, const ImagePoints& points, bool rejected_only) {
  io::Json rows = io::Json::array();
  for (const ObservationResidual& r : s.residuals) {
    if (rejected_only && !r.rejected) continue;
    const ImagePoint& p = points.rows[r.row];
    rows.push_back({{"line", p.line},
                    {"frame", p.frame},
                    {"t_s", p.t_s},
                    {"id", r.id},
                    {"az_deg", geo::RadToDeg(r.target_az_rad)},
                    {"el_deg", geo::RadToDeg(r.target_el_rad)},
                    {"dx_px", r.residual_px.x()},
                    {"dy_px", r.residual_px.y()},
                    {"chi2", r.chi2},
                    {"rejected", r.rejected}});
  }
  return rows;
}

}  // namespace

io::Json PointingFileJson(const PointingSolution& s, const ImagePoints& points, const camera::CameraModel& input,
                          const std::string& date_utc) {
  camera::PointingModel m = s.Model();
  io::Json names = io::Json::array(), matrix = io::Json::array();
  for (int k : s.estimated_params) names.push_back(PointingParamName(k));
  for (int a = 0; a < s.correlation.rows(); ++a) {
    io::Json row = io::Json::array();
    for (int b = 0; b < s.correlation.cols(); ++b) row.push_back(s.correlation(a, b));
    matrix.push_back(row);
  }
  m.extra["method"] = "rk-calibrate pointing";
  m.extra["date"] = date_utc;
  m.extra["estimated"] = names;
  m.extra["correlation"] = {{"parameters", names}, {"matrix", matrix}};
  m.extra["camera"] = CameraBlock(s, input);
  m.extra["observations"] = s.residuals.size();
  m.extra["observations_used"] = s.used;
  m.extra["dwells"] = s.dwells;
  m.extra["targets"] = s.targets;
  m.extra["residual_rms_px"] = s.rms_px;
  m.extra["chi2_per_dof"] = s.chi2_per_dof;
  m.extra["warnings"] = s.warnings;
  m.extra["rejected"] = ResidualRows(s, points, true);
  m.extra["residuals"] = ResidualRows(s, points, false);
  return camera::PointingModelToJson(m);
}

io::RunSummary PointingRunSummary(const PointingSolution& s, const camera::CameraModel& input, const std::string& out) {
  io::RunSummary r;
  for (const std::string& w : s.warnings) r.Warn("pointing_fit", w);
  if (s.rejected > 0) {
    r.Warn("outliers_rejected", std::to_string(s.rejected) + " of " + std::to_string(s.residuals.size()) +
                                    " observations rejected as outliers (listed under \"rejected\" in " + out + ")");
  }
  if (!s.termination.empty()) r.termination = s.termination == "CONVERGENCE" ? "converged" : s.termination;
  r.AddFigure("residual RMS", s.rms_px, "px", std::to_string(s.used) + " observations used");
  r.details["summary"] = PointingSummaryJson(s, input);
  return r;
}

io::Json PointingSummaryJson(const PointingSolution& s, const camera::CameraModel& input) {
  io::Json sigma = io::Json::object(), value = io::Json::object();
  for (int k : s.estimated_params) {
    const std::string key = std::string(PointingParamName(k)) + "_" + FileUnit(k);
    value[key] = InFileUnit(k, k == kParamFocal ? 1.0 + s.x[static_cast<std::size_t>(k)] : s.x[static_cast<std::size_t>(k)], input);
    sigma[key] = InFileUnit(k, *s.sigma[static_cast<std::size_t>(k)], input);
  }
  return {{"observations", s.residuals.size()},
          {"observations_used", s.used},
          {"rejected", s.rejected},
          {"dwells", s.dwells},
          {"targets", s.targets},
          {"residual_rms_px", s.rms_px},
          {"chi2_per_dof", s.chi2_per_dof},
          {"warnings", s.warnings.size()},
          {"value", value},
          {"sigma", sigma}};
}

namespace {

constexpr int kPanelW = 900, kPanelH = 360, kMargin = 50;

// One panel: residual components (dx solid dots, dy rings) against x in [x0, x1].
void DrawPanel(cv::Mat* img, int top, const PointingSolution& s, bool elevation, double span_px) {
  const cv::Rect box(kMargin, top + 20, kPanelW - 2 * kMargin, kPanelH - 50);
  cv::rectangle(*img, box, cv::Scalar(0, 0, 0), 1);
  const double x0 = elevation ? -5.0 : 0.0, x1 = elevation ? 90.0 : 360.0;
  const int y_mid = box.y + box.height / 2;
  cv::line(*img, {box.x, y_mid}, {box.x + box.width, y_mid}, cv::Scalar(160, 160, 160), 1);
  const std::string title = std::string("residual (px, +/-") + std::to_string(span_px).substr(0, 5) + ") vs target " +
                            (elevation ? "elevation (deg, -5..90)" : "azimuth (deg, 0..360)") +
                            "; filled = x, ring = y, cross = rejected";
  cv::putText(*img, title, {box.x, top + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1);
  int target = 0;
  std::map<std::string, int> colour_of;
  for (const ObservationResidual& r : s.residuals) {
    const int id = colour_of.emplace(r.id, target).first->second;
    if (id == target) ++target;
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((id * 37) % 180, 220, 200)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
    const cv::Scalar colour(c[0], c[1], c[2]);
    const double xv = geo::RadToDeg(elevation ? r.target_el_rad : r.target_az_rad);
    const int px = box.x + static_cast<int>((xv - x0) / (x1 - x0) * box.width);
    for (int k = 0; k < 2; ++k) {
      const double v = std::clamp(r.residual_px[k] / span_px, -1.0, 1.0);
      const cv::Point p(px, y_mid - static_cast<int>(v * box.height / 2));
      if (r.rejected) {
        cv::drawMarker(*img, p, cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 8, 1);
      } else {
        cv::circle(*img, p, 2, colour, k == 0 ? cv::FILLED : 1);
      }
    }
  }
}

}  // namespace

std::string ResidualPlotPng(const PointingSolution& s) {
  double span = 0.0;
  for (const ObservationResidual& r : s.residuals) {
    if (!r.rejected) span = std::max(span, r.residual_px.cwiseAbs().maxCoeff());
  }
  span = std::max(span * 1.1, 1e-3);
  cv::Mat img(2 * kPanelH, kPanelW, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawPanel(&img, 0, s, false, span);
  DrawPanel(&img, kPanelH, s, true, span);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", img, png)) throw ProcessingError("cannot encode the residual plot as PNG");
  return std::string(png.begin(), png.end());
}

}  // namespace rk::calibrate
