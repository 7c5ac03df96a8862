// The subcommands of rk-smooth, one translation unit each (apps/smooth_<name>_cmd.cpp); rk-smooth.cpp lists
// them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddAukfCommand(CLI::App& app);      // smooth_aukf_cmd.cpp
Command AddSingerCommand(CLI::App& app);    // smooth_singer_cmd.cpp
Command AddResampleCommand(CLI::App& app);  // smooth_resample_cmd.cpp

}  // namespace rk::app
