// rk-smooth: time-series filtering (SPEC.md §1): aukf (adaptive UKF fixed-lead prediction, seed 000),
// singer (Singer-model filter/smoother with derivatives), resample (one series to the times of another).
#include "io/cli.h"
#include "smooth_commands.h"

int main(int argc, char** argv) {
  using namespace rk::smooth_app;
  CLI::App app{"rk-smooth: adaptive UKF fixed-lead prediction, Singer tracking/smoothing, resampling"};
  Context ctx;
  ctx.argc = argc;
  ctx.argv = argv;
  rk::cli::AddCommonOptions(app, "rk-smooth", &ctx.common);
  app.require_subcommand(1);
  std::vector<Command> commands;
#ifdef RK_SMOOTH_HAVE_AUKF
  commands.push_back(AddAukfCommand(app));
#endif
#ifdef RK_SMOOTH_HAVE_SINGER
  commands.push_back(AddSingerCommand(app));
#endif
#ifdef RK_SMOOTH_HAVE_RESAMPLE
  commands.push_back(AddResampleCommand(app));
#endif
  return rk::cli::Run(app, "rk-smooth", argc, argv, [&]() -> int {
    for (const Command& c : commands) {
      if (c.app->parsed()) return c.run(ctx);
    }
    throw rk::UsageError("a subcommand is required");
  });
}
