// `rk-extract beacon` as a library call: decode the recording frame by frame
// (video::FrameSource), time-stamp each frame (FrameClock), track the beacon
// (BeaconTracker) and build the beacon track CSV of SPEC.md §2.1:
//   frame,t_s,x_px,y_px,peak,area_px,status,ncc,sigma_x_px,sigma_y_px
// Every decoded frame gets a row; x/y are empty without an accepted
// measurement (or prediction, status `predicted`).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "extract/beacon_tracker.h"
#include "extract/frame_loop.h"
#include "formats/frame_times.h"
#include "io/csv.h"
#include "io/run_summary.h"

namespace rk::extract {

struct BeaconRunResult : VideoRunStats {  // frames, size, bit depth, wall and extraction time
  std::vector<BeaconFrameResult> rows;
  BeaconTrackSummary summary;
  // The report's "summary" (docs/rk-extract.md "Report"): the headline figures rk-run copies.
  nlohmann::json SummaryJson() const;
  // The run's summary (io/run_summary.h): rows by status, tracked frames as headline figure, and the report
  // keys of docs/rk-extract.md "Report" (video, frames, status_counts, acquisitions, ..., options).
  io::RunSummary Summary(const BeaconTrackOptions& opt) const;
};

// Runs the tracker over all frames of `videos`. Throws DataError naming the
// frames file if it has fewer times than the video has frames, and naming the
// (last) video if it has fewer frames than the frames file lists (truncated);
// ProcessingError if the beacon was never found (after the last frame). `progress(frames)` is called
// every frame when set, `on_row(row)` with each frame's row as soon as it is made (streaming output).
BeaconRunResult RunBeacon(const std::vector<std::string>& videos, const formats::FrameClock& clock,
                          const BeaconTrackOptions& opt, const std::function<void(std::int64_t)>& progress = {},
                          const std::function<void(const BeaconFrameResult&)>& on_row = {});

// Reads every frame and does nothing else (for timing the decoder).
struct DecodeResult {
  std::int64_t frames = 0;
  double wall_s = 0.0;
};
DecodeResult DecodeOnly(const std::vector<std::string>& videos);

// The track as CSV (columns above).
io::CsvWriter BeaconTrackCsv(const std::vector<BeaconFrameResult>& rows, int bit_depth);
// One frame's row of that CSV.
void AppendBeaconTrackRow(io::CsvWriter* w, const BeaconFrameResult& r);

}  // namespace rk::extract
