// Multi-mode tools (rk-<verb> with CLI11 subcommands, SPEC.md §1): one file per subcommand,
// apps/<verb>_<name>_cmd.cpp, compiled into rk-<verb> (apps/CMakeLists.txt). Each file defines
//   rk::app::Command Add<Name>Command(CLI::App& app)
// which adds its subcommand to `app` (options parsed into the library's Options struct) and returns
// the function that runs it after parsing, and registers it with
//   RK_REGISTER_SUBCOMMAND(order, Add<Name>Command);   // order: position in --help
// The tool's main is one line: return rk::app::RunTool("rk-<verb>", "description", argc, argv);
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <functional>
#include <string>
#include <utility>
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

// Subcommands of this executable, in registration order (static initialisation).
inline std::vector<std::pair<int, AddCommandFn>>& Registry() {
  static std::vector<std::pair<int, AddCommandFn>> registry;
  return registry;
}

struct SubcommandRegistrar {
  SubcommandRegistrar(int order, AddCommandFn add) { Registry().emplace_back(order, add); }
};

// The main of a multi-mode tool: common options (--version, --report, --quiet), every registered
// subcommand (exactly one required), errors mapped to SPEC.md §4 exit codes by cli::Run.
inline int RunTool(const char* tool, const char* description, int argc, char** argv) {
  CLI::App app{description, tool};
  Context ctx;
  ctx.tool = tool;
  ctx.argc = argc;
  ctx.argv = argv;
  cli::AddCommonOptions(app, tool, &ctx.common);
  app.require_subcommand(1);
  auto entries = Registry();
  std::stable_sort(entries.begin(), entries.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Command> commands;
  for (const auto& e : entries) commands.push_back(e.second(app));
  return cli::Run(app, tool, argc, argv, [&]() -> int {
    for (const Command& c : commands) {
      if (c.app->parsed()) return c.run(ctx);
    }
    throw UsageError("a subcommand is required");
  });
}

}  // namespace rk::app

#define RK_REGISTER_SUBCOMMAND(order, add_fn) \
  static const ::rk::app::SubcommandRegistrar rk_subcommand_registrar_##add_fn(order, add_fn)
