// rk-analyze budget: error propagation through a computation by Jacobian (automatic differentiation)
// and Monte Carlo, side by side (seed 004 §4). Thin CLI: the engine is lib/analysis/budget.h, the models
// analysis/budget_locate.h and attitude/cylinder_budget.h; user page docs/rk-analyze.md.
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include "analysis/budget.h"
#include "analysis/budget_locate.h"
#include "analyze_commands.h"
#include "attitude/cylinder_budget.h"
#include "camera/camera_model.h"
#include "camera/pointing_model.h"
#include "io/error.h"
#include "io/file_util.h"
#include "io/json_util.h"
#include "io/options.h"
#include "sim/theodolite_scene.h"

namespace rk::app {
namespace {

struct BudgetArgs {
  std::string budget_path, out_path;
  analysis::BudgetOptions given;        // --samples, --seed: only those on the command line are used
  attitude::CylinderSolveOptions solve;  // --method (cylinder models, Monte Carlo)
  bool table = false;
};

// A file's count: a value outside [0, 2^63) is made one that Check() refuses.
std::uint64_t FileCount(double v) {
  return v >= 0.0 && v < 9.2e18 ? static_cast<std::uint64_t>(v) : std::numeric_limits<std::uint64_t>::max();
}

// The number options of `table` given on the command line (app.count), copied from `given` over `*to`:
// flags override the file's values.
template <class O>
void CopyGivenOptions(const CLI::App& app, const io::OptionTable<O>& table, const O& given, O* to) {
  using Kind = typename io::OptionSpec<O>::Kind;
  O& from = const_cast<O&>(given);  // the accessors only read from it
  for (const auto& s : table.specs()) {
    if (app.count(s.flag) == 0) continue;
    if (s.kind == Kind::kReal) s.real(*to) = s.real(from);
    if (s.kind == Kind::kInteger) s.integer(*to) = s.integer(from);
    if (s.kind == Kind::kCount) s.count(*to) = s.count(from);
    if (s.kind == Kind::kFlag) s.flag_value(*to) = s.flag_value(from);
    if (s.kind == Kind::kChoice) s.set_choice(to, s.get_choice(from));
  }
}

// "camera": a path (relative to the budget file), an inline model, or absent (the model's default).
camera::CameraModel BudgetCamera(const io::Json& j, const std::string& budget_path, const camera::CameraModel& fallback) {
  if (!j.contains("camera") || j.at("camera").is_null()) return fallback;
  const io::Json& c = j.at("camera");
  if (c.is_string()) {
    std::filesystem::path p(c.get<std::string>());
    if (p.is_relative() && !io::IsStdStream(budget_path)) p = std::filesystem::path(budget_path).parent_path() / p;
    return camera::LoadCameraModel(p.string());
  }
  if (c.is_object()) return camera::CameraModelFromJson(c, budget_path + ": camera");
  throw DataError(budget_path, 0, 0, "\"camera\" must be a path or a camera model object");
}

// "pointing" (model locate): a pointing.json path (relative to the budget file), an inline pointing model, or
// absent (every term zero, no σ). *file names it for the sources made from its σ.
camera::PointingModel BudgetPointing(const io::Json& j, const std::string& budget_path, std::string* file) {
  *file = "pointing";
  if (!j.contains("pointing") || j.at("pointing").is_null()) return {};
  const io::Json& p = j.at("pointing");
  if (p.is_string()) {
    std::filesystem::path path(p.get<std::string>());
    if (path.is_relative() && !io::IsStdStream(budget_path)) {
      path = std::filesystem::path(budget_path).parent_path() / path;
    }
    *file = path.filename().string();
    return camera::LoadPointingModel(path.string());
  }
  if (p.is_object()) return camera::PointingModelFromJson(p, budget_path + ": pointing");
  throw DataError(budget_path, 0, 0, "\"pointing\" must be a path or a pointing model object");
}

}  // namespace

Command AddBudgetCommand(CLI::App& parent) {
  auto a = std::make_shared<BudgetArgs>();
  CLI::App* c = parent.add_subcommand(
      "budget",
      "Error budget: independent error sources (angles in arcmin/arcsec, pixels, sizes, ranges) from a JSON budget "
      "propagated through a computation (models: cylinder, cylinder-ranges, locate) by autodiff Jacobian and by "
      "Monte Carlo, side by side, with each source's share.");
  c->add_option("--budget", a->budget_path,
                "Budget JSON: model, camera, [pointing,] nominal, sources[, monte_carlo] ('-' = stdin)")
      ->required();
  c->add_option("-o,--output", a->out_path, "Result JSON ('-' = stdout)")->required();
  cli::AddOptions(c, &a->given, analysis::BudgetOptions::Table());
  cli::AddOptions(c, &a->solve, attitude::CylinderSolveOptions::Table());
  c->add_flag("--table", a->table, "Print a fixed-width table to stdout (to stderr when -o is '-')");

  return {c, [a, c](const Context& ctx) -> int {
            cli::CheckStreams(ctx.common, {{"--budget", a->budget_path}}, {{"-o", a->out_path, true}});
            const io::Json j = io::LoadJson(a->budget_path);
            const std::string& where = a->budget_path;
            if (!j.is_object()) throw DataError(where, 0, 0, "a budget must be a JSON object");
            const std::string model_name = io::RequireString(j, "model", where);
            if (!j.contains("nominal")) throw DataError(where, 0, 0, "missing \"nominal\"");
            if (!j.contains("sources")) throw DataError(where, 0, 0, "missing \"sources\"");
            const attitude::CylinderSolveOptions& solve = a->solve;
            std::unique_ptr<analysis::BudgetModel> model;
            std::vector<analysis::BudgetSource> calibrated;  // σ the camera and pointing files carry
            if (model_name != "locate" && j.contains("pointing")) {
              throw DataError(where, 0, 0, "\"pointing\" is a term of the locate model only");
            }
            if (model_name == "cylinder") {
              model = attitude::MakeCylinderBudgetModel(j.at("nominal"), BudgetCamera(j, where, sim::Seed004Camera()), solve, where);
            } else if (model_name == "cylinder-ranges") {
              model = attitude::MakeCylinderRangesBudgetModel(j.at("nominal"), BudgetCamera(j, where, sim::Seed004Camera()),
                                                              solve, where);
            } else if (model_name == "locate") {
              const camera::CameraModel cam = BudgetCamera(j, where, camera::DefaultCamera());
              std::string pointing_file;
              const camera::PointingModel pointing = BudgetPointing(j, where, &pointing_file);
              model = analysis::MakeLocateBudgetModel(j.at("nominal"), cam, pointing, where);
              calibrated = analysis::LocateCalibrationSources(*model, cam, pointing, pointing_file, where);
            } else {
              throw DataError(where, 0, 0, "unknown model '" + model_name + "' (cylinder, cylinder-ranges or locate)");
            }
            std::vector<analysis::BudgetSource> sources = analysis::ParseBudgetSources(j.at("sources"), *model, where);
            sources.insert(sources.end(), calibrated.begin(), calibrated.end());
            analysis::BudgetOptions opt;
            if (j.contains("monte_carlo") && j.at("monte_carlo").is_object()) {
              const io::Json& mc = j.at("monte_carlo");
              const std::string mc_where = where + ": monte_carlo";
              opt.samples = FileCount(io::NumberOr(mc, "samples", static_cast<double>(opt.samples), mc_where));
              opt.seed = FileCount(io::NumberOr(mc, "seed", static_cast<double>(opt.seed), mc_where));
            }
            CopyGivenOptions(*c, analysis::BudgetOptions::Table(), a->given, &opt);
            std::string why;
            if (!opt.Check(&why)) throw UsageError(why);
            const analysis::BudgetResult r = analysis::RunBudget(*model, sources, opt);
            io::Json out = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
            cli::AddReportInput(&out, "budget", a->budget_path);
            out["subcommand"] = "budget";
            out["solver"] = attitude::CylinderMethodName(solve.method);
            out.update(analysis::BudgetResultToJson(*model, sources, opt, r));
            const io::RunSummary summary = analysis::BudgetSummary(*model, r);
            cli::WarnAll(ctx.tool, ctx.common, summary);
            io::WriteJson(a->out_path, out);
            if (!ctx.common.report_path.empty() && ctx.common.report_path != a->out_path)
              cli::WriteReport(ctx.common.report_path, out, summary);
            if (a->table) {
              const std::string text = analysis::FormatBudgetTable(*model, sources, r);
              if (io::IsStdStream(a->out_path)) {
                std::cerr << text;
              } else {
                std::cout << text;
              }
            }
            return 0;
          }};
}

}  // namespace rk::app
