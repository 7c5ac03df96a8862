// The subcommands of rk-calibrate, one translation unit each (apps/calibrate_<name>_cmd.cpp); rk-calibrate.cpp
// lists them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddLensCommand(CLI::App& app);      // calibrate_lens_cmd.cpp
Command AddPointingCommand(CLI::App& app);  // calibrate_pointing_cmd.cpp

}  // namespace rk::app
