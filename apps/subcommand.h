// Multi-mode tools (rk-<verb> with CLI11 subcommands, SPEC.md §1): one file per subcommand,
// apps/<verb>_<name>_cmd.cpp, an ordinary translation unit linked into rk-<verb>
// (apps/CMakeLists.txt). Each file defines
//   rk::app::Command Add<Name>Command(CLI::App& app)
// (declared in apps/<verb>_commands.h) which adds its subcommand to `app` (options parsed into the
// library's Options struct) and returns the function that runs it after parsing. Messages and reports
// name the tool by ctx.tool. The tool's main, apps/rk-<verb>.cpp, lists its subcommands in --help order
// and runs them (as COLMAP's exe/colmap.cc does):
//   constexpr rk::app::Subcommand kSubcommands[] = {{"name", rk::app::Add<Name>Command}, ...};
//   return rk::app::RunTool("rk-<verb>", "description", kSubcommands, argc, argv);
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/cli.h"
#include "io/error.h"

namespace rk::app {

struct Context {
  std::string tool;           // "rk-<verb>", for messages and reports
  cli::CommonOptions common;  // --report, --quiet
  int argc = 0;
  char** argv = nullptr;
};

struct Command {
  CLI::App* app = nullptr;                 // the subcommand
  std::function<int(const Context&)> run;  // returns the exit code
};

using AddCommandFn = Command (*)(CLI::App& app);

// One row of a tool's subcommand table: the subcommand's name (as it adds itself) and its Add function.
struct Subcommand {
  const char* name;
  AddCommandFn add;
};

// The main of a multi-mode tool: common options (--version, --report, --quiet), the subcommands of
// the table in its order (exactly one required), errors mapped to SPEC.md §4 exit codes by cli::Run.
inline int RunTool(const char* tool, const char* description, std::span<const Subcommand> subcommands,
                   int argc, char** argv) {
  CLI::App app{description, tool};
  Context ctx;
  ctx.tool = tool;
  ctx.argc = argc;
  ctx.argv = argv;
  cli::AddCommonOptions(app, tool, &ctx.common);
  app.require_subcommand(1);
  std::vector<Command> commands;
  for (const Subcommand& s : subcommands) {
    commands.push_back(s.add(app));
    if (commands.back().app->get_name() != s.name) {
      throw std::logic_error(std::string(tool) + ": subcommand table names '" + s.name +
                             "' but its Add function added '" + commands.back().app->get_name() + "'");
    }
  }
  return cli::Run(app, tool, argc, argv, [&]() -> int {
    for (const Command& c : commands) {
      if (c.app->parsed()) return c.run(ctx);
    }
    throw UsageError("a subcommand is required");
  });
}

}  // namespace rk::app
