// rk-calibrate lens: camera intrinsics and distortion from images of a chessboard, circle grid or ChArUco
// board (SPEC.md §1.1, §3); method in lib/calibrate/lens_calibration.h, user page docs/rk-calibrate.md.
#include <chrono>
#include <ctime>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/lens_calibration.h"
#include "calibrate_commands.h"
#include "io/error.h"
#include "io/file_util.h"
#include "video/stdin_video.h"

namespace rk::app {
namespace {

struct LensArgs {
  calibrate::LensOptions opt;
  std::vector<std::string> images;
  std::string out_path, plot_path;
};

std::string UtcNowIso() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

io::Json LensReport(const Context& ctx, const LensArgs& a, const calibrate::LensResult& res) {
  io::Json rep = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
  for (std::size_t i = 0; i < a.images.size(); ++i) cli::AddReportInput(&rep, "images_" + std::to_string(i), a.images[i]);
  rep["subcommand"] = "lens";
  rep["output"] = a.out_path;
  if (!a.plot_path.empty()) rep["plot"] = a.plot_path;
  rep["image"] = {{"width_px", res.width_px}, {"height_px", res.height_px}};
  io::Json views = io::Json::array();
  for (const auto& v : res.views) {
    io::Json j = {{"name", v.name}, {"found", v.found}, {"used", v.used}};
    if (v.found) j["rms_px"] = v.rms_px, j["points"] = v.image_px.size();
    if (!v.used) j["reason"] = v.reason;
    views.push_back(j);
  }
  rep["views"] = views;
  rep["time_s"] = {{"detection", res.detect_s}, {"solve", res.solve_s}};
  rep["options"] = a.opt.ToJson();
  return rep;
}

}  // namespace

Command AddLensCommand(CLI::App& parent) {
  auto a = std::make_shared<LensArgs>();
  CLI::App* c = parent.add_subcommand(
      "lens",
      "Camera intrinsics and OpenCV distortion (k1,k2,p1,p2,k3) from images of a planar board (Zhang's method, "
      "cv::calibrateCamera), with the 1 sigma of every estimated parameter. Views without a board are skipped, views "
      "far above the median RMS rejected. Writes camera.json (SPEC.md section 3) with a calibration object.");
  c->add_option("--images", a->images,
                "Image file, image-sequence pattern dir/%02d.png or video; repeat for more (read in the order given)")
      ->required();
  c->add_option("-o,--output", a->out_path, "Output camera model JSON ('-' = stdout)")->required();
  c->add_option("--plot", a->plot_path, "Also write a PNG of the residuals over the image and the board coverage");
  cli::AddOptions(c, &a->opt, calibrate::LensOptions::Table());
  // Required by SPEC.md §1.1.
  for (const char* flag : {"--board", "--cols", "--rows", "--square-mm", "--pixel-size-mm"}) c->get_option(flag)->required();

  return {c, [a](const Context& ctx) -> int {
            std::string why;
            if (!a->opt.Check(&why)) throw UsageError(why);
            video::RefuseStdinVideo(a->images, "--images");
            std::vector<cli::NamedPath> images;
            for (const std::string& p : a->images) images.push_back({"--images", p});
            cli::CheckStreams(ctx.common, images, {{"--plot", a->plot_path}, {"-o", a->out_path}});
            const bool progress = cli::ShowProgress(ctx.common);
            cli::ProgressMeter meter(ctx.tool, "images", 0, progress);  // the count is known only once read
            const calibrate::LensResult res =
                calibrate::CalibrateLens(a->images, a->opt, [&](std::int64_t n) { meter.Update(n); });
            meter.Finish();
            const io::RunSummary summary = res.Summary();
            cli::WarnAll(ctx.tool, ctx.common, summary);
            const io::Json camera = res.CameraJson(a->opt, UtcNowIso());
            const std::string png = a->plot_path.empty() ? std::string() : calibrate::LensPlotPng(res);
            io::WriteJson(a->out_path, camera);
            if (!a->plot_path.empty()) io::WriteFileAtomic(a->plot_path, png);
            if (!ctx.common.report_path.empty()) cli::WriteReport(ctx.common.report_path, LensReport(ctx, *a, res), summary);
            if (progress) {
              std::cerr << ctx.tool << ": " << res.views.size() << " images: " << res.ViewsUsed() << " used, "
                        << res.ViewsWithoutBoard() << " without a board, " << res.ViewsRejected() << " rejected; RMS "
                        << res.rms_px << " px\n";
            }
            return 0;
          }};
}

}  // namespace rk::app
