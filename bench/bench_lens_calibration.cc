// rk-calibrate lens speed (issue 17 target: 20 five-megapixel views ≤ 30 s on 2 cores): 20 views of a 9 × 6
// chessboard rendered through a 2448 × 2048 camera with distortion (sim/lens_board.h), written once as a PNG
// sequence, then calibrate::CalibrateLens timed end to end (read, detect on 2 threads, solve).
// Run (Release): build-rel/bench/bench_lens_calibration   (one iteration each; argument: --detect-max-px, 0 = off)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "calibrate/lens_calibration.h"
#include "sim/lens_board.h"

namespace {

constexpr int kViews = 20;

rk::camera::CameraModel FiveMegapixelCamera() {
  rk::camera::CameraModel c;  // 2448 × 2048, 3.45 µm, 12 mm
  c.focal_length_mm = 12.0;
  c.principal_point_px = {1230.2, 1020.9};
  c.distortion = {-0.12, 0.05, 0.0004, -0.0002, 0.0};
  return c;
}

// The image-sequence pattern of the rendered views (made on first use, in $TMPDIR or /tmp).
const std::string& Views() {
  static const std::string pattern = [] {
    const char* tmp = std::getenv("TMPDIR");
    const std::filesystem::path dir = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") / "rk_bench_lens";
    std::filesystem::create_directories(dir);
    const rk::camera::CameraModel cam = FiveMegapixelCamera();
    const rk::sim::BoardRenderer renderer(cam);
    const auto poses = rk::sim::VariedBoardPoses(cam, -30, -30, 270, 180, kViews, 3);
    rk::sim::BoardViewOptions vo;
    vo.supersample = 2;
    for (int i = 0; i < static_cast<int>(poses.size()); ++i) {
      vo.seed = static_cast<std::uint64_t>(i + 1);
      const cv::Mat img = renderer.Render(poses[static_cast<std::size_t>(i)].R_cam_board,
                                          poses[static_cast<std::size_t>(i)].t_cam_board_mm,
                                          rk::sim::ChessboardTexture(9, 6, 30.0), vo);
      char name[32];
      std::snprintf(name, sizeof name, "%02d.png", i);
      cv::imwrite((dir / name).string(), img);
    }
    return (dir / "%02d.png").string();
  }();
  return pattern;
}

void BM_LensCalibration20x5MP(benchmark::State& state) {
  const std::string pattern = Views();
  rk::calibrate::LensOptions opt;
  opt.board = rk::calibrate::BoardKind::kChessboard;
  opt.cols = 9;
  opt.rows = 6;
  opt.square_mm = 30.0;
  opt.threads = 2;
  opt.detect_max_px = static_cast<int>(state.range(0));  // 0: full-size search; 1600: scaled copy + cornerSubPix
  for (auto _ : state) {
    const rk::calibrate::LensResult res = rk::calibrate::CalibrateLens({pattern}, opt);
    state.counters["views_used"] = res.ViewsUsed();
    state.counters["rms_px"] = res.rms_px;
    state.counters["detect_s"] = res.detect_s;
    state.counters["solve_s"] = res.solve_s;
    state.counters["map_err_px"] = rk::calibrate::MapDifferenceRmsPx(FiveMegapixelCamera(), res.camera, 16);
  }
}
BENCHMARK(BM_LensCalibration20x5MP)->Arg(0)->Arg(1600)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
