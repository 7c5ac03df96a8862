// Image points mapped to a target model; see image_points.h.
#include "pose/image_points.h"

#include <algorithm>

#include "io/error.h"

namespace rk::pose {

ImagePoints ReadImagePoints(const io::CsvTable& table, const target::FeatureModel& model) {
  const formats::ImagePoints file = formats::ReadImagePoints(table);
  const bool points_track = table.HasColumn("score");  // rk-extract points' own column
  ImagePoints out;
  out.source = file.source;
  out.has_frame = file.has_frame;
  out.rows = file.rows;
  out.frames.reserve(file.frames.size());
  for (const formats::ImagePointFrame& in : file.frames) {
    PointFrame f;
    f.frame = in.frame;
    f.t_s = in.t_s;
    f.rows = in.points.size();
    f.first_line = in.line;
    for (const formats::ImagePoint& q : in.points) {
      const int idx = model.Find(q.id);
      if (idx < 0 && points_track) {
        // A points track may carry points the model does not have (a nose, debris): not for the pose.
        ++out.ignored_rows;
        if (std::find(out.ignored_ids.begin(), out.ignored_ids.end(), q.id) == out.ignored_ids.end()) {
          out.ignored_ids.push_back(q.id);
        }
        continue;
      }
      if (idx < 0) {
        throw DataError(file.source, q.line, q.col_id,
                        "id '" + q.id + "' is not in the target model " + model.source + " (ids: " + model.IdList() + ")");
      }
      if (!q.measured()) {
        ++out.unusable_rows;
        continue;
      }
      ImagePoint p;
      p.model_index = idx;
      p.px = *q.px;
      if (q.sigma_px) p.sigma_px = q.sigma_px->mean();
      p.line = q.line;
      p.col_x = q.col_x;
      f.points.push_back(p);
    }
    out.frames.push_back(std::move(f));
  }
  return out;
}

}  // namespace rk::pose
