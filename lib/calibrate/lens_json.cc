// The calibrated camera's JSON (SPEC.md §3 with its "calibration" object) and the report's summary.
#include "calibrate/lens_calibration.h"

namespace rk::calibrate {
namespace {

io::Json BoardJson(const LensOptions& opt) {
  io::Json b = {{"kind", BoardKindName(opt.board)}, {"cols", opt.cols}, {"rows", opt.rows}, {"square_mm", opt.square_mm}};
  if (opt.board == BoardKind::kCharuco) {
    b["marker_mm"] = opt.marker_mm;
    b["dictionary"] = ArucoDictionaryName(opt.dictionary);
  }
  return b;
}

std::string MethodText(const LensOptions& opt) {
  const char* detector = opt.board == BoardKind::kChessboard ? "findChessboardCornersSB"
                         : opt.board == BoardKind::kCircles  ? "findCirclesGrid (asymmetric)"
                                                             : "aruco detectMarkers + interpolateCornersCharuco";
  return std::string("OpenCV calibrateCamera (Zhang), ") + detector + ", views above " +
         std::to_string(opt.reject_ratio).substr(0, 4) + " x median RMS rejected";
}

std::vector<std::string> FixedNames(const LensOptions& opt) {
  std::vector<std::string> f;
  if (opt.fix_aspect) f.push_back("aspect");
  if (opt.fix_principal_point) f.push_back("principal_point");
  if (opt.zero_tangent) f.insert(f.end(), {"p1", "p2"});
  if (opt.fix_k3) f.push_back("k3");
  return f;
}

// 1σ, or null for a fixed term.
io::Json SigmaOrNull(double sigma, bool fixed) { return fixed ? io::Json(nullptr) : io::Json(sigma); }

}  // namespace

io::Json LensResult::CameraJson(const LensOptions& opt, const std::string& date_utc) const {
  io::Json j = camera::CameraModelToJson(camera);
  io::Json used = io::Json::array(), rejected = io::Json::array();
  for (const auto& v : views) {
    if (v.used) {
      used.push_back(v.name);
    } else {
      io::Json r = {{"name", v.name}, {"reason", v.reason}};
      if (v.found) r["rms_px"] = v.rms_px;
      rejected.push_back(r);
    }
  }
  const bool pp = opt.fix_principal_point, tan = opt.zero_tangent;
  io::Json s = {
      {"focal_length_mm", sigma.fx_px * opt.pixel_size_mm},
      {"fx_px", sigma.fx_px},
      {"fy_px", sigma.fy_px},
      {"principal_point_px", {SigmaOrNull(sigma.cx_px, pp), SigmaOrNull(sigma.cy_px, pp)}},
      {"distortion",
       {sigma.distortion[0], sigma.distortion[1], SigmaOrNull(sigma.distortion[2], tan),
        SigmaOrNull(sigma.distortion[3], tan), SigmaOrNull(sigma.distortion[4], opt.fix_k3)}}};
  j["calibration"] = {{"method", MethodText(opt)},
                      {"date", date_utc},
                      {"board", BoardJson(opt)},
                      {"fixed", FixedNames(opt)},
                      {"rms_px", rms_px},
                      {"map_sigma_px", map_sigma.rms_px},
                      {"map_sigma_modulo_rotation_px", map_sigma.modulo_rotation_rms_px},
                      {"views", views.size()},
                      {"views_used", used},
                      {"views_rejected", rejected},
                      {"sigma", s}};
  return j;
}

io::RunSummary LensResult::Summary() const {
  io::RunSummary r;
  for (const std::string& w : warnings) r.Warn("poorly_determined", w);
  const io::Json j = SummaryJson();
  if (j.contains("rms_px") && j["rms_px"].is_number()) r.AddFigure("reprojection RMS", j["rms_px"].get<double>(), "px");
  r.details["summary"] = j;
  return r;
}

io::Json LensResult::SummaryJson() const {
  return {{"rms_px", rms_px},
          {"views", views.size()},
          {"views_used", ViewsUsed()},
          {"views_rejected", ViewsRejected()},
          {"views_without_board", ViewsWithoutBoard()},
          {"fx_px", camera.fx()},
          {"fy_px", camera.fy()},
          {"cx_px", camera.principal_point_px.x()},
          {"cy_px", camera.principal_point_px.y()},
          {"sigma_fx_px", sigma.fx_px},
          {"sigma_fy_px", sigma.fy_px},
          {"sigma_cx_px", sigma.cx_px},
          {"sigma_cy_px", sigma.cy_px},
          {"map_sigma_px", map_sigma.rms_px},
          {"map_sigma_modulo_rotation_px", map_sigma.modulo_rotation_rms_px},
          {"solves", solves}};
}

}  // namespace rk::calibrate
