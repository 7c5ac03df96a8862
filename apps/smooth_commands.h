// Subcommands of rk-smooth, one file each (apps/smooth_<name>_cmd.cpp). Each Add*Command
// registers its CLI11 subcommand on `app` (options parsed into the library's Options struct)
// and returns the function that runs it after parsing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

#include "io/cli.h"

namespace rk::smooth_app {

struct Context {
  cli::CommonOptions common;  // --report, --quiet
  int argc = 0;
  char** argv = nullptr;
};

struct Command {
  CLI::App* app = nullptr;                 // the subcommand
  std::function<int(const Context&)> run;  // returns the exit code
};

Command AddAukfCommand(CLI::App& app);
Command AddSingerCommand(CLI::App& app);
Command AddResampleCommand(CLI::App& app);

}  // namespace rk::smooth_app
