// `rk-extract silhouette` as a library call: decode the recording (video::FrameSource, segments and
// image-sequence patterns), time-stamp each frame (FrameClock), extract the three silhouette points of
// each frame (silhouette.h) and build the image points CSV of SPEC.md §2.1, long format:
//   frame,t_s,id,x_px,y_px,status,detail,width_px,length_px
// three rows per decoded frame (ids nose, tail1, tail2). status: ok; lost (no target found: detail
// not_found); invalid (a target but no measurement: detail touches_border, too_small or bad_fit) with
// empty x_px, y_px. Rows are never dropped.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "extract/frame_loop.h"
#include "formats/frame_times.h"
#include "extract/silhouette.h"
#include "io/csv.h"
#include "io/run_summary.h"

namespace rk::extract {

struct SilhouetteFrameRow {
  std::int64_t frame = 0;
  double t_s = 0.0;
  SilhouetteResult result;
};

struct SilhouetteRunResult : VideoRunStats {  // frames, size, bit depth, wall and extraction time
  std::vector<SilhouetteFrameRow> rows;
  std::array<std::int64_t, 5> by_status{};  // indexed by SilhouetteStatus
  // The report's "summary" (docs/rk-extract.md "Report"): the headline figures rk-run copies.
  nlohmann::json SummaryJson() const;
  // The run's summary (io/run_summary.h): the frames-without-points warning by cause, the fraction of frames
  // with points, and the report keys video, frames, status_counts (by SilhouetteStatus), summary, options.
  // No rows_by_status: a frame's outcome here is a SilhouetteStatus, not a SPEC.md §2 row status.
  io::RunSummary Summary(const SilhouetteOptions& opt) const;
};

// Throws DataError for a truncated video (fewer frames than the frames file lists) or a frames file with
// fewer times than frames, ProcessingError if no frame gives the three points, UsageError for bad options.
SilhouetteRunResult RunSilhouette(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                                  const SilhouetteOptions& options,
                                  const std::function<void(std::int64_t)>& progress = {},
                                  const std::function<void(const SilhouetteFrameRow&)>& on_row = {});

io::CsvWriter SilhouettePointsCsv(const std::vector<SilhouetteFrameRow>& rows);
// One frame's rows of that CSV (nose, tail1, tail2). on_row of RunSilhouette gets each frame's row as soon
// as it is made (streaming output).
void AppendSilhouettePointRows(io::CsvWriter* w, const SilhouetteFrameRow& r);

}  // namespace rk::extract
