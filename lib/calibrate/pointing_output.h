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
#include "io/run_summary.h"

namespace rk::calibrate {

// pointing.json. `date_utc` is written as "date"; `input` is the camera the calibration started from.
io::Json PointingFileJson(const PointingSolution& s, const ImagePoints& points, const camera::CameraModel& input,
                          const std::string& date_utc);
// The report's "summary" (headline figures: rms, counts, σ in arcsec / mm / ms).
io::Json PointingSummaryJson(const PointingSolution& s, const camera::CameraModel& input);
// The run's summary (io/run_summary.h): the solution's warnings (code "pointing_fit": separability and doubtful
// fits, in words), outliers rejected (naming `out`, where they are listed), Ceres' termination, the RMS residual
// as headline, and the report's "summary". No rows_by_status: the product is a model, not rows.
io::RunSummary PointingRunSummary(const PointingSolution& s, const camera::CameraModel& input, const std::string& out);
// The residual plot as PNG bytes.
std::string ResidualPlotPng(const PointingSolution& s);

}  // namespace rk::calibrate
