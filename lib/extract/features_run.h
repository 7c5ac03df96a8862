// `rk-extract features` as a library call: decode the attitude-camera recording frame by frame
// (video::FrameSource), time-stamp each frame (FrameClock), track the target's markers with
// their model ids (FeatureTracker) and build the image-points CSV (SPEC.md §2.1, long format):
//   frame,t_s,id,x_px,y_px,status,sigma_px,ncc,radius_px
// one row per frame and model id, ids in the target model's order; x/y empty when the marker
// was not measured (status lost) or was rejected (invalid). sigma_px is the 1σ of each
// coordinate from the least-squares correlation fit.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "extract/features_tracker.h"
#include "extract/frame_loop.h"
#include "formats/frame_times.h"
#include "io/csv.h"
#include "io/run_summary.h"
#include "target/feature_model.h"

namespace rk::extract {

struct FeatureRunResult : VideoRunStats {  // frames, size, bit depth, wall and extraction time
  std::vector<FeatureFrameResult> rows;
  FeatureTrackSummary summary;
  // The report's "summary" (docs/rk-extract.md "Report"): the headline figures rk-run copies.
  nlohmann::json SummaryJson() const;
  // The run's summary (io/run_summary.h): point rows by status, the ambiguous-identification warning, the
  // fraction of rows ok, and the report keys video, frames, markers, status_counts, ..., summary, options.
  io::RunSummary Summary(const target::FeatureModel& model, const FeatureTrackOptions& opt) const;
};

// Throws DataError for a frames file that lists fewer frames than the video has (and for a
// truncated video), ProcessingError if the target was never identified, UsageError for bad
// options. progress(frames) is called every 20 frames when set.
FeatureRunResult RunFeatures(const std::vector<std::string>& videos, const formats::FrameClock& clock, const target::FeatureModel& model,
                             const FeatureTrackOptions& options,
                             const std::function<void(std::int64_t)>& progress = {},
                             const std::function<void(const FeatureFrameResult&)>& on_row = {});

io::CsvWriter FeaturePointsCsv(const std::vector<FeatureFrameResult>& rows, const target::FeatureModel& model);
// One frame's rows of that CSV (one per marker). on_row of RunFeatures gets each frame's row as soon as
// it is made (streaming output).
void AppendFeaturePointRows(io::CsvWriter* w, const FeatureFrameResult& r, const target::FeatureModel& model);

}  // namespace rk::extract
