// `rk-extract points` as a library call: decode the recording frame by frame (video::FrameSource), time-stamp
// each frame (FrameClock), track the seeded points (PointsTracker) and build the points track of SPEC.md §2.1:
//   frame,t_s,id,x_px,y_px,status,sigma_x_px,sigma_y_px,score
// one row per frame and point id (ids in the seeds file's order of first appearance); x/y and σ empty when
// the point has no position (lost, invalid, before its first seed), score empty unless it was measured.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "extract/frame_loop.h"
#include "extract/points_tracker.h"
#include "formats/frame_times.h"
#include "formats/seeds.h"
#include "io/csv.h"
#include "io/run_summary.h"

namespace rk::extract {

struct PointsRunResult : VideoRunStats {
  std::vector<PointsFrameResult> rows;
  std::vector<PointSummary> points;
  std::vector<PointsTracker::SeedFailure> seed_failures;
  nlohmann::json SummaryJson() const;
  io::RunSummary Summary(const PointsTrackOptions& opt) const;
};

// Throws DataError at the seeds file's line and column for a seed outside the first frame or at a frame past
// the recording's end (before any row reaches on_row: rows are held until the last seed frame has been
// processed), DataError for frame-time problems as the other extractions, ProcessingError when no point was
// measured in any frame.
PointsRunResult RunPoints(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                          const formats::Seeds& seeds, const PointsTrackOptions& options,
                          const std::function<void(std::int64_t)>& progress = {},
                          const std::function<void(const PointsFrameResult&)>& on_row = {});

io::CsvWriter PointsTrackCsv(const std::vector<PointsFrameResult>& rows, const formats::Seeds& seeds);
void AppendPointsTrackRows(io::CsvWriter* w, const PointsFrameResult& r, const formats::Seeds& seeds);

}  // namespace rk::extract
