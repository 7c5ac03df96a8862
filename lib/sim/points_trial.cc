// rk-sim points' folder (sim/points_scene.h WritePointsTrial): video, frame times, seeds, truth.
#include <set>

#include "io/csv.h"
#include "io/error.h"
#include "sim/points_scene.h"
#include "sim/sim_common.h"
#include "sim/trial_folder.h"
#include "video/frame_sink.h"

namespace rk::sim {
namespace points_detail {

constexpr int kPointsTruthDecimals = 6;  // truth x, y: 1e-6 px, far below the tracker's 0.02 px

void AddSeedRow(io::CsvWriter* csv, const PointsSimulator::Seed& s) {
  csv->Add(s.id).Add(s.frame).Add(s.x_px, kPointsTruthDecimals).Add(s.y_px, kPointsTruthDecimals).Add(s.method);
  csv->Add(s.size_px, 3).EndRow();
}

}  // namespace points_detail

io::Json PointsTrialSummary::ToJson() const {
  io::Json j;
  j["frames"] = frames;
  j["markers"] = markers;
  j["hidden_rows"] = hidden_rows;
  j["lookalike_frames"] = lookalike_frames;
  j["seeds"] = seeds;
  return j;
}

PointsTrialSummary WritePointsTrial(const PointsSceneOptions& opt, const std::filesystem::path& out_dir,
                                    const PointsWriteOptions& w) {
  using namespace points_detail;
  const PointsSimulator sim(opt);  // checks the options
  PointsTrialSummary sum;
  // Seeds first: a bad re-seed is refused before anything is written.
  io::CsvWriter seeds({"id", "frame", "x_px", "y_px", "method", "size_px"});
  std::set<std::pair<std::string, int>> seeded;
  for (const PointsSimulator::Seed& s : sim.Seeds()) {
    AddSeedRow(&seeds, s);
    seeded.insert({s.id, s.frame});
  }
  for (const auto& [id, frame] : w.reseeds) {
    const PointsSimulator::Seed s = sim.SeedAt(id, frame);
    if (!seeded.insert({id, frame}).second) {
      throw UsageError("--reseed " + id + ":" + std::to_string(frame) + " repeats a seed of that id and frame");
    }
    AddSeedRow(&seeds, s);
  }
  sum.seeds = static_cast<int>(seeds.rows());

  if (out_dir.empty() || out_dir == "-") throw UsageError("--out must name a folder");
  TrialFolder folder(out_dir.string(), w.force);
  folder.MakeSubfolder("truth");
  io::CsvWriter frames({"frame", "t_s"});
  io::CsvWriter truth({"frame", "t_s", "id", "x_px", "y_px", "visible", "occlusion"});
  const bool deep = opt.bits == 16;
  if (deep) folder.MakeSubfolder("video");
  video::FrameSink sink(folder.Path(deep ? "video/%06d.png" : "video.mkv"), opt.width, opt.height, opt.bits, opt.fps);
  for (int k = 0; k < sim.frames(); ++k) {
    const double t = sim.TimeS(k);
    frames.Add(k).Add(t, kTimeDecimals).EndRow();
    for (const PointTruth& r : sim.Truth(k)) {
      truth.Add(k).Add(t, kTimeDecimals).Add(r.id).Add(r.x_px, kPointsTruthDecimals).Add(r.y_px, kPointsTruthDecimals);
      truth.Add(r.visible ? 1 : 0).Add(r.occlusion, 4).EndRow();
      if (r.id == "lookalike") {
        sum.lookalike_frames += r.visible ? 1 : 0;
      } else {
        sum.hidden_rows += r.visible ? 0 : 1;
        if (k == 0) ++sum.markers;
      }
    }
    sink.Write(sim.Frame(k));
    if (w.progress) w.progress(k + 1, sim.frames());
  }
  sink.Close();
  sum.frames = sim.frames();
  frames.Write(folder.Path("frames.csv"));
  seeds.Write(folder.Path("seeds.csv"));
  truth.Write(folder.Path("truth/points.csv"));
  folder.Commit();
  return sum;
}

}  // namespace rk::sim
