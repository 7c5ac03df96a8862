// The pointing model file pointing.json (SPEC.md §3.1), written by rk-calibrate pointing and read by every
// tool that turns pixels and turret angles into directions (rk-locate, rk-attitude):
//   {"az_offset_deg", "tilt_north_deg", "tilt_east_deg", "el_axis_tilt_deg"}   (absent = 0)
//   "sigma": {same keys}                                                       (1σ; a term not estimated has none)
// plus whatever else the calibration reports (correlations, residuals, observation count, date), kept as read.
// The geometry is geo::RotationEnuFromTurretT (geo/pointing.h).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "geo/pointing.h"
#include "io/json_positions.h"
#include "io/json_util.h"

namespace rk::camera {

// The four terms in file order; index into PointingModel::sigma_rad.
enum PointingTerm { kAzOffset = 0, kTiltNorth = 1, kTiltEast = 2, kElAxisTilt = 3 };
inline constexpr std::array<const char*, 4> kPointingTermKeys = {"az_offset_deg", "tilt_north_deg",
                                                                 "tilt_east_deg", "el_axis_tilt_deg"};

struct PointingModel {
  geo::PointingTerms terms;
  std::array<std::optional<double>, 4> sigma_rad;  // 1σ of each term (radians), nullopt = not estimated
  io::Json extra = io::Json::object();             // every other key of the file, kept as read

  // Terms in file order (radians).
  std::array<double, 4> TermsRad() const {
    return {terms.az_offset_rad, terms.tilt_north_rad, terms.tilt_east_rad, terms.el_axis_tilt_rad};
  }
  void SetTermsRad(const std::array<double, 4>& t) {
    terms = {t[kAzOffset], t[kTiltNorth], t[kTiltEast], t[kElAxisTilt]};
  }
};

// Reads and validates pointing.json; DataError names the file, the line and column of the offending value
// (io::JsonPositions) and the key (terms numbers, finite, |term| ≤ 360°, tilts ≤ 10°, σ finite and ≥ 0).
PointingModel LoadPointingModel(const std::string& path);
PointingModel ParsePointingModel(const std::string& text, const std::string& name);
// The same for parsed JSON; with `positions` of its text the errors name line and column, else the file only.
PointingModel PointingModelFromJson(const io::Json& j, const std::string& where,
                                    const io::JsonPositions& positions = io::JsonPositions());
io::Json PointingModelToJson(const PointingModel& model);

}  // namespace rk::camera
