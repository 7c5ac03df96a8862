// What rk-calibrate pointing writes: pointing.json (SPEC.md §3.1: the four terms in degrees, their 1σ
// under "sigma", plus the calibration's correlations, residuals, outliers, counts and date), the summary
// of its --report, and the residual plot (PNG: residuals against target azimuth and elevation, one
// colour per target, rejected observations as crosses).
#pragma once

#include <string>

#include "calibrate/pointing_observations.h"
#include "calibrate/pointing_solve.h"
#include "camera/camera_model.h"
#include "io/json_util.h"

namespace rk::calibrate {

// pointing.json. `date_utc` is written as "date"; `input` is the camera the calibration started from.
io::Json PointingFileJson(const PointingSolution& s, const ImagePoints& points, const camera::CameraModel& input,
                          const std::string& date_utc);
// The report's "summary" (headline figures: rms, counts, σ in arcsec / mm / ms).
io::Json PointingSummaryJson(const PointingSolution& s, const camera::CameraModel& input);
// The residual plot as PNG bytes.
std::string ResidualPlotPng(const PointingSolution& s);

}  // namespace rk::calibrate
