// The seeds file of `rk-extract points` (SPEC.md §2.1): where the user put each point on a frame and how it
// is to be measured.
//   id,frame,x_px,y_px,method  (+ optional size_px, search_px)
// method ∈ correlation, centroid-dark, centroid-bright, quadrant, circle. Several rows of one id seed it again
// at later frames (a re-seed: the user's position replaces the track's there). size_px is the marker's size
// (a circle's or blob's diameter, a quadrant marker's side, a correlation template's side); search_px the
// smallest search half-width around the prediction. Pixel convention SPEC.md §3.
// Errors (DataError at file:line:col, never skipped: a wrong seed is never guessed around): a missing column,
// an empty id, a negative frame, a method not in the list, a size or search that is not > 0, one id seeded
// twice at one frame, one id seeded with two methods (a point keeps its method). The image size and the
// number of frames are checked by the tool that knows them (SeedRow keeps its line and columns for that).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/csv.h"

namespace rk::formats {

enum class PointMethod { kCorrelation, kCentroidDark, kCentroidBright, kQuadrant, kCircle };

const char* PointMethodName(PointMethod m);
std::optional<PointMethod> ParsePointMethod(std::string_view s);
// "correlation, centroid-dark, centroid-bright, quadrant or circle" (messages and help).
std::string PointMethodList();

struct SeedRow {
  std::string id;
  std::int64_t frame = 0;
  double x_px = 0.0, y_px = 0.0;
  PointMethod method = PointMethod::kCorrelation;
  std::optional<double> size_px, search_px;
  std::size_t line = 0, col_frame = 0, col_x = 0;  // 1-based line and character columns (messages)
};

struct Seeds {
  std::string source;
  std::vector<SeedRow> rows;      // in file order
  std::vector<std::string> ids;   // distinct ids in order of first appearance
};

Seeds ReadSeeds(const io::CsvTable& table);
Seeds ReadSeeds(const std::string& path);
// The header of a seeds file as rangekit writes it (rk-sim points).
std::vector<std::string> SeedsColumns();

}  // namespace rk::formats
