// rk-extract points: tracking cost per point-frame on 5-megapixel frames already decoded (issue 31 target:
// ≥ 5000 point-frames/s on one core for quadrant, centroid and circle, ≥ 2000 for correlation), and the same
// on 640×480 frames (the cost must not depend on the frame size). Frames from rk-sim points (moving
// scenario: translation, rotation, growth, motion blur) at 640×480, rendered once, held in memory and, for the
// 5-MP table, placed in a 2448×2048 frame (the same motion: rk-sim's motion scales with the frame); for each method,
// 10 point ids seeded on that method's markers (repeated), tracked over every frame. Reference: OpenCV's
// matchTemplate of a 32×32 template over a 96×96 area. Prints a table (docs/benchmarks.md "Issue 31").
// Usage: points_speed [frames, default 200]   (Release build; one core: taskset -c 0)
//        RK_BENCH_METHOD=circle points_speed ...   one method only (for perf record)
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "extract/points_tracker.h"
#include "formats/seeds.h"
#include "io/csv.h"
#include "sim/points_scene.h"

namespace {

using Clock = std::chrono::steady_clock;

double PointFramesPerSecond(const std::vector<cv::Mat>& frames, const rk::sim::PointsSimulator& sim,
                            const std::string& method, const cv::Point& offset, int* measured) {
  std::string csv = "id,frame,x_px,y_px,method,size_px\n";
  std::vector<rk::sim::PointsSimulator::Seed> mine;
  for (const auto& s : sim.Seeds()) {
    if (s.method == method) mine.push_back(s);
  }
  if (mine.empty()) return 0.0;
  for (int i = 0; i < 10; ++i) {
    const auto& s = mine[static_cast<std::size_t>(i) % mine.size()];
    csv += "p" + std::to_string(i) + ",0," + std::to_string(s.x_px + offset.x) + "," + std::to_string(s.y_px + offset.y) + "," + method +
           "," + std::to_string(s.size_px) + "\n";
  }
  const rk::formats::Seeds seeds = rk::formats::ReadSeeds(rk::io::CsvTable::Parse(csv, "seeds.csv"));
  rk::extract::PointsTracker tracker(seeds, rk::extract::PointsTrackOptions{});
  tracker.Process(frames[0], 0, 0.0);  // the seeds (not timed)
  const auto t0 = Clock::now();
  for (std::size_t k = 1; k < frames.size(); ++k) {
    tracker.Process(frames[k], static_cast<std::int64_t>(k), sim.TimeS(static_cast<int>(k)));
  }
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  *measured = 0;
  for (const auto& p : tracker.summary()) *measured += static_cast<int>(p.rows_by_status[0] + p.rows_by_status[1]);
  return 10.0 * static_cast<double>(frames.size() - 1) / s;
}

void Table(int width, int height, int n) {
  rk::sim::PointsSceneOptions o;
  o.scenario = rk::sim::PointsScenario::kMoving;
  o.frames = n;
  o.clouds = false;
  const rk::sim::PointsSimulator sim(o);
  const cv::Point offset((width - o.width) / 2, (height - o.height) / 2);
  std::vector<cv::Mat> frames;
  for (int k = 0; k < n; ++k) {
    cv::Mat f;
    cv::copyMakeBorder(sim.Frame(k), f, offset.y, height - o.height - offset.y, offset.x, width - o.width - offset.x,
                       cv::BORDER_REPLICATE);
    frames.push_back(f);
  }
  std::printf("\n%d x %d, %d frames, 10 points:\n| method | point-frames/s | measured rows |\n|---|---|---|\n", width,
              height, n);
  const char* only = std::getenv("RK_BENCH_METHOD");  // one method only (profiling)
  for (const char* m : {"quadrant", "circle", "centroid-bright", "centroid-dark", "correlation"}) {
    if (only && std::string(only) != m) continue;
    int measured = 0;
    const double rate = PointFramesPerSecond(frames, sim, m, offset, &measured);
    std::printf("| %s | %.0f | %d of %d |\n", m, rate, measured, 10 * (n - 1) + 10);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200;
  Table(2448, 2048, n);
  Table(640, 480, n);
  // Reference: one matchTemplate of 32×32 over 96×96 (float), as in issue 31.
  cv::Mat area(96, 96, CV_32FC1), templ(32, 32, CV_32FC1), map;
  cv::randu(area, 0, 255);
  area(cv::Rect(30, 30, 32, 32)).copyTo(templ);
  const int reps = 2000;
  const auto t0 = Clock::now();
  for (int i = 0; i < reps; ++i) cv::matchTemplate(area, templ, map, cv::TM_CCOEFF_NORMED);
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("\nOpenCV matchTemplate 32x32 over 96x96: %.3f ms\n", 1e3 * s / reps);
  return 0;
}
